/* The float32 stress cases that must hold (examples/scenes/stress_cases.h, class STRESS_MUST_HOLD):
 * the two paper scenes at scales 1e-3 .. 1e4 and moved up to 1e4 from the origin in three directions,
 * each within the normal thresholds of gpu_thresholds.h against the CPU reference of the same case
 * and against the CPU reference of the scene at the origin, with no acne pixel and no NaN or Inf;
 * and the scene with point lights lying exactly on its surfaces, which holds since shadow segments
 * are open at the light's end (docs/shading.md 2.8), against its CPU reference likewise.
 * Every other stress case is asserted free of NaN and Inf in the GPU's float output; how far those
 * degrade is measured by make stress, not asserted here. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "scenes/image_metrics.h"
#include "scenes/stress_cases.h"
#include "stress_verdict.h"
#include "util_gpu.h"

enum { W = STRESS_WIDTH, H = STRESS_HEIGHT };

static bg_scene *build(const stress_case *c, bool origin)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_status st = origin ? stress_case_build_origin(c, s) : stress_case_build(c, s);
    if (st != BG_OK)
        fail_msg("%s: %s", c->name, bg_scene_error_message(s));
    return s;
}

static void render_gpu(const stress_case *c, bg_scene *s, bg_image *img)
{
    bg_render_settings set = stress_case_settings(c);
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, img, c->name);
}

static void render_cpu(const stress_case *c, bg_scene *s, bg_image *img)
{
    bg_render_settings set = stress_case_settings(c);
    assert_int_equal(bg_render_cpu(s, &set, img), BG_OK);
}

/* The table has what must be asserted: both paper scenes at every decade from 1e-3 to 1e4 and at
 * offsets up to 1e4 in more than one direction, and the terrain mesh at 1e-3, 1 and 1e4. */
static void table_covers_the_must_hold_set(void **state)
{
    (void)state;
    int scaled[2] = {0, 0}, moved[2] = {0, 0}, own = 0;
    for (size_t i = 0; i < stress_case_count(); i++) {
        const stress_case *c = stress_case_at(i);
        if (c->class_ != STRESS_MUST_HOLD)
            continue;
        if (c->build) {
            /* the open end of shadow segments, and a mesh's self-shadowing from 1e-3 to 1e4 */
            assert_true(strcmp(c->name, "light on a surface") == 0 || strncmp(c->name, "terrain scale ", 14) == 0);
            own++;
            continue;
        }
        assert_true(c->scene == SCENE_PAPER_EARTH || c->scene == SCENE_PAPER_EARTH_SHADOW);
        assert_true(stress_case_is_placed(c));
        int k = c->scene == SCENE_PAPER_EARTH_SHADOW;
        if (c->offset != 0.0)
            moved[k] += c->offset <= 1e4;
        else
            scaled[k] += c->scale >= 1e-3 && c->scale <= 1e4;
    }
    for (int k = 0; k < 2; k++) {
        assert_int_equal(scaled[k], 7); /* 1e-3, 1e-2, 1e-1, 1e1, 1e2, 1e3, 1e4 */
        assert_true(moved[k] >= 5);
    }
    assert_int_equal(own, 4);
    assert_null(stress_case_at(stress_case_count()));
}

static void must_hold_cases(void **state)
{
    (void)state;
    unsigned char *cpu = malloc((size_t)W * H * 4), *org = malloc((size_t)W * H * 4), *gpu = malloc((size_t)W * H * 4);
    float *gpuf = malloc((size_t)W * H * 16);
    assert_non_null(cpu);
    assert_non_null(org);
    assert_non_null(gpu);
    assert_non_null(gpuf);
    bg_image ci = {W, H, BG_PIXEL_RGBA8, 0, cpu}, oi = {W, H, BG_PIXEL_RGBA8, 0, org};
    bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu}, fi = {W, H, BG_PIXEL_RGBA32F, 0, gpuf};
    int checked = 0, origin_scene = -1;
    for (size_t i = 0; i < stress_case_count(); i++) {
        const stress_case *c = stress_case_at(i);
        if (c->class_ != STRESS_MUST_HOLD)
            continue;
        bool placed = stress_case_is_placed(c);
        if (placed && (int)c->scene != origin_scene) {
            bg_scene *o = build(c, true);
            render_cpu(c, o, &oi);
            bg_scene_destroy(o);
            origin_scene = (int)c->scene;
        }
        bg_scene *s = build(c, false);
        render_cpu(c, s, &ci);
        render_gpu(c, s, &gi);
        render_gpu(c, s, &fi);
        bg_scene_destroy(s);

        image_metrics m, drift;
        image_acne acne, drift_acne;
        char why[256], line[512];
        assert_true(image_metrics_compare(&ci, &gi, GPU_SILHOUETTE_THRESHOLD, &m));
        assert_true(image_metrics_acne(&ci, &gi, GPU_SILHOUETTE_THRESHOLD, &acne));
        print_message("%-38s %s\n", c->name, image_metrics_format(&m, line, sizeof line));
        if (!stress_holds(c, &m, &acne, image_metrics_count_nonfinite(&fi), why, sizeof why))
            fail_msg("%s against its CPU reference: %s", c->name, why);
        checked++;
        /* A scene of its own has no origin image to drift from. */
        if (!placed)
            continue;
        /* The drift of the whole pipeline: the same ideal image as the scene at the origin. */
        assert_true(image_metrics_compare(&oi, &gi, GPU_SILHOUETTE_THRESHOLD, &drift));
        assert_true(image_metrics_acne(&oi, &gi, GPU_SILHOUETTE_THRESHOLD, &drift_acne));
        if (!stress_holds(c, &drift, &drift_acne, 0, why, sizeof why))
            fail_msg("%s against the CPU image of the scene at the origin: %s", c->name, why);
    }
    assert_true(checked >= 25);
    free(cpu);
    free(org);
    free(gpu);
    free(gpuf);
}

/* Every case, sweep ones included: the GPU's float output has no NaN and no Inf (GLSL 1.10 promises nothing about them, so the shaders guard every operation that could make one), and
 * a render is never refused. */
static void no_case_has_nan_or_inf(void **state)
{
    (void)state;
    float *px = malloc((size_t)W * H * 16);
    assert_non_null(px);
    bg_image fi = {W, H, BG_PIXEL_RGBA32F, 0, px};
    for (size_t i = 0; i < stress_case_count(); i++) {
        const stress_case *c = stress_case_at(i);
        bg_scene *s = build(c, false);
        render_gpu(c, s, &fi);
        size_t bad = image_metrics_count_nonfinite(&fi);
        if (bad != 0)
            fail_msg("%s: %zu non-finite values in the GPU's float output", c->name, bad);
        bg_scene_destroy(s);
    }
    free(px);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(table_covers_the_must_hold_set),
        cmocka_unit_test(must_hold_cases),
        cmocka_unit_test(no_case_has_nan_or_inf),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
