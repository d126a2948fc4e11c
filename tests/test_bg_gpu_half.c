/* The RGBA16F G-buffer (bg_renderer_desc.half_gbuffer) on every shared scene: its error against the
 * CPU reference within the bounds below, no NaN or Inf, the stats counting the half targets, split
 * passes (mixed RGBA32F and RGBA16F chunks) giving the same image (the same bits on Mesa, the error
 * model's bound elsewhere: util_expect_gpu_twins), and the fallback to RGBA32F with a
 * warning where GL refuses RGBA16F (simulated through a wrapped GL loader). 160x120 as in
 * test_bg_gpu_scenes, whose full-precision bounds (gpu_thresholds.h) these extend. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/scene/scene_internal.h"
#include "gpu_thresholds.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_thresholds.h"

enum { W = 160, H = 120 };

/* Bounds of the half-precision G-buffer against the CPU reference, in the units and with the
 * silhouette split of gpu_thresholds.h (interior max, mean and PSNR over the interior pixels, the over
 * share over every pixel). These rows stay measured: the error model of gpu_thresholds.h covers
 * float32 targets, not the 2^-11 steps of half floats. Measured on Mesa 22.3 llvmpipe (OSMesa, 2 cores) at 160x120;
 * the measured value is beside each row (interior max, largest channel mean, PSNR, over share with
 * its pixel count); the full-precision G-buffer's errors are those of gpu_thresholds.h. Each bound
 * is twice the measured error (PSNR 3 dB below it), with the floors of gpu_thresholds.h (interior
 * max 2, over 0.001). Half precision costs most in glass and many_spheres, where (most likely) a refracted
 * or reflected ray carries the normal's 2^-11 error to an edge farther on: there the error is not
 * spread evenly but a few pixels far off. The bounds still catch a half-pixel camera offset on every
 * scene (half_thresholds_catch_half_pixel_offset). */
static const gpu_threshold half_thresholds[SCENE_COUNT] = {
    /* scene                 interior_max mean   psnr  over      measured: interior max, mean, PSNR, over */
    {SCENE_PAPER_EARTH,          2.0,  0.022, 65.5, 0.001}, /* 1, 0.011, 68.59, 0 */
    {SCENE_PAPER_EARTH_SHADOW,   2.0,  0.024, 64.5, 0.001}, /* 1, 0.012, 67.64, 0 */
    {SCENE_MIRROR,               2.0,  0.052, 61.0, 0.001}, /* 1, 0.026, 64.10, 0 */
    {SCENE_GLASS,               48.0,  0.282, 41.5, 0.007}, /* 24, 0.141, 44.46, 0.0035 (68 px) */
    {SCENE_MANY_SPHERES,         4.0,  0.100, 48.0, 0.001}, /* 2, 0.050, 51.25, 0.0004 (7 px) */
    {SCENE_MANY_LIGHTS,          8.0,  0.036, 63.0, 0.001}, /* 4, 0.018, 66.09, 0 */
    {SCENE_ALL_PRIMITIVES,       2.0,  0.006, 70.0, 0.001}, /* 1, 0.003, 73.30, 0 */
    {SCENE_TEXTURED_ANISO,      12.0,  0.044, 61.5, 0.001}, /* 6, 0.022, 64.65, 0 */
};

/* Warnings and errors a renderer logged. */
typedef struct log_record {
    int warnings, errors;
    char last[1024];
} log_record;

static void record_log(bg_log_level level, const char *message, void *user)
{
    log_record *l = user;
    if (level == BG_LOG_WARNING)
        l->warnings++;
    if (level == BG_LOG_ERROR)
        l->errors++;
    snprintf(l->last, sizeof l->last, "%s", message);
}

/* One context for the suite (util_fx), with a full-precision and a half-precision renderer on it. */
static bg_renderer *half;
static log_record half_log;

static bg_renderer *renderer_on(macs_context *ctx, bool half_gbuffer, log_record *log)
{
    bg_renderer_desc d = {0};
    d.context = ctx;
    d.half_gbuffer = half_gbuffer;
    d.logger.func = record_log;
    d.logger.user = log;
    bg_renderer *r = NULL;
    assert_int_equal(bg_renderer_create(&d, &r, NULL, 0), BG_OK);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    return r;
}

static int group_setup(void **state)
{
    util_gpu_group_setup(state);
    half = renderer_on(util_fx.ctx, true, &half_log);
    return 0;
}

static int group_teardown(void **state)
{
    bg_renderer_destroy(half);
    return util_gpu_group_teardown(state);
}

/* Llvmpipe renders to RGBA16F: the probe found it, said nothing, and left no error behind. */
static void probe_finds_rgba16f(void **state)
{
    (void)state;
    if (half_log.warnings || half_log.errors)
        fail_msg("the probe logged: %s", half_log.last);
    assert_int_equal(bg_renderer_error(half), BG_OK);
    assert_int_equal(macs_context_error(util_fx.ctx), MACS_OK);
}

