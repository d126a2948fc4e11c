/* The GPU renderer's multipass plan (forced: test_bg_gpu_plans covers the fused one) against the
 * CPU reference on every shared scene: image metrics within the
 * thresholds of gpu_thresholds.h (printed per scene), no NaN or Inf in the float output, the RGBA8
 * output the encoding of the float one, and statistics that match the scene.
 *
 * Size: 160x120 rather than a square. A 4:3 image catches swapped width and height, an aspect ratio
 * applied to the wrong axis and row-stride mistakes that a square image hides; the vertical field of
 * view is fixed, so 4:3 only widens the view and every object stays framed. */
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
#include "betelgeuse/common/encoding.h"
#include "betelgeuse/cpu/cpu_internal.h"
#include "betelgeuse/scene/scene_internal.h"
#include "gpu_thresholds.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_thresholds.h"

enum { W = 160, H = 120 };

/* One context and renderer for the whole suite (util_fx): the renderer also meets scene after scene. */

/* Does the scene have mirror or glass materials (bounce levels expected), by construction in
 * examples/scenes/scenes.c: a specular share needs a roughness below 1/2 in some layer. */
static bool has_bounces(scene_id id)
{
    switch (id) {
    case SCENE_PAPER_EARTH:
    case SCENE_PAPER_EARTH_SHADOW:
    case SCENE_ALL_PRIMITIVES:
        return false;
    default:
        return true; /* mirror, glass, many_spheres (mirror, glass), many_lights and textured_aniso (coats) */
    }
}

static void check_stats(scene_id id, const bg_scene *s, const bg_render_stats *st)
{
    const char *name = scenes_name(id);
    const bg_scene_state *ss = bgi_scene_committed(s);
    int total = 0;
    for (int k = 0; k < BG_PASS_KIND_COUNT_; k++) {
        assert_true(st->passes[k] >= 0);
        total += st->passes[k];
    }
    /* Every object is tested at least once; batching (BG_SKIP_BATCH) puts several in one pass. */
    if (st->intersect_objects < (int)ss->object_count)
        fail_msg("%s: intersection passes tested %d objects for %u objects", name, st->intersect_objects,
                 ss->object_count);
    assert_true(st->passes[BG_PASS_INTERSECT] >= 1);
    assert_true(st->passes[BG_PASS_INTERSECT] <= st->intersect_objects);
    assert_true(st->passes[BG_PASS_RAYS] >= 1);
    assert_true(st->passes[BG_PASS_LIGHT] >= 1);
    assert_true(st->passes[BG_PASS_RESOLVE] >= 1);
    assert_true(st->chunks >= total); /* every pass draws at least one chunk */
    if (has_bounces(id)) {
        if (st->levels < 1)
            fail_msg("%s: has mirrors or glass but traced %d bounce levels", name, st->levels);
        assert_true(st->live_pixels[1] > 0);
        assert_true(st->passes[BG_PASS_SPAWN] >= 1);
    } else if (st->levels != 0 || st->passes[BG_PASS_SPAWN] != 0) {
        fail_msg("%s: no mirror or glass, yet %d bounce levels and %d spawn passes", name, st->levels,
                 st->passes[BG_PASS_SPAWN]);
    }
    assert_true(st->levels <= 5); /* default max_depth */
    assert_true(st->ray_sets >= 1 + st->levels);
    assert_true(st->live_pixels[0] > 0 && st->live_pixels[0] <= (uint64_t)W * H);
    for (int l = 0; l <= st->levels; l++)
        if (!(st->dmax[l] > 0.0 && isfinite(st->dmax[l])))
            fail_msg("%s: dmax[%d] = %g", name, l, st->dmax[l]);
    assert_true(st->gbuffer_targets >= 1);
    assert_int_equal(st->depth_bits, 24); /* float_depth was not asked for */
    assert_false(st->timed);              /* gpu_timing was not asked for */
}

