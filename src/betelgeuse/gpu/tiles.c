/* Tiles (docs/gpu_pipeline.md, "Tiles"): an image beyond GL's texture size limit, or whose render
 * targets would exceed settings.gpu_memory_budget, is rendered as windows of the frame, each written
 * straight into its rectangle of the caller's image (the same stride, its first pixel moved). A
 * window's pixels are the frame's bit for bit (docs/shading.md 1), so the tiled image is the one
 * piece's. GPU memory then follows the tile: every target is made at the tile's size. */
#include <math.h>

#include "driver.h"

#define DEFAULT_BUDGET (1024.0 * 1024.0 * 1024.0)

/* Bytes of render targets per pixel, by the largest plan (the multipass): the G-buffer's slots, the
 * accumulation, visibility, encoded and depth-stencil targets, and a ray set (origin, direction,
 * weight) per level plus one pending; a fused plan needs far less. Several samples add the frame's
 * sum (accumulate.c): two RGBA32F sums, a sample and the RGBA8 target of the exact resolve. */
static double bytes_per_pixel(const bg_render_settings *settings)
{
    double sum = settings->samples > 1 ? 3 * 16.0 + 4.0 : 0.0;
    return GPU_SLOT_COUNT * 16.0 + 16.0 + 4.0 + 4.0 + 4.0 + (settings->max_depth + 2) * 48.0 + sum;
}

/* How many pieces of at most max each cover n, and the size of each (the last may be smaller). */
static void split(int n, int max, int *count, int *size)
{
    *count = (n + max - 1) / max;
    *size = (n + *count - 1) / *count;
}

/* Maps each tile's fractions 0 .. 1 onto its share of the image's, remembering a cancel asked for
 * at a tile's last call (whose return value the tile's render ignores). */
typedef struct tile_progress {
    const bg_render_settings *settings;
    int done, count;
    bool cancel;
} tile_progress;

static bool tile_progress_fn(double fraction, void *user)
{
    tile_progress *p = user;
    if (p->cancel)
        return false;
    /* A tile's 0 repeats the previous tile's 1, never less; the last tile's 1 is exactly 1. */
    if (!bgi_render_progress(p->settings, (p->done + fraction) / p->count))
        p->cancel = true;
    return !p->cancel;
}

bg_status bgi_gpu_tiles_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view)
{
    double budget = settings->gpu_memory_budget > 0.0 ? settings->gpu_memory_budget : DEFAULT_BUDGET;
    double max_pixels = floor(budget / bytes_per_pixel(settings));
    int max_side = r->limits.max_texture_size;
    int nx, tw, ny, th;
    split(out->width, max_side, &nx, &tw);
    int rows = max_pixels / tw < 1.0 ? 1 : (max_pixels / tw > max_side ? max_side : (int)(max_pixels / tw));
    split(out->height, rows, &ny, &th);
    if (nx == 1 && ny == 1) {
        bg_status st = bgi_gpu_frame_render(r, scene, settings, out, view);
        r->stats.tiles = 1;
        return st;
    }
    tile_progress tp = {settings, 0, nx * ny, false};
    bg_render_settings inner = *settings;
    inner.progress = settings->progress ? tile_progress_fn : NULL;
    inner.progress_user = &tp;
    size_t texel = out->as_float ? 16 : 4;
    uint64_t fallback = 0;
    int compiled = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            if (tp.cancel)
                return bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress after %d of %d tiles; "
                                    "the finished tiles are written, the others untouched", tp.done,
                                    tp.count);
            /* Every tile has the same size, so targets and passes are made once: the last column and
             * row move back to end at the image's edge, overlapping their neighbours, whose pixels
             * they write again with the same values (a window's pixels are the frame's). */
            int x0 = i * tw < out->width - tw ? i * tw : out->width - tw;
            int y0 = j * th < out->height - th ? j * th : out->height - th;
            int w = tw, h = th;
            bg_image tile = *out->image;
            tile.width = w;
            tile.height = h;
            tile.stride = out->stride;
            tile.pixels = (unsigned char *)out->image->pixels + (size_t)y0 * out->stride + (size_t)x0 * texel;
            gpu_frame_out o = *out;
            o.image = &tile;
            o.width = w;
            o.height = h;
            bgi_render_view v = *view;
            v.x0 += x0;
            v.y0 += y0;
            v.width = w;
            v.height = h;
            bg_status st = bgi_gpu_frame_render(r, scene, &inner, &o, &v);
            if (st == BG_ERR_CANCELLED)
                return st; /* the tile's render said when */
            if (st != BG_OK)
                return st;
            fallback += r->stats.fallback_pixels;
            compiled += r->stats.programs_compiled;
            tp.done++;
        }
    r->stats.tiles = nx * ny;
    r->stats.fallback_pixels = fallback;
    r->stats.programs_compiled = compiled;
    return BG_OK;
}
