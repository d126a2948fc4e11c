/* Tiles read back through a read-back buffer (docs/gpu_pipeline.md, "Tiles"): settings.rows_done
 * names bands that cover the image once, in order, each told only when its rows hold the one piece's
 * bytes and (where the tile's read is queued) before any row below is written; progress says 1 only
 * after the last band; the GL work of a tiled frame is one read of 4 bytes a pixel and one sync per
 * tile; a driver whose glMapBuffer gives NULL fails the render with a message, not a crash. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "util_gl.h"
#include "util_gpu.h"

/* With GL's texture size capped at 256 and a budget of 151 x 30 pixels at 500 bytes (the renderer's
 * estimate is about 476 bytes a pixel at one sample, 528 with more: tiles of 28 to 31 rows at most),
 * 301 x 41 is 2 x 2 tiles of 151 x 21, the last column and row moved back by one pixel to end at the
 * edge (overlapping their neighbours). */
enum { W = 301, H = 41, CAP = 256, TW = 151, TH = 21, SENTINEL = 0xA5 };
#define BUDGET (151.0 * 30.0 * 500.0)

typedef struct rows_log {
    const bg_image *image;
    unsigned char *snapshot; /* each band's rows as they were when told */
    int bands[8][2];
    int count;
    int events;        /* calls of either callback */
    int last_band_event, last_progress_event;
    double last_fraction;
    bool below_written; /* a row below a told band was written when it was told */
} rows_log;

static size_t texel_of(const bg_image *img)
{
    return img->format == BG_PIXEL_RGBA32F ? 16 : 4;
}

static void on_rows(int y0, int y1, void *user)
{
    rows_log *log = user;
    size_t row = (size_t)log->image->width * texel_of(log->image);
    if (log->count < 8) {
        log->bands[log->count][0] = y0;
        log->bands[log->count][1] = y1;
    }
    log->count++;
    log->last_band_event = log->events++;
    if (y0 < 0 || y1 > log->image->height || y0 >= y1)
        return; /* the checks after the render say so */
    const unsigned char *px = log->image->pixels;
    memcpy(log->snapshot + (size_t)y0 * row, px + (size_t)y0 * row, (size_t)(y1 - y0) * row);
    for (size_t i = (size_t)y1 * row; i < (size_t)log->image->height * row; i++)
        if (px[i] != SENTINEL) {
            log->below_written = true;
            break;
        }
}

static bool on_progress(double fraction, void *user)
{
    rows_log *log = user;
    log->last_progress_event = log->events++;
    log->last_fraction = fraction;
    return true;
}

static void image_alloc(bg_image *img, int w, int h, bg_pixel_format format)
{
    size_t px = format == BG_PIXEL_RGBA32F ? 16 : 4;
    *img = (bg_image){w, h, format, 0, malloc((size_t)w * h * px)};
    assert_non_null(img->pixels);
    memset(img->pixels, SENTINEL, (size_t)w * h * px);
}

/* Renders s tiled on small (capped) and in one piece on whole, with the callbacks logged; checks the
 * bands and that the image and every band's snapshot are the one piece's. queued: the frames end in
 * a read the loop queues, so no row below a band is written when it is told. */
static void expect_bands(bg_renderer *small, macs_context *small_ctx, bg_renderer *whole, bg_scene *s,
                         bg_render_settings set, bg_pixel_format format, bool queued, const char *label)
{
    bg_image one, tiled;
    image_alloc(&one, W, H, format);
    image_alloc(&tiled, W, H, format);
    util_render_gpu(whole, util_fx.ctx, s, &set, &one, label);
    bg_render_stats st;
    bg_renderer_get_stats(whole, &st);
    assert_int_equal(st.tiles, 1);
    rows_log log;
    memset(&log, 0, sizeof log);
    set.gpu_memory_budget = BUDGET;
    size_t bytes = (size_t)W * H * texel_of(&tiled);
    log.image = &tiled;
    log.snapshot = malloc(bytes);
    assert_non_null(log.snapshot);
    memset(log.snapshot, 0, bytes);
    set.rows_done = on_rows;
    set.rows_user = &log;
    set.progress = on_progress;
    set.progress_user = &log;
    util_render_gpu(small, small_ctx, s, &set, &tiled, label);
    bg_renderer_get_stats(small, &st);
    assert_int_equal(st.tiles, 4);
    /* Two bands of tile rows, [0, 21) and [21, 41): in order, once each, the image covered. */
    if (log.count != 2 || log.bands[0][0] != 0 || log.bands[0][1] != TH || log.bands[1][0] != TH ||
        log.bands[1][1] != H)
        fail_msg("%s: bands told: %d, the first [%d, %d), the second [%d, %d)", label, log.count, log.bands[0][0],
                 log.bands[0][1], log.bands[1][0], log.bands[1][1]);
    /* Fused plans in two contexts: programs of the same source strings, so bit for bit on any
     * conforming driver (test_bg_gpu_view, beyond_the_texture_size). */
    if (memcmp(tiled.pixels, one.pixels, bytes) != 0)
        fail_msg("%s: the tiled image is not the one piece", label);
    if (memcmp(log.snapshot, one.pixels, bytes) != 0)
        fail_msg("%s: a band's rows, when told, were not yet the one piece's", label);
    if (queued && log.below_written)
        fail_msg("%s: rows below a band were written before it was told", label);
    assert_true(log.last_fraction == 1.0);
    assert_true(log.last_progress_event > log.last_band_event);
    free(log.snapshot);
    free(one.pixels);
    free(tiled.pixels);
}

