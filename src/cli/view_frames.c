/* The viewer's frames (view_frames.h): moving, bg_render_gpu_to_texture at one sample; at rest,
 * bg_render_gpu_accumulate a sample at a time and bg_accumulation_resolve_to_texture. */
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
    int w = settings->frame_width, h = settings->frame_height;
    bg_status st = sized_texture(f->context, &f->full, w, h);
    if (st != BG_OK)
        return st;
    if (!f->sum || f->sum_width != w || f->sum_height != h) {
        bg_accumulation_destroy(f->sum);
        f->sum = NULL;
        f->samples = 0;
        st = bg_accumulation_create(f->renderer, w, h, &f->sum);
        if (st != BG_OK)
            return st;
        f->sum_width = w;
        f->sum_height = h;
    }
    /* One sample a step: the first shows at once, and each later one refines what is shown. */
    st = bg_render_gpu_accumulate(f->renderer, scene, settings, f->sum, f->samples, 1);
    if (st == BG_OK)
        st = bg_accumulation_resolve_to_texture(f->renderer, f->sum, settings, f->full);
    if (st == BG_OK) {
        f->samples = bg_accumulation_samples(f->sum);
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
    bg_accumulation_destroy(f->sum);
    f->sum = NULL;
    macs_texture_destroy(f->full);
    macs_texture_destroy(f->reduced);
    f->full = f->reduced = f->shown = NULL;
    f->samples = 0;
}
