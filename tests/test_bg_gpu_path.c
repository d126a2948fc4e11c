/* The path integrator on the GPU (docs/shading.md 13, docs/gpu_pipeline.md "The path integrator"):
 * both fused plans draw it and follow the CPU reference at 16 samples; a box of emitting white
 * walls gives its exact radiance; the multipass plan refuses it by name; a Whitted program and a
 * path program of one scene are two programs. */
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
#include "scenes/path_box.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 48, H = 40 };

static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE};
static const char *const plan_names[] = {"fused", "tree"};

/* A new scene that builder builds and commits. */
static bg_scene *built(bg_status (*builder)(bg_scene *))
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (builder(s) != BG_OK)
        fail_msg("building the scene: %s", bg_scene_error_message(s));
    return s;
}

static bg_render_settings path_settings(int samples, int max_depth)
{
    bg_render_settings set = bg_render_settings_init();
    set.integrator = BG_INTEGRATOR_PATH;
    set.samples = samples;
    set.max_depth = max_depth;
    set.threads = 2;
    return set;
}

/* The image of s in linear RGBA32F: on the CPU (plan < 0) or on plans[plan], which must draw it. */
static float *linear_image(bg_scene *s, const bg_render_settings *set, int w, int h, int plan)
{
    float *px = malloc((size_t)w * h * 16);
    assert_non_null(px);
    bg_image img = {w, h, BG_PIXEL_RGBA32F, 0, px};
    if (plan < 0) {
        if (bg_render_cpu(s, set, &img) != BG_OK)
            fail_msg("bg_render_cpu: %s", bg_scene_error_message(s));
        return px;
    }
    bg_render_settings own = *set;
    own.gpu_plan = plans[plan];
    bg_renderer *r = util_renderer(util_fx.ctx);
    util_render_gpu(r, util_fx.ctx, s, &own, &img, plan_names[plan]);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_int_equal(stats.plan, plans[plan]);
    bg_renderer_destroy(r);
    return px;
}

/* ---- the white box ---- */

/* A closed box of white Lambertian walls (C = 1, r = 1) that emit E: every hit adds E and every way
 * on is the f way with weight exactly 1 in exact arithmetic (rho = 1, f (L.n) / p_b = (1 / pi) (L.n)
 * / ((L.n) / pi)), and roulette keeps every path (q = 1), so each pixel is E (D + 1) after
 * D = max_depth bounces, whatever the samples. In float the weight is 1 to a few roundings a
 * bounce: 1e-5 relative is far above them and far below one bounce's E. */
#define WHITE_BOX_E 0.25
#define WHITE_BOX_TOLERANCE 1e-5

static void white_box_gives_e_times_bounces(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (path_box_white(s, WHITE_BOX_E) != BG_OK)
        fail_msg("path_box_white: %s", bg_scene_error_message(s));
    const int depths[] = {0, 2, 5};
    for (size_t k = 0; k < sizeof depths / sizeof depths[0]; k++) {
        bg_render_settings set = path_settings(4, depths[k]);
        double exact = WHITE_BOX_E * (depths[k] + 1);
        for (int plan = 0; plan < 2; plan++) {
            float *px = linear_image(s, &set, 16, 12, plan);
            double worst = 0.0;
            for (int i = 0; i < 16 * 12; i++)
                for (int c = 0; c < 3; c++) {
                    double e = fabs(px[4 * i + c] - exact);
                    worst = e > worst ? e : worst;
                }
            print_message("white box, max_depth %d, %-5s: largest error %.3g of %.3f\n", depths[k], plan_names[plan], worst,
                          exact);
            assert_true(worst <= WHITE_BOX_TOLERANCE * exact);
            free(px);
        }
    }
    bg_scene_destroy(s);
}

/* ---- the plans ---- */

/* The multipass plan does not draw the path integrator: forced, or chosen by BG_PLAN_AUTO for a
 * setting only it has, it refuses by naming settings.integrator; BG_PLAN_AUTO otherwise takes a
 * fused plan. */
static void multipass_refuses_path(void **state)
{
    (void)state;
    bg_scene *s = built(path_box_cornell);
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = path_settings(1, 2);
    set.gpu_plan = BG_PLAN_MULTIPASS;
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    print_message("forced multipass: %s\n", bg_renderer_error_message(r));
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.integrator"));
    bg_renderer_destroy(r); /* a renderer keeps its first error */
    r = util_renderer(util_fx.ctx);
    set.gpu_plan = BG_PLAN_AUTO;
    set.dmax = 100.0; /* the multipass plan's depth scale: BG_PLAN_AUTO would take that plan */
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    print_message("auto with dmax: %s\n", bg_renderer_error_message(r));
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.integrator"));
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.dmax"));
    bg_renderer_destroy(r);
    r = util_renderer(util_fx.ctx);
    set.dmax = 0.0;
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "auto");
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_true(stats.plan == BG_PLAN_FUSED || stats.plan == BG_PLAN_FUSED_TREE);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* One renderer, one scene: the Whitted image, the path image (a program of its own: one compile),
 * and the Whitted image again, the cached Whitted program's (no compile), byte for byte the first. */
static void whitted_and_path_are_two_programs(void **state)
{
    (void)state;
    bg_scene *s = built(path_box_cornell);
    for (int plan = 0; plan < 2; plan++) {
        unsigned char a[W * H * 4], b[W * H * 4], c[W * H * 4];
        bg_image ia = {W, H, BG_PIXEL_RGBA8, 0, a}, ib = {W, H, BG_PIXEL_RGBA8, 0, b}, ic = {W, H, BG_PIXEL_RGBA8, 0, c};
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_settings whitted = bg_render_settings_init(), path = path_settings(1, 3);
        whitted.gpu_plan = path.gpu_plan = plans[plan];
        bg_render_stats stats;
        util_render_gpu(r, util_fx.ctx, s, &whitted, &ia, "whitted");
        util_render_gpu(r, util_fx.ctx, s, &path, &ib, "path");
        bg_renderer_get_stats(r, &stats);
        assert_int_equal(stats.programs_compiled, 1);
        util_render_gpu(r, util_fx.ctx, s, &whitted, &ic, "whitted again");
        assert_memory_equal(a, c, sizeof a);
        assert_memory_not_equal(a, b, sizeof a);
        bg_renderer_destroy(r);
    }
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(white_box_gives_e_times_bounces),
        cmocka_unit_test(multipass_refuses_path),
        cmocka_unit_test(whitted_and_path_are_two_programs),
    };
    return cmocka_run_group_tests_name("bg_gpu_path", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