static void check_scene(scene_id id)
{
    const char *name = scenes_name(id);
    bg_scene *s = util_scene(id);
    unsigned char *cpu = malloc((size_t)W * H * 4), *gpu = malloc((size_t)W * H * 4);
    float *gpuf = malloc((size_t)W * H * 4 * sizeof(float));
    assert_non_null(cpu);
    assert_non_null(gpu);
    assert_non_null(gpuf);
    bg_render_settings set = util_multipass_settings();
    bg_image ci = {W, H, BG_PIXEL_RGBA8, 0, cpu}, gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
    bg_image fi = {W, H, BG_PIXEL_RGBA32F, 0, gpuf};
    assert_int_equal(bg_render_cpu(s, &set, &ci), BG_OK);
    memset(gpu, 0xCD, (size_t)W * H * 4);
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &gi, name);
    bg_render_stats stats;
    bg_renderer_get_stats(util_fx.renderer, &stats);

    image_metrics m;
    assert_true(image_metrics_compare(&ci, &gi, GPU_SILHOUETTE_THRESHOLD, &m));
    char line[512], why[256];
    print_message("%-19s %s\n", name, image_metrics_format(&m, line, sizeof line));
    print_message("%-19s passes rays %d intersect %d shadow %d light %d spawn %d, chunks %d, levels %d, "
                  "ray sets %d (+%d skipped), dmax[0] %g, G-buffer targets %d\n",
                  name, stats.passes[BG_PASS_RAYS], stats.passes[BG_PASS_INTERSECT], stats.passes[BG_PASS_SHADOW],
                  stats.passes[BG_PASS_LIGHT], stats.passes[BG_PASS_SPAWN], stats.chunks, stats.levels,
                  stats.ray_sets, stats.ray_sets_skipped, stats.dmax[0], stats.gbuffer_targets);
    if (!gpu_threshold_check(gpu_threshold_of(id), &m, why, sizeof why)) {
        int x = m.interior.worst_x, y = m.interior.worst_y;
        const unsigned char *c = cpu + ((size_t)y * W + x) * 4, *g = gpu + ((size_t)y * W + x) * 4;
        fail_msg("%s: %s (worst interior pixel (%d, %d): CPU %d %d %d, GPU %d %d %d)", name, why, x, y, c[0], c[1],
                 c[2], g[0], g[1], g[2]);
    }
    for (int i = 0; i < W * H; i++)
        if (gpu[4 * i + 3] != cpu[4 * i + 3])
            fail_msg("%s: pixel (%d, %d) alpha %d, CPU %d", name, i % W, i / W, gpu[4 * i + 3], cpu[4 * i + 3]);
    check_stats(id, s, &stats);

    /* The float output: finite, non-negative, and what the RGBA8 output encodes. */
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &fi, name);
    size_t bad = image_metrics_count_nonfinite(&fi);
    if (bad != 0)
        fail_msg("%s: %zu non-finite values in the RGBA32F output", name, bad);
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            float v = gpuf[4 * i + c];
            int want = bgi_encode_channel(v, BG_ENCODING_SRGB);
            if (v < 0.0f || abs(want - gpu[4 * i + c]) > 1)
                fail_msg("%s: pixel (%d, %d) channel %d: float %g encodes to %d, RGBA8 output %d", name, i % W,
                         i / W, c, (double)v, want, gpu[4 * i + c]);
        }
    free(cpu);
    free(gpu);
    free(gpuf);
    bg_scene_destroy(s);
}

UTIL_EACH_SCENE(UTIL_SCENE_TEST)

/* The thresholds are tight enough to matter: the CPU reference seen through a camera turned by half
 * a pixel (the classic pixel-centre mistake) breaks them on every scene. */
static void thresholds_catch_half_pixel_offset(void **state)
{
    (void)state;
    util_thresholds_catch_half_pixel_offset(gpu_thresholds, W, H, "the thresholds");
}

/* The table is in scene_id order, one row per scene. */
static void threshold_table_is_complete(void **state)
{
    (void)state;
    for (int id = 0; id < SCENE_COUNT; id++) {
        const gpu_threshold *t = gpu_threshold_of((scene_id)id);
        assert_int_equal(t->scene, id);
        assert_true(t->interior_max >= 0 && t->interior_max < 255 && t->mean > 0 && t->psnr > 20 && t->over < 0.1);
    }
}

/* A 32-bit float depth buffer, when the context allows it and GL has ARB_depth_buffer_float: the
 * stats say 32 bits, and the image stays within the same bounds against the reference. */
static void float_depth(void **state)
{
    (void)state;
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(util_fx.headless);
    cd.get_proc_address_user = macs_headless_proc_user(util_fx.headless);
    cd.allow_float_depth = true;
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    macs_features feats;
    macs_context_get_features(ctx, &feats);
    bg_renderer_desc rd = {0};
    rd.context = ctx;
    rd.float_depth = true;
    bg_renderer *r = NULL;
    assert_int_equal(bg_renderer_create(&rd, &r, NULL, 0), BG_OK);
    const scene_id ids[2] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS};
    unsigned char *cpu = malloc((size_t)W * H * 4), *gpu = malloc((size_t)W * H * 4);
    assert_non_null(cpu);
    assert_non_null(gpu);
    for (int k = 0; k < 2; k++) {
        bg_scene *s = util_scene(ids[k]);
        bg_render_settings set = util_multipass_settings();
        bg_image ci = {W, H, BG_PIXEL_RGBA8, 0, cpu}, gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
        assert_int_equal(bg_render_cpu(s, &set, &ci), BG_OK);
        if (bg_render_gpu(r, s, &set, &gi) != BG_OK)
            fail_msg("%s: %s", scenes_name(ids[k]), bg_renderer_error_message(r));
        bg_render_stats stats;
        bg_renderer_get_stats(r, &stats);
        assert_int_equal(stats.depth_bits, feats.depth_buffer_float ? 32 : 24);
        image_metrics m;
        char line[512], why[256];
        assert_true(image_metrics_compare(&ci, &gi, GPU_SILHOUETTE_THRESHOLD, &m));
        print_message("%-19s float depth: %s\n", scenes_name(ids[k]), image_metrics_format(&m, line, sizeof line));
        if (!gpu_threshold_check(gpu_threshold_of(ids[k]), &m, why, sizeof why))
            fail_msg("%s with float depth: %s", scenes_name(ids[k]), why);
        bg_scene_destroy(s);
    }
    free(cpu);
    free(gpu);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(threshold_table_is_complete),
        cmocka_unit_test(thresholds_catch_half_pixel_offset),
        UTIL_EACH_SCENE(UTIL_SCENE_UNIT_TEST)
        cmocka_unit_test(float_depth),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
