/* Tiles (docs/gpu_pipeline.md, "Tiles"): an image beyond GL's texture size limit, or whose render
 * targets would exceed settings.gpu_memory_budget, is rendered as windows of the frame, each written
 * into its rectangle of the caller's image (the same stride, its first pixel moved). A window's
 * pixels are the frame's bit for bit (docs/shading.md 1), so the tiled image is the one piece's.
 * GPU memory then follows the tile: every target is made at the tile's size.
 *
 * The read-back is pipelined: a tile's frame parks its finished texture (r->defer_reads,
 * read_back.c) instead of reading it; the loop submits the tile's work, takes the previous tile's
 * texels from the read-back buffer into the image while the GPU renders this one, and only then
 * queues this tile's read into the buffer (macs_texture_read_begin). So the GPU always has a tile to
 * render while the host copies one, and one buffer suffices: the buffer is emptied before the next
 * read is queued. Queuing the read after the copy rather than before it keeps the overlap also on a
 * driver whose glGetTexImage into a buffer waits for the texture (the read would otherwise wait for
 * this tile before the host could take the last). A frame that writes the image itself after its
 * read (the CPU's pixels of walks that ran out of steps) is read at once, as in one piece.
 * The invariant: when the loop stops, for whatever reason, every tile whose frame finished is in the
 * image (unless taking its read back failed, which the error says) and no other pixel was written;
 * the read-back buffer is destroyed on every path. */
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
 * at a tile's last call (whose return value the tile's render ignores). The last tile's 1 is held
 * back: the image is complete only once that tile's read is in it, and the loop says 1 then. */
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
    if (p->done == p->count - 1 && fraction >= 1.0)
        return true;
    /* A tile's 0 repeats the previous tile's 1, never less. */
    if (!bgi_render_progress(p->settings, (p->done + fraction) / p->count))
        p->cancel = true;
    return !p->cancel;
}

/* The tiling of out: nx x ny tiles of tw x th each. */
typedef struct tiling {
    int nx, ny, tw, th;
    int width, height;
    size_t texel, stride;
    bg_image *image;
} tiling;

/* A tile rendered whose pixels are not all in the image yet, or whose band is not told yet. */
typedef struct tile_on_way {
    bool present;
    int i, j;         /* its place in the grid */
    bool queued;      /* its texels are in the read-back buffer; else its frame wrote the image */
    bool opaque;
} tile_on_way;

/* Tile (i, j)'s window: every tile has the same size, so targets and passes are made once; the last
 * column and row move back to end at the image's edge, overlapping their neighbours, whose pixels
 * they write again with the same values (a window's pixels are the frame's). */
static void window_of(const tiling *t, int i, int j, int *x0, int *y0)
{
    *x0 = i * t->tw < t->width - t->tw ? i * t->tw : t->width - t->tw;
    *y0 = j * t->th < t->height - t->th ? j * t->th : t->height - t->th;
}

/* The end of band j (its rows are [j * th, band_end)). */
static int band_end(const tiling *t, int j)
{
    return (j + 1) * t->th < t->height ? (j + 1) * t->th : t->height;
}

/* Puts a tile's pixels in the image (its own part of its window only: the columns and rows no
 * earlier tile holds, so no told band is written again) and tells its band when it is the band's
 * last tile. */
static bg_status settle(bg_renderer *r, const bg_render_settings *settings, const tiling *t, macs_readback *rb,
                        tile_on_way *w)
{
    if (!w->present)
        return BG_OK;
    w->present = false;
    if (w->queued) {
        const void *texels = NULL;
        size_t src_stride = 0;
        macs_status ms = macs_readback_map(rb, &texels, &src_stride);
        if (ms)
            return bgi_gpu_fail_macs(r, ms, "taking a tile's read back");
        int x0, y0;
        window_of(t, w->i, w->j, &x0, &y0);
        int nx0 = w->i * t->tw, ny0 = w->j * t->th;
        int nx1 = nx0 + t->tw < t->width ? nx0 + t->tw : t->width;
        unsigned char *dst = (unsigned char *)t->image->pixels + (size_t)ny0 * t->stride + (size_t)nx0 * t->texel;
        bgi_gpu_copy_rows(texels, src_stride, t->th, nx0 - x0, nx1 - nx0, ny0 - y0, band_end(t, w->j) - ny0,
                          t->texel, w->opaque, dst, t->stride);
        ms = macs_readback_unmap(rb);
        if (ms)
            return bgi_gpu_fail_macs(r, ms, "taking a tile's read back");
    }
    if (w->i == t->nx - 1)
        bgi_render_rows_done(settings, w->j * t->th, band_end(t, w->j));
    return BG_OK;
}

/* Queues the read of the texture tile's frame parked, or, where GL cannot make the read-back
 * buffer's store (GPU memory), reads it into the tile's window at once, as one piece is read (its
 * texture is intact until the next tile renders). */
