/* The GPU renderer's samples, crop windows, progress and cancelling, on every plan (docs/shading.md
 * 1.1): one sample is the default render bit for bit; at 4 samples every shared scene stays within
 * its threshold row against the CPU reference at 4 samples; 16 samples of the slanted edge come
 * within the CPU's bound of the exact coverage; a window is the same rectangle of the full frame
 * bit for bit (the camera ray of a frame pixel is computed from the same floats either way; the
 * multipass may batch a window otherwise, and is then held to the error model: expect_rectangle),
 * including the tree plan's pixels that go to the CPU reference; into a texture, samples and windows
 * give bg_render_gpu's image; progress is told 0, each finished sample pass, 1; a cancelled render
 * returns BG_ERR_CANCELLED and leaves the image untouched; bad settings name their field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "util_coverage.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_thresholds.h"

/* The size of test_bg_gpu_scenes, where the thresholds were measured. */
enum { W = 160, H = 120 };

static const bg_gpu_plan plans[3] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
static const char *const plan_names[3] = {"fused", "fused tree", "multipass"};

static void *image_alloc(bg_image *img, int w, int h, bg_pixel_format format)
{
    size_t px = format == BG_PIXEL_RGBA32F ? 16 : 4;
    img->width = w;
    img->height = h;
    img->format = format;
    img->stride = 0;
    img->pixels = malloc((size_t)w * h * px);
    assert_non_null(img->pixels);
    memset(img->pixels, 0xA5, (size_t)w * h * px); /* a sentinel no render writes */
    return img->pixels;
}

static bg_render_stats render(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_image *img,
                              const char *label)
{
    util_render_gpu(r, util_fx.ctx, s, set, img, label);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    return stats;
}

/* ---- samples ---- */