static void bands_are_told_once_in_order_when_final(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_texture_size = CAP;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    bg_renderer *small = util_renderer(ctx);
    bg_renderer *whole = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    bg_render_settings set = bg_render_settings_init();
    expect_bands(small, ctx, whole, s, set, BG_PIXEL_RGBA8, true, "1 sample, RGBA8");
    expect_bands(small, ctx, whole, s, set, BG_PIXEL_RGBA32F, true, "1 sample, RGBA32F");
    set.samples = 2; /* the exact bytes of the GPU's resolve, queued */
    expect_bands(small, ctx, whole, s, set, BG_PIXEL_RGBA8, true, "2 samples, RGBA8");
    /* A float mean of samples is divided on the host: its tile writes the image itself. */
    expect_bands(small, ctx, whole, s, set, BG_PIXEL_RGBA32F, false, "2 samples, RGBA32F");
    bg_scene_destroy(s);
    /* The tree plan's CPU pixels: those tiles are read at once and written by their frames. */
    s = util_tube_scene();
    set.samples = 1;
    expect_bands(small, ctx, whole, s, set, BG_PIXEL_RGBA8, false, "tube, CPU pixels");
    bg_scene_destroy(s);
    bg_renderer_destroy(small);
    bg_renderer_destroy(whole);
    macs_context_destroy(ctx);
}

/* One piece, on the GPU and on the CPU: one band, the whole image, once it is complete. */
static void one_piece_is_one_band(void **state)
{
    (void)state;
    enum { w = 40, h = 30 };
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_renderer *r = util_renderer(util_fx.ctx);
    for (int cpu = 0; cpu < 2; cpu++) {
        bg_image img;
        image_alloc(&img, w, h, BG_PIXEL_RGBA8);
        rows_log log;
        memset(&log, 0, sizeof log);
        log.image = &img;
        log.snapshot = malloc((size_t)w * h * 4);
        assert_non_null(log.snapshot);
        bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, 1);
        set.rows_done = on_rows;
        set.rows_user = &log;
        set.progress = on_progress;
        set.progress_user = &log;
        if (cpu)
            assert_int_equal(bg_render_cpu(s, &set, &img), BG_OK);
        else
            util_render_gpu(r, util_fx.ctx, s, &set, &img, "one piece");
        assert_int_equal(log.count, 1);
        assert_int_equal(log.bands[0][0], 0);
        assert_int_equal(log.bands[0][1], h);
        assert_memory_equal(log.snapshot, img.pixels, (size_t)w * h * 4);
        assert_true(log.last_progress_event > log.last_band_event && log.last_fraction == 1.0);
        free(log.snapshot);
        free(img.pixels);
    }
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* The GL work of a tiled cached frame: each tile's read is 4 bytes a pixel of its window, queued
 * (no sync) and taken by one map (one sync); nothing else waits, as in one piece (the budgets of
 * docs/gpu_pipeline.md, "GL work per frame", per tile). */
static void tiled_work_is_per_tile(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_texture_size = CAP;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    for (int samples = 1; samples <= 4; samples += 3) {
        bg_image img;
        image_alloc(&img, W, H, BG_PIXEL_RGBA8);
        bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, samples);
        set.gpu_memory_budget = BUDGET;
        util_render_gpu(r, ctx, s, &set, &img, "first frame");
        util_render_gpu(r, ctx, s, &set, &img, "cached frame");
        bg_render_stats st;
        bg_renderer_get_stats(r, &st);
        assert_int_equal(st.tiles, 4);
        assert_int_equal(st.gl_work.readback_bytes, (uint64_t)4 * TW * TH * 4);
        assert_int_equal(st.gl_work.syncs, 4);
        assert_int_equal(st.gl_work.upload_bytes, 0);
        assert_int_equal(st.gl_work.programs_compiled, 0);
        free(img.pixels);
    }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* A driver whose glMapBuffer returns NULL: the tiled render fails naming it; one piece, which reads
 * without a buffer, still renders. */
static void a_null_map_fails_the_render(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_texture_size = CAP;
    macs_context *ctx = util_context_null_map(util_fx.headless, &caps);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_image img;
    image_alloc(&img, W, H, BG_PIXEL_RGBA8);
    bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, 1);
    set.gpu_memory_budget = BUDGET;
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_GL);
    const char *m = bg_renderer_error_message(r);
    if (!strstr(m, "glMapBuffer") || !strstr(m, "returned NULL"))
        fail_msg("the message does not say what failed: %s", m);
    bg_renderer_clear_error(r);
    bg_image small;
    image_alloc(&small, 64, 48, BG_PIXEL_RGBA8);
    util_render_gpu(r, ctx, s, &set, &small, "one piece on the same driver");
    free(small.pixels);
    free(img.pixels);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bands_are_told_once_in_order_when_final),
        cmocka_unit_test(one_piece_is_one_band),
        cmocka_unit_test(tiled_work_is_per_tile),
        cmocka_unit_test(a_null_map_fails_the_render),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