static bg_status queue(bg_renderer *r, macs_readback **rb, tile_on_way *w, bg_image *tile)
{
    macs_texture *texture = r->parked;
    bool opaque = r->parked_opaque;
    r->parked = NULL;
    if (!texture)
        return BG_OK; /* the frame wrote the image itself */
    /* A refusal is forgotten only if nothing was wrong before it. */
    bool clean = macs_context_error(r->ctx) == MACS_OK;
    macs_status ms = *rb ? MACS_OK : macs_readback_create(r->ctx, rb);
    if (!ms)
        ms = macs_texture_read_begin(texture, *rb);
    if (!ms) {
        w->queued = true;
        w->opaque = opaque;
        return BG_OK;
    }
    if (!clean || ms != MACS_ERR_GPU_OUT_OF_MEMORY)
        return bgi_gpu_fail_macs(r, ms, "queuing a tile's read back");
    bgi_gpu_log(r, BG_LOG_INFO, "%s; the tile is read back at once", macs_context_error_message(r->ctx));
    macs_context_clear_error(r->ctx);
    return bgi_gpu_read_back(r, texture, tile, tile->stride, opaque);
}

/* Renders tile (i, j) of the loop: its frame, then the previous tile's pixels into the image while
 * the GPU works on this one, then this one's read queued. */
static bg_status render_tile(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                             const bg_render_settings *inner, const gpu_frame_out *out, const bgi_render_view *view,
                             const tiling *t, int i, int j, macs_readback **rb, tile_on_way *previous)
{
    int x0, y0;
    window_of(t, i, j, &x0, &y0);
    bg_image tile = *out->image;
    tile.width = t->tw;
    tile.height = t->th;
    tile.stride = t->stride;
    tile.pixels = (unsigned char *)out->image->pixels + (size_t)y0 * t->stride + (size_t)x0 * t->texel;
    gpu_frame_out o = *out;
    o.image = &tile;
    o.width = t->tw;
    o.height = t->th;
    bgi_render_view v = *view;
    v.x0 += x0;
    v.y0 += y0;
    v.width = t->tw;
    v.height = t->th;
    r->defer_reads = true;
    r->parked = NULL;
    bg_status st = bgi_gpu_frame_render(r, scene, inner, &o, &v);
    r->defer_reads = false;
    if (st != BG_OK) {
        r->parked = NULL; /* an unfinished tile never reaches the image */
        return st;
    }
    macs_context_flush(r->ctx);
    st = settle(r, settings, t, *rb, previous);
    tile_on_way now = {true, i, j, false, true};
    if (st == BG_OK)
        st = queue(r, rb, &now, &tile);
    r->parked = NULL;
    if (st == BG_OK)
        *previous = now;
    return st;
}

bg_status bgi_gpu_tiles_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view)
{
    double budget = settings->gpu_memory_budget > 0.0 ? settings->gpu_memory_budget : DEFAULT_BUDGET;
    double max_pixels = floor(budget / bytes_per_pixel(settings));
    int max_side = r->limits.max_texture_size;
    tiling t = {0, 0, 0, 0, out->width, out->height, out->as_float ? 16 : 4, out->stride, out->image};
    split(out->width, max_side, &t.nx, &t.tw);
    int rows = max_pixels / t.tw < 1.0 ? 1 : (max_pixels / t.tw > max_side ? max_side : (int)(max_pixels / t.tw));
    split(out->height, rows, &t.ny, &t.th);
    /* One piece is one tile of progress: its 1 also waits for the rows. */
    tile_progress tp = {settings, 0, t.nx * t.ny, false};
    bg_render_settings inner = *settings;
    inner.progress = settings->progress ? tile_progress_fn : NULL;
    inner.progress_user = &tp;
    inner.rows_done = NULL;
    if (t.nx == 1 && t.ny == 1) {
        bg_status st = bgi_gpu_frame_render(r, scene, &inner, out, view);
        r->stats.tiles = 1;
        if (st != BG_OK)
            return st;
        bgi_render_rows_done(settings, 0, out->height);
        bgi_render_progress(settings, 1.0);
        return BG_OK;
    }
    uint64_t fallback = 0;
    int compiled = 0;
    macs_readback *rb = NULL;
    tile_on_way previous = {false, 0, 0, false, true};
    bg_status st = BG_OK;
    for (int j = 0; j < t.ny && st == BG_OK; j++)
        for (int i = 0; i < t.nx && st == BG_OK; i++) {
            if (tp.cancel) {
                st = bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress after %d of %d tiles; "
                                  "the finished tiles are written, the others untouched", tp.done, tp.count);
                break;
            }
            /* A cancel inside the tile's render says when, itself. */
            st = render_tile(r, scene, settings, &inner, out, view, &t, i, j, &rb, &previous);
            if (st == BG_OK) {
                fallback += r->stats.fallback_pixels;
                compiled += r->stats.programs_compiled;
                tp.done++;
            }
        }
    /* The last finished tile reaches the image whatever stopped the loop; the first error stays the
     * renderer's. */
    bg_status last = settle(r, settings, &t, rb, &previous);
    macs_readback_destroy(rb);
    if (st == BG_OK)
        st = last;
    if (st != BG_OK)
        return st;
    bgi_render_progress(settings, 1.0);
    r->stats.tiles = t.nx * t.ny;
    r->stats.fallback_pixels = fallback;
    r->stats.programs_compiled = compiled;
    return BG_OK;
}