static void one_sample_is_the_default(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_GLASS);
    for (int p = 0; p < 3; p++) {
        bg_image a, b;
        image_alloc(&a, W, H, BG_PIXEL_RGBA32F);
        image_alloc(&b, W, H, BG_PIXEL_RGBA32F);
        bg_render_settings set = bg_render_settings_init();
        set.gpu_plan = plans[p];
        render(r, s, &set, &a, plan_names[p]);
        set.samples = 1;
        set.frame_width = W; /* the frame spelled out is the frame by default */
        set.frame_height = H;
        render(r, s, &set, &b, plan_names[p]);
        /* The same settings spelled out: the same programs on the same inputs (GL 2.1 appendix A, rule 4). */
        assert_memory_equal(a.pixels, b.pixels, (size_t)W * H * 16);
        set.samples = 2;
        assert_int_equal(render(r, s, &set, &b, plan_names[p]).plan, plans[p]);
        assert_true(memcmp(a.pixels, b.pixels, (size_t)W * H * 16) != 0);
        free(a.pixels);
        free(b.pixels);
    }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* textured_aniso's row for 4 samples. A 2x2 grid at 160x120 puts rays at the pixel centres of
 * 320x240, where more of them meet the checkered floor's texel edges, at which float and double
 * (and GL's filter weights) disagree most: one sample at 320x240 measures PSNR 69.39 dB and max 22,
 * against the shared row's 77.5 dB measured at 160x120 and 96x96. 4 samples at 160x120 measured
 * interior max 1, mean 0.003, PSNR 73.53 dB, none over 8 (every plan); the row keeps the shared
 * table's rule: PSNR 3 dB below, mean twice the measured value. */
static const gpu_threshold textured_aniso_4_samples = {SCENE_TEXTURED_ANISO, 2.0, 0.006, 70.5, 0.001};

static void check_scene(scene_id id)
{
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(id);
    bg_render_settings set = bg_render_settings_init();
    set.samples = 4;
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    for (int p = 0; p < 3; p++) {
        /* The multipass is slow on the tree scenes; the fused plan suffices there for AUTO's choice. */
        if (plans[p] == BG_PLAN_MULTIPASS && id != SCENE_PAPER_EARTH_SHADOW && id != SCENE_GLASS)
            continue;
        bg_image img;
        image_alloc(&img, W, H, BG_PIXEL_RGBA8);
        set.gpu_plan = plans[p];
        char label[96];
        snprintf(label, sizeof label, "%s, 4 samples, %s", scenes_name(id), plan_names[p]);
        render(r, s, &set, &img, label);
        if (id == SCENE_TEXTURED_ANISO)
            util_expect_near_row(cpu, &img, &textured_aniso_4_samples, label);
        else
            util_expect_near(cpu, &img, id, label);
        free(img.pixels);
    }
    free(cpu);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}
UTIL_EACH_SCENE(UTIL_SCENE_TEST)

static void sixteen_samples_converge_to_the_coverage(void **state)
{
    (void)state;
    enum { EW = 64, EH = 48 };
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_edge_scene();
    for (int p = 0; p < 3; p++) {
        double max[2], mean[2];
        for (int k = 0; k < 2; k++) {
            bg_image img;
            float *px = image_alloc(&img, EW, EH, BG_PIXEL_RGBA32F);
            bg_render_settings set = util_edge_settings(k ? 16 : 1);
            set.gpu_plan = plans[p];
            render(r, s, &set, &img, plan_names[p]);
            util_edge_error(px, EW, EH, &max[k], &mean[k]);
            print_message("%s: %2d samples: max error %.4f, mean %.5f\n", plan_names[p], k ? 16 : 1, max[k], mean[k]);
            free(px);
        }
        /* The CPU's bounds (test_bg_cpu_view): float moves a sample by far less than its spacing. */
        assert_true(max[0] > 0.07 && mean[0] > 0.0006);
        assert_true(max[1] <= 0.07);
        assert_true(mean[1] <= 0.0006);
    }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* ---- windows ---- */

/* Why a window or a tile of a frame is the frame's rectangle bit for bit on any conforming driver, in
 * the fused plans: every pixel runs the same program (its source does not depend on the view) on
 * the same uniforms, and what differs, gl_FragCoord and the view's shift (samples.c), adds up to the
 * same frame coordinate exactly (every term a multiple of 2^-BGI_SAMPLE_BITS below 2^14), which the
 * pixel hash and the camera ray then take alike (GL 2.1 appendix A, rule 4). The multipass batches
 * objects by the area their scissor covers in the view (multipass/batch.c), so a window or a tile
 * may run other programs over the same formulas: bit for bit where the batches agree (every case
 * here on Mesa), else within the scene's row of the error model (util_expect_gpu_twins). row NULL:
 * bit for bit whatever the plan. */
static void expect_rectangle(bg_gpu_plan plan, bool as_float, const unsigned char *got, const unsigned char *want,
                             int w, int h, const gpu_threshold *row, const char *label)
{
    size_t bytes = (size_t)w * (size_t)h * (as_float ? 16 : 4);
    if (memcmp(got, want, bytes) == 0)
        return;
    if (plan != BG_PLAN_MULTIPASS || !row)
        fail_msg("%s: differs from the full frame's rectangle", label);
    if (as_float) {
        util_expect_gpu_twins((const float *)want, (const float *)got, w, h, row, label);
    } else {
        bg_image img = {w, h, BG_PIXEL_RGBA8, 0, (void *)got};
        util_expect_near_row(want, &img, row, label);
    }
}

static void check_window(bg_renderer *r, bg_scene *s, bg_gpu_plan plan, int samples, bg_pixel_format format, int fw,
                         int fh, int x0, int y0, int w, int h, const gpu_threshold *row, const char *label)
{
    size_t px = format == BG_PIXEL_RGBA32F ? 16 : 4;
    bg_image full, win;
    unsigned char *f = image_alloc(&full, fw, fh, format);
    unsigned char *p = image_alloc(&win, w, h, format);
    bg_render_settings set = bg_render_settings_init();
    set.samples = samples;
    set.gpu_plan = plan;
    render(r, s, &set, &full, label);
    set.frame_width = fw;
    set.frame_height = fh;
    set.window_x = x0;
    set.window_y = y0;
    render(r, s, &set, &win, label);
    unsigned char *rect = malloc((size_t)w * h * px);
    assert_non_null(rect);
    for (int y = 0; y < h; y++)
        memcpy(rect + (size_t)y * w * px, f + ((size_t)(y0 + y) * fw + x0) * px, (size_t)w * px);
    char what[160];
    snprintf(what, sizeof what, "%s: window %dx%d at (%d, %d) of %dx%d, %d samples", label, w, h, x0, y0, fw, fh,
             samples);
    expect_rectangle(plan, format == BG_PIXEL_RGBA32F, p, rect, w, h, row, what);
    free(rect);
    free(f);
    free(p);
}

static void windows_are_rectangles_of_the_frame(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    const scene_id ids[2] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS};
    for (int k = 0; k < 2; k++) {
        bg_scene *s = util_scene(ids[k]);
        for (int p = 0; p < 3; p++) {
            const gpu_threshold *row = gpu_threshold_of(ids[k]);
            check_window(r, s, plans[p], 1, BG_PIXEL_RGBA8, W, H, 0, 0, 37, 21, row, plan_names[p]);
            check_window(r, s, plans[p], 1, BG_PIXEL_RGBA32F, W, H, 100, 70, 60, 50, row, plan_names[p]);
            check_window(r, s, plans[p], 4, BG_PIXEL_RGBA32F, W, H, 41, 33, 64, 40, row, plan_names[p]);
            check_window(r, s, plans[p], 3, BG_PIXEL_RGBA8, W, H, 57, 0, 1, H, row, plan_names[p]);
        }
        bg_scene_destroy(s);
    }
    bg_renderer_destroy(r);
}

/* The tree plan's pixels that ran out of walk steps are the CPU reference's, for the window's pixels
 * of the frame and the pass's sample: a window of the tube is the full frame's rectangle. */
static void cpu_pixels_of_a_window(void **state)
{
    (void)state;
    enum { TW = 48, TH = 36 };
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_tube_scene();
    for (int samples = 1; samples <= 4; samples += 3) {
        check_window(r, s, BG_PLAN_AUTO, samples, BG_PIXEL_RGBA8, TW, TH, 13, 11, 20, 15, NULL, "tube");
        check_window(r, s, BG_PLAN_AUTO, samples, BG_PIXEL_RGBA32F, TW, TH, 20, 15, 9, 7, NULL, "tube float");
        bg_render_stats st;
        bg_renderer_get_stats(r, &st);
        assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
        assert_true(st.fallback_pixels > 0);
    }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* Into a texture, samples and a window give what bg_render_gpu gives (rows bottom first). */
static void into_a_texture(void **state)
{
    (void)state;
    enum { TW = 40, TH = 30 };
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    for (int f = 0; f < 2; f++) {
        macs_format mf = f ? MACS_FORMAT_RGBA32F : MACS_FORMAT_RGBA8;
        size_t px = f ? 16 : 4;
        macs_texture_desc d = {TW, TH, mf, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, NULL, 0};
        macs_texture *t = NULL;
        assert_int_equal(macs_texture_create(util_fx.ctx, &d, &t), MACS_OK);
        bg_render_settings set = bg_render_settings_init();
        set.samples = 4;
        set.frame_width = W;
        set.frame_height = H;
        set.window_x = 70;
        set.window_y = 40;
        bg_image img;
        unsigned char *want = image_alloc(&img, TW, TH, f ? BG_PIXEL_RGBA32F : BG_PIXEL_RGBA8);
        render(r, s, &set, &img, "texture's reference");
        bg_status st = bg_render_gpu_to_texture(r, s, &set, t);
        if (st != BG_OK)
            fail_msg("bg_render_gpu_to_texture: %s", bg_renderer_error_message(r));
        unsigned char *got = malloc((size_t)TW * TH * px);
        assert_non_null(got);
        assert_int_equal(macs_texture_read(t, got, 0), MACS_OK);
        /* The same passes into a texture as into the image read back (GL 2.1 appendix A, rule 4). */
        for (int y = 0; y < TH; y++)
            if (memcmp(got + (size_t)(TH - 1 - y) * TW * px, want + (size_t)y * TW * px, (size_t)TW * px) != 0)
                fail_msg("texture (%s): row %d differs from bg_render_gpu's", f ? "RGBA32F" : "RGBA8", y);
        free(got);
        free(want);
        macs_texture_destroy(t);
    }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* ---- tiles ---- */

/* 1 MiB makes tiles of 13 rows or fewer at 160 wide (docs/gpu_pipeline.md: 476 bytes a pixel at
 * max_depth 5), 10 of them: the image is the one piece's bit for bit on every plan (on any driver
 * in the fused plans, on Mesa in the multipass, which may batch a tile otherwise: expect_rectangle). */
static void budget_tiles_are_the_one_piece(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_GLASS);
    for (int p = 0; p < 3; p++)
        for (int samples = 1; samples <= 4; samples += 3) {
            bg_pixel_format format = samples == 1 ? BG_PIXEL_RGBA8 : BG_PIXEL_RGBA32F;
            bg_image one, tiled;
            image_alloc(&one, W, H, format);
            image_alloc(&tiled, W, H, format);
            bg_render_settings set = bg_render_settings_init();
            set.gpu_plan = plans[p];
            set.samples = samples;
            assert_int_equal(render(r, s, &set, &one, plan_names[p]).tiles, 1);
            set.gpu_memory_budget = 1024.0 * 1024.0;
            bg_render_stats st = render(r, s, &set, &tiled, plan_names[p]);
            assert_int_equal(st.tiles, 10);
            char what[96];
            snprintf(what, sizeof what, "%s, %d samples, tiles against the one piece", plan_names[p], samples);
            expect_rectangle(plans[p], samples != 1, tiled.pixels, one.pixels, W, H, gpu_threshold_of(SCENE_GLASS),
                             what);
            free(one.pixels);
            free(tiled.pixels);
        }
    /* The tree plan's CPU pixels in tiles: 96x72 at 1 MiB is 4 tiles of 18 rows. */
    bg_scene_destroy(s);
    s = util_tube_scene();
    bg_image one, tiled;
    image_alloc(&one, 96, 72, BG_PIXEL_RGBA8);
    image_alloc(&tiled, 96, 72, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    set.samples = 2;
    render(r, s, &set, &one, "tube");
    set.gpu_memory_budget = 1024.0 * 1024.0;
    bg_render_stats st = render(r, s, &set, &tiled, "tube tiles");
    assert_int_equal(st.tiles, 4);
    assert_true(st.fallback_pixels > 0);
    /* The tree plan: the same program per pixel (expect_rectangle), the CPU reference's pixels alike. */
    assert_memory_equal(one.pixels, tiled.pixels, (size_t)96 * 72 * 4);
    free(one.pixels);
    free(tiled.pixels);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* Beyond GL's texture size (capped at 256 here, the earth texture's width) the image renders in
 * tiles, equal to the uncapped renderer's one piece, on the fused and the tree plan. */
static void beyond_the_texture_size(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_texture_size = 256;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    bg_renderer *small = util_renderer(ctx);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *scenes[2] = {util_scene(SCENE_PAPER_EARTH_SHADOW), util_scene(SCENE_MANY_SPHERES)};
    for (int k = 0; k < 2; k++) {
        int w = k ? 300 : 300, h = k ? 100 : 280;
        bg_image one, tiled;
        image_alloc(&one, w, h, BG_PIXEL_RGBA8);
        image_alloc(&tiled, w, h, BG_PIXEL_RGBA8);
        bg_render_settings set = bg_render_settings_init();
        set.samples = 2;
        render(r, scenes[k], &set, &one, "one piece");
        util_render_gpu(small, ctx, scenes[k], &set, &tiled, "tiles");
        bg_render_stats st;
        bg_renderer_get_stats(small, &st);
        assert_int_equal(st.tiles, k ? 2 : 4);
        assert_int_equal(st.plan, k ? BG_PLAN_FUSED_TREE : BG_PLAN_FUSED);
        /* Fused plans in two contexts: programs of the same source strings (the cap changes the tree
         * textures' layout, whose texel indices are whole numbers, not the text), so bit for bit on
         * any conforming driver (expect_rectangle). */
        assert_memory_equal(one.pixels, tiled.pixels, (size_t)w * h * 4);
        free(one.pixels);
        free(tiled.pixels);
        bg_scene_destroy(scenes[k]);
    }
    bg_renderer_destroy(r);
    bg_renderer_destroy(small);
    macs_context_destroy(ctx);
}

/* ---- progress and cancel ---- */

typedef struct progress_log {
    double values[64];
    int count;
    int cancel_at; /* the call that returns false; -1 never */
} progress_log;

static bool record(double fraction, void *user)
{
    progress_log *log = user;
    if (log->count < 64)
        log->values[log->count] = fraction;
    log->count++;
    return log->count - 1 != log->cancel_at;
}

static void progress_per_sample_pass(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    for (int p = 0; p < 3; p++)
        for (int samples = 1; samples <= 4; samples += 3) {
            progress_log log;
            memset(&log, 0, sizeof log);
            log.cancel_at = -1;
            bg_image img;
            image_alloc(&img, W, H, BG_PIXEL_RGBA8);
            bg_render_settings set = bg_render_settings_init();
            set.gpu_plan = plans[p];
            set.samples = samples;
            set.progress = record;
            set.progress_user = &log;
            render(r, s, &set, &img, plan_names[p]);
            /* 0, then k / n after pass k of n but the last, then 1. */
            assert_int_equal(log.count, samples + 1);
            for (int k = 0; k <= samples; k++)
                assert_true(log.values[k] == (double)k / samples);
            free(img.pixels);
        }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

static void cancel_leaves_the_image_untouched(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_GLASS);
    const int cases[3][2] = {{1, 0}, {4, 0}, {4, 2}}; /* samples, the call that cancels */
    for (int p = 0; p < 3; p++)
        for (int c = 0; c < 3; c++) {
            progress_log log;
            memset(&log, 0, sizeof log);
            log.cancel_at = cases[c][1];
            bg_image img;
            unsigned char *px = image_alloc(&img, W, H, BG_PIXEL_RGBA8);
            bg_render_settings set = bg_render_settings_init();
            set.gpu_plan = plans[p];
            set.samples = cases[c][0];
            set.progress = record;
            set.progress_user = &log;
            assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_CANCELLED);
            assert_int_equal(bg_renderer_error(r), BG_ERR_CANCELLED);
            assert_non_null(strstr(bg_renderer_error_message(r), "cancelled"));
            bg_renderer_clear_error(r);
            assert_int_equal(log.count, cases[c][1] + 1);
            for (size_t i = 0; i < (size_t)W * H * 4; i++)
                if (px[i] != 0xA5)
                    fail_msg("%s, %d samples, cancelled at call %d: the image was written", plan_names[p],
                             cases[c][0], cases[c][1]);
            /* The renderer renders the next frame. */
            set.progress = NULL;
            render(r, s, &set, &img, plan_names[p]);
            free(px);
        }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* With tiles, progress runs over the whole image and a cancel leaves the finished tiles written and
 * the others untouched. */
static void tiles_progress_and_cancel(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    bg_image one, img;
    unsigned char *f = image_alloc(&one, W, H, BG_PIXEL_RGBA8);
    unsigned char *p = image_alloc(&img, W, H, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    render(r, s, &set, &one, "one piece");
    set.gpu_memory_budget = 1024.0 * 1024.0; /* 10 tiles of 12 rows */
    set.samples = 2;
    progress_log log;
    memset(&log, 0, sizeof log);
    log.cancel_at = -1;
    set.progress = record;
    set.progress_user = &log;
    render(r, s, &set, &img, "tiles");
    /* Per tile: its 0, its one pass's 1/2, its 1. */
    assert_int_equal(log.count, 30);
    for (int k = 1; k < log.count; k++)
        assert_true(log.values[k] >= log.values[k - 1]);
    assert_true(log.values[0] == 0.0 && log.values[log.count - 1] == 1.0);
    memset(&log, 0, sizeof log);
    log.cancel_at = 7; /* the fourth tile's last call */
    set.samples = 0;
    memset(p, 0xA5, (size_t)W * H * 4);
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_CANCELLED);
    bg_renderer_clear_error(r);
    unsigned char sentinel[W * 4];
    memset(sentinel, 0xA5, sizeof sentinel);
    for (int y = 0; y < H; y++) {
        /* A finished tile is the one piece's rows on any driver: the fused plan (expect_rectangle). */
        bool done = memcmp(p + (size_t)y * W * 4, f + (size_t)y * W * 4, W * 4) == 0;
        bool untouched = memcmp(p + (size_t)y * W * 4, sentinel, sizeof sentinel) == 0;
        /* Tiles of 12 rows, one sample: calls 0, 1 per tile; call 7 is the fourth tile's 1, which its
         * render ignores, so four tiles are written and the fifth is never started. */
        if (y < 48 ? !done : !untouched)
            fail_msg("cancelled tiles: row %d is %s", y, done ? "written" : untouched ? "untouched" : "neither");
    }
    free(f);
    free(p);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

static void bad_settings_name_their_field(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_image img;
    unsigned char *px = image_alloc(&img, 32, 24, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    set.samples = -3;
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.samples"));
    bg_renderer_clear_error(r);
    set.samples = 0;
    set.frame_width = 40;
    set.window_x = 9;
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.window_x"));
    bg_renderer_clear_error(r);
    macs_texture_desc d = {32, 24, MACS_FORMAT_RGBA8, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, NULL, 0};
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(util_fx.ctx, &d, &t), MACS_OK);
    set.frame_width = 0;
    set.window_x = 0;
    set.frame_height = 23;
    assert_int_equal(bg_render_gpu_to_texture(r, s, &set, t), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.frame_height"));
    bg_renderer_clear_error(r);
    set.frame_height = 0;
    set.gpu_memory_budget = 1000.0;
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.gpu_memory_budget"));
    bg_renderer_clear_error(r);
    for (size_t i = 0; i < (size_t)32 * 24 * 4; i++)
        assert_int_equal(px[i], 0xA5);
    macs_texture_destroy(t);
    free(px);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(one_sample_is_the_default),
        UTIL_EACH_SCENE(UTIL_SCENE_UNIT_TEST)
        cmocka_unit_test(sixteen_samples_converge_to_the_coverage),
        cmocka_unit_test(windows_are_rectangles_of_the_frame),
        cmocka_unit_test(cpu_pixels_of_a_window),
        cmocka_unit_test(into_a_texture),
        cmocka_unit_test(budget_tiles_are_the_one_piece),
        cmocka_unit_test(beyond_the_texture_size),
        cmocka_unit_test(progress_per_sample_pass),
        cmocka_unit_test(tiles_progress_and_cancel),
        cmocka_unit_test(cancel_leaves_the_image_untouched),
        cmocka_unit_test(bad_settings_name_their_field),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
