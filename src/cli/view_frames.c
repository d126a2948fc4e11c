/* The viewer's frames (view_frames.h), on bg_render_gpu_to_texture until bg_accumulation lands. */
#include "view_frames.h"

#include <stdlib.h>
#include <string.h>

/* A texture of exactly width x height: kept when it has that size, else made anew. */
static bg_status sized_texture(macs_context *context, macs_texture **t, int width, int height)
{
    int w = 0, h = 0;
    if (*t)
        macs_texture_size(*t, &w, &h);
    if (*t && w == width && h == height)
        return BG_OK;
    macs_texture_destroy(*t);
    *t = NULL;
    macs_texture_desc d;
    memset(&d, 0, sizeof d);
    d.width = width;
    d.height = height;
    d.format = MACS_FORMAT_RGBA8;
    return macs_texture_create(context, &d, t) == MACS_OK ? BG_OK : BG_ERR_GL;
}

bg_status view_frames_moving(view_frames *f, bg_scene *scene, const bg_render_settings *settings, int width,
                             int height)
{
    bg_status st = sized_texture(f->context, &f->reduced, width, height);
    if (st != BG_OK)
        return st;
    bg_render_settings one = *settings;
    one.samples = 1;
    one.frame_width = width;
    one.frame_height = height;
    st = bg_render_gpu_to_texture(f->renderer, scene, &one, f->reduced);
    if (st == BG_OK)
        f->shown = f->reduced;
    return st;
}

bg_status view_frames_rest(view_frames *f, bg_scene *scene, const bg_render_settings *settings)
{
    bg_status st = sized_texture(f->context, &f->full, settings->frame_width, settings->frame_height);
    if (st != BG_OK)
        return st;
    /* The seam: a one-sample picture first, then the N samples at once. */
    bg_render_settings step = *settings;
    step.samples = f->samples == 0 ? 1 : settings->samples;
    st = bg_render_gpu_to_texture(f->renderer, scene, &step, f->full);
    if (st == BG_OK) {
        f->samples = step.samples;
        f->shown = f->full;
    }
    return st;
}

void view_frames_restart(view_frames *f)
{
    f->samples = 0;
}

bool view_frames_read(view_frames *f, bg_image *image)
{
    if (!f->shown)
        return false;
    int w = 0, h = 0;
    macs_texture_size(f->shown, &w, &h);
    size_t row = (size_t)w * 4;
    unsigned char *bottom_first = malloc(row * (size_t)h), *pixels = malloc(row * (size_t)h);
    bool ok = bottom_first && pixels && macs_texture_read(f->shown, bottom_first, 0) == MACS_OK;
    if (ok)
        for (int y = 0; y < h; y++)
            memcpy(pixels + row * (size_t)y, bottom_first + row * (size_t)(h - 1 - y), row);
    free(bottom_first);
    if (!ok) {
        free(pixels);
        return false;
    }
    *image = (bg_image){w, h, BG_PIXEL_RGBA8, 0, pixels};
    return true;
}

void view_frames_free(view_frames *f)
{
    macs_texture_destroy(f->full);
    macs_texture_destroy(f->reduced);
    f->full = f->reduced = f->shown = NULL;
    f->samples = 0;
}
