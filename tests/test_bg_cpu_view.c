/* The CPU reference's samples, crop windows, progress and cancelling (bg_render_settings.samples,
 * frame_*, window_*, progress; docs/shading.md 1.1): one sample is the default render bit for bit;
 * 16 samples of a slanted high-contrast edge come within a measured bound of the exact coverage; a
 * window is the same rectangle of the full frame bit for bit, at any sample count and thread count;
 * progress is told 0 first, never less than before, 1 last; a cancelled render returns
 * BG_ERR_CANCELLED with each row complete or untouched; bad settings name their field. */
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
#include "util_gpu.h"

enum { W = 64, H = 48 };

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

static void render_ok(bg_scene *s, const bg_render_settings *set, bg_image *img)
{
    bg_status st = bg_render_cpu(s, set, img);
    if (st != BG_OK)
        fail_msg("bg_render_cpu: %s: %s", bg_status_string(st), bg_scene_error_message(s));
}

/* ---- samples ---- */

static void one_sample_is_the_default(void **state)
{
    (void)state;
    const scene_id ids[] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS, SCENE_TEXTURED_ANISO};
    for (size_t k = 0; k < sizeof ids / sizeof ids[0]; k++) {
        bg_scene *s = util_scene(ids[k]);
        for (int f = 0; f < 2; f++) {
            bg_pixel_format format = f ? BG_PIXEL_RGBA32F : BG_PIXEL_RGBA8;
            bg_image a, b;
            image_alloc(&a, W, H, format);
            image_alloc(&b, W, H, format);
            bg_render_settings set = bg_render_settings_init();
            render_ok(s, &set, &a);
            set.samples = 1;
            render_ok(s, &set, &b);
            assert_memory_equal(a.pixels, b.pixels, (size_t)W * H * (f ? 16 : 4));
            /* More samples do change an image with edges: the comparison above can fail. */
            set.samples = 4;
            render_ok(s, &set, &b);
            assert_true(memcmp(a.pixels, b.pixels, (size_t)W * H * (f ? 16 : 4)) != 0);
            free(a.pixels);
            free(b.pixels);
        }
        bg_scene_destroy(s);
    }
}

/* Measured (64x48, the edge at 20 degrees from the vertical): 1 sample max error 0.4614, mean
 * 0.00414; 4 samples (2x2) max 0.1415, mean 0.00120; 16 samples (4x4) max 0.0459, mean 0.00034.
 * The bounds are 1.5 times the 16-sample values; one sample must break them (the test can fail). */
static void sixteen_samples_converge_to_the_coverage(void **state)
{
    (void)state;
    bg_scene *s = util_edge_scene();
    double max[3], mean[3];
    const int counts[3] = {1, 4, 16};
    for (int k = 0; k < 3; k++) {
        bg_image img;
        float *px = image_alloc(&img, W, H, BG_PIXEL_RGBA32F);
        bg_render_settings set = util_edge_settings(counts[k]);
        render_ok(s, &set, &img);
        util_edge_error(px, W, H, &max[k], &mean[k]);
        print_message("%2d samples: max error %.4f, mean %.5f\n", counts[k], max[k], mean[k]);
        free(px);
    }
    assert_true(max[0] > 0.07 && mean[0] > 0.0006);
    assert_true(max[2] <= 0.07);
    assert_true(mean[2] <= 0.0006);
    assert_true(mean[2] < mean[1] && mean[1] < mean[0]);
    bg_scene_destroy(s);
}

static void sample_count_and_threads_do_not_matter(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_GLASS);
    bg_image a, b;
    image_alloc(&a, W, H, BG_PIXEL_RGBA32F);
    image_alloc(&b, W, H, BG_PIXEL_RGBA32F);
    bg_render_settings set = bg_render_settings_init();
    set.samples = 6; /* a 2 x 3 grid */
    set.threads = 1;
    render_ok(s, &set, &a);
    set.threads = 5;
    render_ok(s, &set, &b);
    assert_memory_equal(a.pixels, b.pixels, (size_t)W * H * 16);
    free(a.pixels);
    free(b.pixels);
    bg_scene_destroy(s);
}

/* ---- windows ---- */

