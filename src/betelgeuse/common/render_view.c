/* The crop window and the sample pattern of docs/shading.md 1.1, shared by both renderers so that
 * they place every camera ray alike. */
#include <math.h>
#include <stdio.h>

#include "image.h"
#include "render_view.h"

/* One frame side: 0 takes the image's; the window [origin, origin + size) must lie inside it. */
static bool side_check(int frame, int origin, int size, const char *frame_name, const char *origin_name,
                       const char *image_name, const char *where, int *out, char *message, size_t msize)
{
    if (frame < 0 || frame > BG_MAX_IMAGE_SIDE) {
        snprintf(message, msize, "%s: settings.%s = %d is outside [0, %d] (0 = the image's %s)", where, frame_name,
                 frame, BG_MAX_IMAGE_SIDE, image_name);
        return false;
    }
    int f = frame ? frame : size;
    if (f < size) {
        snprintf(message, msize, "%s: settings.%s = %d is smaller than the image's %s %d", where, frame_name, f,
                 image_name, size);
        return false;
    }
    if (origin < 0 || origin > f - size) {
        snprintf(message, msize, "%s: settings.%s = %d puts the image (%s %d) outside the frame (%s %d): it must be "
                 "in [0, %d]", where, origin_name, origin, image_name, size, frame_name, f, f - size);
        return false;
    }
    *out = f;
    return true;
}

bg_status bgi_render_view_make(const bg_render_settings *settings, int width, int height, const char *where,
                               bgi_render_view *view, char *message, size_t size)
{
    const bg_render_settings *s = settings;
    if (s->samples < 0 || s->samples > BG_MAX_SAMPLES) {
        snprintf(message, size, "%s: settings.samples = %d is outside [0, %d] (0 and 1 = one sample at the pixel "
                 "centre)", where, s->samples, BG_MAX_SAMPLES);
        return BG_ERR_INVALID_ARGUMENT;
    }
    if (!side_check(s->frame_width, s->window_x, width, "frame_width", "window_x", "width", where, &view->frame_width,
                    message, size) ||
        !side_check(s->frame_height, s->window_y, height, "frame_height", "window_y", "height", where,
                    &view->frame_height, message, size))
        return BG_ERR_INVALID_ARGUMENT;
    view->x0 = s->window_x;
    view->y0 = s->window_y;
    view->width = width;
    view->height = height;
    view->samples = s->samples > 1 ? s->samples : 1;
    view->sample_first = 0;
    view->sample_count = view->samples;
    return BG_OK;
}

/* rows = the largest divisor of n not above sqrt(n), columns = n / rows: every cell has area 1 / n,
 * so equal weights are the box filter's integral by the midpoint rule of each cell. */
int bgi_sample_rows(int n)
{
    int rows = 1;
    for (int k = 1; k * k <= n; k++)
        if (n % k == 0)
            rows = k;
    return rows;
}

/* The cell centre (i + 1/2) / cells rounded to the nearest multiple of 2^-BGI_SAMPLE_BITS (no ties:
 * cells <= 256 has fewer factors of 2 than 2^(BGI_SAMPLE_BITS + 1)). */
static double cell_centre(int i, int cells)
{
    double scale = (double)(1 << BGI_SAMPLE_BITS);
    return floor((i + 0.5) / cells * scale + 0.5) / scale;
}

void bgi_sample_position(int samples, int s, double *px, double *py)
{
    int n = samples > 1 ? samples : 1;
    int rows = bgi_sample_rows(n), columns = n / rows;
    *px = cell_centre(s % columns, columns);
    *py = cell_centre(s / columns, rows);
}

bool bgi_render_progress(const bg_render_settings *settings, double fraction)
{
    if (!settings->progress)
        return true;
    return settings->progress(fraction, settings->progress_user);
}
