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

/* The primes of m (>= 1) in ascending order into p (at most 8 of them for m <= 256); their count. */
static int prime_factors(int m, int p[8])
{
    int count = 0;
    for (int q = 2; m > 1 && count < 8; q++)
        while (m % q == 0 && count < 8) {
            p[count++] = q;
            m /= q;
        }
    return count;
}

/* docs/shading.md 1.1, "The order the samples are taken in". Three steps, each one an integer map:
 *  1. k -> t, the ends inwards: t = 0, n - 1, 1, n - 2, ... (for odd n the middle index (n - 1) / 2
 *     first), so that indices t and n - 1 - t come as a pair;
 *  2. t's digits in a mixed radix whose bases are the primes of columns and of rows, interleaved
 *     (the axis with more cells left takes the next prime, columns first on a tie), least
 *     significant digit first: each digit is the next most significant digit of its axis's cell
 *     (a Morton order with each axis's digits reversed, van der Corput's radical inverse per axis),
 *     so the first b_1 indices spread over b_1 strips of the first axis, the first b_1 b_2 over a
 *     b_1 x b_2 grid of blocks, and so on;
 *  3. every base-2 digit of an axis at an odd place (the second, fourth ... most significant) is
 *     flipped: the first sample then sits about a third of the way in, not in the corner cell.
 * n - 1 - t has every digit d of t replaced by b - 1 - d, and flipping a bit commutes with that, so
 * the pair t, n - 1 - t is a cell and its mirror through the pixel centre: every even prefix (every
 * odd one for odd n, which starts at the centre cell) has its mean at the pixel centre exactly, and
 * the first 2^j of a grid of 2^a x 2^b cells hit each block of the first j digits once. */
int bgi_sample_order(int samples, int k)
{
    int n = samples > 1 ? samples : 1;
    if (k < 0 || k >= n)
        return 0;
    int j = k;
    if (n % 2 == 1) {
        if (k == 0)
            return bgi_sample_index_cell(n, (n - 1) / 2);
        j = k - 1;
    }
    return bgi_sample_index_cell(n, j % 2 == 0 ? j / 2 : n - 1 - j / 2);
}

int bgi_sample_index_cell(int samples, int t)
{
    int n = samples > 1 ? samples : 1;
    int rows = bgi_sample_rows(n), columns = n / rows;
    int px[8], py[8];
    int nx = prime_factors(columns, px), ny = prime_factors(rows, py);
    int ix = 0, iy = 0, x = 0, y = 0, left_x = columns, left_y = rows;
    while (ix < nx || iy < ny) {
        bool along_x = iy == ny || (ix < nx && left_x >= left_y);
        int b = along_x ? px[ix] : py[iy], place = along_x ? ix : iy;
        int d = t % b;
        t /= b;
        if (b == 2 && place % 2 == 1)
            d ^= 1;
        if (along_x) {
            left_x /= b;
            x += d * left_x;
            ix++;
        } else {
            left_y /= b;
            y += d * left_y;
            iy++;
        }
    }
    return y * columns + x;
}

bool bgi_render_progress(const bg_render_settings *settings, double fraction)
{
    if (!settings->progress)
        return true;
    return settings->progress(fraction, settings->progress_user);
}

void bgi_render_rows_done(const bg_render_settings *settings, int y0, int y1)
{
    if (settings->rows_done)
        settings->rows_done(y0, y1, settings->rows_user);
}