static void check_window(bg_scene *s, int samples, bg_pixel_format format, int x0, int y0, int w, int h)
{
    size_t px = format == BG_PIXEL_RGBA32F ? 16 : 4;
    bg_image full, win;
    unsigned char *f = image_alloc(&full, W, H, format);
    unsigned char *p = image_alloc(&win, w, h, format);
    bg_render_settings set = bg_render_settings_init();
    set.samples = samples;
    render_ok(s, &set, &full);
    set.frame_width = W;
    set.frame_height = H;
    set.window_x = x0;
    set.window_y = y0;
    set.threads = 3;
    render_ok(s, &set, &win);
    for (int y = 0; y < h; y++)
        if (memcmp(p + (size_t)y * w * px, f + ((size_t)(y0 + y) * W + x0) * px, (size_t)w * px) != 0)
            fail_msg("window %dx%d at (%d, %d), %d samples: row %d differs from the full frame's", w, h, x0, y0,
                     samples, y);
    free(f);
    free(p);
}

static void windows_are_rectangles_of_the_frame(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    check_window(s, 1, BG_PIXEL_RGBA8, 0, 0, 17, 9);
    check_window(s, 1, BG_PIXEL_RGBA32F, 30, 20, 34, 28); /* the bottom-right corner */
    check_window(s, 4, BG_PIXEL_RGBA32F, 5, 7, 1, 1);
    check_window(s, 9, BG_PIXEL_RGBA8, 11, 0, 40, 48);
    bg_scene_destroy(s);
    s = util_scene(SCENE_GLASS);
    check_window(s, 2, BG_PIXEL_RGBA32F, 13, 29, 21, 11);
    bg_scene_destroy(s);
}

/* Four windows tiling the frame are the frame. */
static void tiles_make_the_frame(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_MIRROR);
    bg_image full, tile;
    unsigned char *f = image_alloc(&full, W, H, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    set.samples = 4;
    render_ok(s, &set, &full);
    unsigned char *asm_ = calloc((size_t)W * H, 4);
    assert_non_null(asm_);
    const int xs[3] = {0, 23, W}, ys[3] = {0, 31, H};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int w = xs[i + 1] - xs[i], h = ys[j + 1] - ys[j];
            unsigned char *t = image_alloc(&tile, w, h, BG_PIXEL_RGBA8);
            set.frame_width = W;
            set.frame_height = H;
            set.window_x = xs[i];
            set.window_y = ys[j];
            render_ok(s, &set, &tile);
            for (int y = 0; y < h; y++)
                memcpy(asm_ + ((size_t)(ys[j] + y) * W + xs[i]) * 4, t + (size_t)y * w * 4, (size_t)w * 4);
            free(t);
        }
    assert_memory_equal(asm_, f, (size_t)W * H * 4);
    free(asm_);
    free(f);
    bg_scene_destroy(s);
}

/* ---- progress and cancel ---- */

typedef struct progress_log {
    double values[4096];
    int count;
    int cancel_at; /* the call that returns false; -1 never */
    bool decreased;
} progress_log;

static bool record(double fraction, void *user)
{
    progress_log *log = user;
    if (log->count > 0 && fraction < log->values[log->count - 1])
        log->decreased = true;
    if (log->count < 4096)
        log->values[log->count] = fraction;
    log->count++;
    return log->count - 1 != log->cancel_at;
}

static void progress_runs_from_zero_to_one(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    for (int threads = 1; threads <= 4; threads += 3) {
        progress_log log;
        memset(&log, 0, sizeof log);
        log.cancel_at = -1;
        bg_image img;
        image_alloc(&img, W, H, BG_PIXEL_RGBA8);
        bg_render_settings set = bg_render_settings_init();
        set.threads = threads;
        set.progress = record;
        set.progress_user = &log;
        render_ok(s, &set, &img);
        assert_false(log.decreased);
        assert_true(log.values[0] == 0.0);
        assert_true(log.values[log.count - 1] == 1.0);
        /* Every row but the last is told once, whichever thread rendered it, plus 0 and 1: the count
         * does not depend on the threads or on the machine's load. */
        assert_int_equal(log.count, H + 1);
        for (int i = 0; i < log.count; i++)
            assert_true(log.values[i] == (i == H ? 1.0 : (double)i / H));
        free(img.pixels);
    }
    bg_scene_destroy(s);
}