static void check_scene(scene_id id)
{
    const char *name = scenes_name(id);
    bg_scene *s = util_scene(id);
    size_t n = (size_t)W * H * 4;
    unsigned char *cpu = malloc(n), *full8 = malloc(n), *half8 = malloc(n);
    float *fullf = malloc(n * sizeof(float)), *halff = malloc(n * sizeof(float));
    assert_true(cpu && full8 && half8 && fullf && halff);
    bg_image ci = {W, H, BG_PIXEL_RGBA8, 0, cpu}, fi8 = {W, H, BG_PIXEL_RGBA8, 0, full8};
    bg_image hi8 = {W, H, BG_PIXEL_RGBA8, 0, half8};
    bg_image fif = {W, H, BG_PIXEL_RGBA32F, 0, fullf}, hif = {W, H, BG_PIXEL_RGBA32F, 0, halff};
    bg_render_settings set = util_multipass_settings();
    assert_int_equal(bg_render_cpu(s, &set, &ci), BG_OK);

    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &fi8, name);
    bg_render_stats full_stats, half_stats;
    bg_renderer_get_stats(util_fx.renderer, &full_stats);
    util_render_gpu(half, util_fx.ctx, s, &set, &hi8, name);
    bg_renderer_get_stats(half, &half_stats);

    /* Every slot but HIT and ONCE (both always written) is half; the default renderer has none. */
    assert_int_equal(full_stats.gbuffer_half_targets, 0);
    assert_int_equal(half_stats.gbuffer_targets, full_stats.gbuffer_targets);
    if (half_stats.gbuffer_half_targets != half_stats.gbuffer_targets - 2)
        fail_msg("%s: %d of %d G-buffer targets half, expected %d", name, half_stats.gbuffer_half_targets,
                 half_stats.gbuffer_targets, half_stats.gbuffer_targets - 2);

    image_metrics m_half, m_full, m_diff;
    assert_true(image_metrics_compare(&ci, &hi8, GPU_SILHOUETTE_THRESHOLD, &m_half));
    assert_true(image_metrics_compare(&ci, &fi8, GPU_SILHOUETTE_THRESHOLD, &m_full));
    assert_true(image_metrics_compare(&fi8, &hi8, GPU_SILHOUETTE_THRESHOLD, &m_diff));
    char line[512], why[256];
    print_message("%-19s half vs CPU  %s\n", name, image_metrics_format(&m_half, line, sizeof line));
    print_message("%-19s full vs CPU  %s\n", name, image_metrics_format(&m_full, line, sizeof line));
    print_message("%-19s half vs full %s\n", name, image_metrics_format(&m_diff, line, sizeof line));
    if (!gpu_threshold_check(&half_thresholds[id], &m_half, why, sizeof why))
        fail_msg("%s with the RGBA16F G-buffer: %s", name, why);

    /* Float output: finite, and the bits say whether half precision reached the image at all. */
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &fif, name);
    util_render_gpu(half, util_fx.ctx, s, &set, &hif, name);
    size_t bad = image_metrics_count_nonfinite(&hif);
    if (bad != 0)
        fail_msg("%s: %zu non-finite values in the RGBA32F output with the RGBA16F G-buffer", name, bad);
    size_t differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += fullf[i] != halff[i];
    print_message("%-19s %zu of %zu float output values differ from the RGBA32F G-buffer's\n", name, differ, n);
    if (differ == 0)
        fail_msg("%s: the RGBA16F G-buffer changed no bit of the float output", name);

    free(cpu);
    free(full8);
    free(half8);
    free(fullf);
    free(halff);
    bg_scene_destroy(s);
}

UTIL_EACH_SCENE(UTIL_SCENE_TEST)

/* Loose as some rows are, they are not blind: the CPU reference seen through a camera turned by half
 * a pixel breaks them on every scene, as it breaks gpu_thresholds.h. */
static void half_thresholds_catch_half_pixel_offset(void **state)
{
    (void)state;
    util_thresholds_catch_half_pixel_offset(half_thresholds, W, H, "the half-precision bounds");
}

/* One draw buffer splits the intersection pass into one chunk per target, so RGBA32F and RGBA16F
 * targets land in separate framebuffers: the bits must not change (MACS splits passes exactly: docs/gpu_pipeline.md). */