static void check_cancel(bg_scene *s, int threads, int cancel_at)
{
    bg_image full, img;
    unsigned char *f = image_alloc(&full, W, H, BG_PIXEL_RGBA8);
    unsigned char *p = image_alloc(&img, W, H, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    set.threads = threads;
    render_ok(s, &set, &full);
    progress_log log;
    memset(&log, 0, sizeof log);
    log.cancel_at = cancel_at;
    set.progress = record;
    set.progress_user = &log;
    assert_int_equal(bg_render_cpu(s, &set, &img), BG_ERR_CANCELLED);
    assert_int_equal(bg_scene_error(s), BG_ERR_CANCELLED);
    assert_non_null(strstr(bg_scene_error_message(s), "cancelled"));
    bg_scene_clear_error(s);
    assert_int_equal(log.count, cancel_at + 1); /* no call after the cancel */
    unsigned char sentinel[W * 4];
    memset(sentinel, 0xA5, sizeof sentinel);
    int complete = 0;
    for (int y = 0; y < H; y++) {
        const unsigned char *row = p + (size_t)y * W * 4;
        if (memcmp(row, f + (size_t)y * W * 4, W * 4) == 0)
            complete++;
        else if (memcmp(row, sentinel, sizeof sentinel) != 0)
            fail_msg("threads %d, cancelled at call %d: row %d is neither complete nor untouched", threads,
                     cancel_at, y);
    }
    /* Cancelled before any row: nothing; after the k-th row told: at least k rows, and with one thread
     * not all. With more, the other threads may have finished every row before the caller's thread
     * got to tell the k-th (a busy machine does that), so "not all" is no promise there. */
    if (cancel_at == 0)
        assert_int_equal(complete, 0);
    else
        assert_true(complete >= cancel_at && (threads > 1 || complete < H));
    free(f);
    free(p);
}

static void cancel_stops_the_render(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_GLASS);
    check_cancel(s, 1, 0);
    check_cancel(s, 1, 5);
    check_cancel(s, 3, 0);
    check_cancel(s, 3, 2);
    /* The scene renders again after a cancel. */
    bg_image img;
    image_alloc(&img, W, H, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    render_ok(s, &set, &img);
    free(img.pixels);
    bg_scene_destroy(s);
}

/* ---- bad settings ---- */

static void bad_settings_name_their_field(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    struct {
        const char *field;
        int samples, fw, fh, wx, wy;
    } cases[] = {
        {"settings.samples", -1, 0, 0, 0, 0},
        {"settings.samples", BG_MAX_SAMPLES + 1, 0, 0, 0, 0},
        {"settings.samples", 1 << 30, 0, 0, 0, 0},
        {"settings.frame_width", 0, -5, 0, 0, 0},
        {"settings.frame_width", 0, 20000, 0, 0, 0},
        {"settings.frame_width", 0, W - 1, 0, 0, 0},   /* smaller than the image */
        {"settings.frame_height", 0, 0, H - 1, 0, 0},
        {"settings.window_x", 0, 0, 0, 1, 0},          /* the frame is the image: no room */
        {"settings.window_x", 0, W + 10, 0, -1, 0},
        {"settings.window_x", 0, W + 10, 0, 11, 0},    /* past the frame's right edge */
        {"settings.window_y", 0, 0, H + 3, 0, 4},
        {"settings.window_y", 0, 0, H + 3, 0, -2},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        bg_image img;
        unsigned char *p = image_alloc(&img, W, H, BG_PIXEL_RGBA8);
        bg_render_settings set = bg_render_settings_init();
        set.samples = cases[k].samples;
        set.frame_width = cases[k].fw;
        set.frame_height = cases[k].fh;
        set.window_x = cases[k].wx;
        set.window_y = cases[k].wy;
        assert_int_equal(bg_render_cpu(s, &set, &img), BG_ERR_INVALID_ARGUMENT);
        const char *m = bg_scene_error_message(s);
        print_message("%s\n", m);
        if (!strstr(m, cases[k].field))
            fail_msg("case %zu: message \"%s\" does not name %s", k, m, cases[k].field);
        for (size_t i = 0; i < (size_t)W * H * 4; i++)
            if (p[i] != 0xA5)
                fail_msg("case %zu: the image was written", k);
        bg_scene_clear_error(s);
        free(p);
    }
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(one_sample_is_the_default),
        cmocka_unit_test(sixteen_samples_converge_to_the_coverage),
        cmocka_unit_test(sample_count_and_threads_do_not_matter),
        cmocka_unit_test(windows_are_rectangles_of_the_frame),
        cmocka_unit_test(tiles_make_the_frame),
        cmocka_unit_test(progress_runs_from_zero_to_one),
        cmocka_unit_test(cancel_stops_the_render),
        cmocka_unit_test(bad_settings_name_their_field),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