static void split_passes_give_the_same_bits(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_draw_buffers = 1;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    log_record log = {0};
    bg_renderer *r = renderer_on(ctx, true, &log);
    size_t n = (size_t)W * H * 4;
    float *a = malloc(n * sizeof(float)), *b = malloc(n * sizeof(float));
    assert_true(a && b);
    bg_image ai = {W, H, BG_PIXEL_RGBA32F, 0, a}, bi = {W, H, BG_PIXEL_RGBA32F, 0, b};
    bg_scene *s = util_scene(SCENE_TEXTURED_ANISO); /* every slot: transparency, tangents and coats */
    bg_render_settings set = util_multipass_settings();
    util_render_gpu(half, util_fx.ctx, s, &set, &ai, "uncapped");
    util_render_gpu(r, ctx, s, &set, &bi, "one draw buffer");
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_int_equal(stats.gbuffer_half_targets, stats.gbuffer_targets - 2);
    assert_true(stats.chunks > stats.passes[BG_PASS_INTERSECT] * stats.gbuffer_targets - 1);
    /* One draw buffer: every chunk a program of its own (util_expect_gpu_twins). */
    util_expect_gpu_twins(a, b, W, H, gpu_threshold_of(SCENE_TEXTURED_ANISO), "half G-buffer, one draw buffer");
    assert_int_equal(log.warnings + log.errors, 0);
    bg_scene_destroy(s);
    free(a);
    free(b);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* ---- a GL without RGBA16F: glTexImage2D refuses GL_RGBA16F_ARB with GL_INVALID_ENUM ---------- */

typedef void (*tex_image_fn)(unsigned, int, int, int, int, int, unsigned, unsigned, const void *);
typedef unsigned (*get_error_fn)(void);

static struct {
    macs_get_proc_address_fn real;
    void *real_user;
    tex_image_fn tex_image;
    get_error_fn get_error;
    unsigned pending; /* the error the next glGetError reports, 0 none */
    int refused;
} no16;

enum { GL_RGBA16F_ARB_ = 0x881A, GL_INVALID_ENUM_ = 0x0500 };

static void no16_tex_image(unsigned target, int level, int ifmt, int w, int h, int border, unsigned fmt,
                           unsigned type, const void *data)
{
    if (ifmt == GL_RGBA16F_ARB_) {
        no16.pending = GL_INVALID_ENUM_;
        no16.refused++;
        return;
    }
    no16.tex_image(target, level, ifmt, w, h, border, fmt, type, data);
}

static unsigned no16_get_error(void)
{
    unsigned e = no16.pending;
    no16.pending = 0;
    return e ? e : no16.get_error();
}

static macs_gl_proc no16_loader(const char *name, void *user)
{
    (void)user;
    macs_gl_proc p = no16.real(name, no16.real_user);
    if (p && strcmp(name, "glTexImage2D") == 0) {
        no16.tex_image = (tex_image_fn)p;
        return (macs_gl_proc)no16_tex_image;
    }
    if (p && strcmp(name, "glGetError") == 0) {
        no16.get_error = (get_error_fn)p;
        return (macs_gl_proc)no16_get_error;
    }
    return p;
}

/* The renderer is still made, warns once through its logger, stores no error, leaves no MACS error,
 * counts no half target and renders exactly what the default renderer renders. */
static void fallback_without_rgba16f(void **state)
{
    (void)state;
    memset(&no16, 0, sizeof no16);
    no16.real = macs_headless_get_proc_address(util_fx.headless);
    no16.real_user = macs_headless_proc_user(util_fx.headless);
    macs_context_desc cd = {0};
    cd.get_proc_address = no16_loader;
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    log_record log = {0}, full_log = {0};
    bg_renderer *r = renderer_on(ctx, true, &log);
    assert_true(no16.refused >= 1);
    assert_int_equal(log.warnings, 1);
    assert_int_equal(log.errors, 0);
    assert_non_null(strstr(log.last, "RGBA16F"));
    print_message("fallback warning: %s\n", log.last);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    assert_int_equal(macs_context_error(ctx), MACS_OK);

    bg_renderer *full = renderer_on(ctx, false, &full_log);
    size_t n = (size_t)W * H * 4;
    float *a = malloc(n * sizeof(float)), *b = malloc(n * sizeof(float));
    assert_true(a && b);
    bg_image ai = {W, H, BG_PIXEL_RGBA32F, 0, a}, bi = {W, H, BG_PIXEL_RGBA32F, 0, b};
    bg_scene *s = util_scene(SCENE_GLASS);
    bg_render_settings set = util_multipass_settings();
    util_render_gpu(r, ctx, s, &set, &ai, "fallback");
    util_render_gpu(full, ctx, s, &set, &bi, "default");
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_true(stats.gbuffer_targets >= 4);
    assert_int_equal(stats.gbuffer_half_targets, 0);
    /* Equal on any conforming driver: the G-buffer's format is no part of any program, so both
     * renderers run programs of the same source strings on the same inputs in the same order (GL 2.1
     * appendix A, rule 4), into targets of the same format. */
    assert_memory_equal(a, b, n * sizeof(float));
    assert_int_equal(log.warnings, 1); /* rendering does not warn again */
    assert_int_equal(full_log.warnings + full_log.errors, 0);
    bg_scene_destroy(s);
    free(a);
    free(b);
    bg_renderer_destroy(full);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(probe_finds_rgba16f),
        cmocka_unit_test(half_thresholds_catch_half_pixel_offset),
        UTIL_EACH_SCENE(UTIL_SCENE_UNIT_TEST)
        cmocka_unit_test(split_passes_give_the_same_bits),
        cmocka_unit_test(fallback_without_rgba16f),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
