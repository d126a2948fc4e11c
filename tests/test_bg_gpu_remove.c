/* Removal on the GPU renderer: a scene rendered (every cache warm), then stripped of a sphere, a
 * light, a material and a texture and committed, renders with the same renderer exactly what a
 * fresh renderer renders for the scene built without them, and within the thresholds against the
 * CPU reference, in each plan: the unrolled fused plan, the multipass, and the tree variant (with
 * 9 spheres, forced and chosen by BG_PLAN_AUTO). The removal changes the committed structure
 * (object, material, light and texture counts and indices), which the renderer must notice. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "gpu_thresholds.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_removal.h"

enum { W = 96, H = 96 };

/* The removal scene is not a shared one; it is held to the error model's common row
 * (gpu_thresholds.h): its spheres' and mirror's silhouettes fall under the silhouette allowance. */
static const gpu_threshold removal_row = {SCENE_MANY_SPHERES, 2.0, 0.004, 69.0, 0.001};

static bg_gpu_plan render(bg_renderer *r, bg_scene *s, const bg_render_settings *set, unsigned char *px,
                          const char *label)
{
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    util_render_gpu(r, util_fx.ctx, s, set, &img, label);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    return stats.plan;
}

static void check_plan(int spheres, bg_gpu_plan plan, bg_gpu_plan want, const char *label)
{
    size_t bytes = (size_t)W * H * 4;
    unsigned char *full = malloc(bytes), *after = malloc(bytes), *fresh = malloc(bytes);
    assert_non_null(full);
    assert_non_null(after);
    assert_non_null(fresh);
    bg_scene *a = NULL, *b = NULL;
    assert_int_equal(bg_scene_create(NULL, &a), BG_OK);
    assert_int_equal(bg_scene_create(NULL, &b), BG_OK);
    util_doomed d;
    util_removal_scene(a, spheres, &d);
    util_removal_scene(b, spheres, NULL);
    bg_render_settings set = bg_render_settings_init();
    set.gpu_plan = plan;

    bg_renderer *r = util_renderer(util_fx.ctx);
    assert_int_equal(render(r, a, &set, full, label), want);
    util_removal_remove(a, &d);
    assert_int_equal(render(r, a, &set, after, label), want);
    bg_renderer *r2 = util_renderer(util_fx.ctx);
    assert_int_equal(render(r2, b, &set, fresh, label), want);
    assert_true(memcmp(full, fresh, bytes) != 0); /* the doomed items showed */
    /* Equal on any conforming driver: the stripped commit has the fresh scene's structure and values,
     * so both renderers run programs of the same source strings on the same uniforms and textures
     * (GL 2.1 appendix A, rule 4). */
    if (memcmp(after, fresh, bytes) != 0)
        fail_msg("%s: after the removal the image differs from that of a scene built without the items", label);
    unsigned char *cpu = util_cpu_reference(b, &set, W, H);
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, after};
    util_expect_near_row(cpu, &img, &removal_row, label);

    free(cpu);
    free(full);
    free(after);
    free(fresh);
    bg_renderer_destroy(r);
    bg_renderer_destroy(r2);
    bg_scene_destroy(a);
    bg_scene_destroy(b);
}

static void fused_plan(void **state)
{
    (void)state;
    check_plan(4, BG_PLAN_FUSED, BG_PLAN_FUSED, "removal fused");
}

static void multipass_plan(void **state)
{
    (void)state;
    check_plan(4, BG_PLAN_MULTIPASS, BG_PLAN_MULTIPASS, "removal multipass");
}

static void tree_plan(void **state)
{
    (void)state;
    check_plan(9, BG_PLAN_FUSED_TREE, BG_PLAN_FUSED_TREE, "removal fused tree");
}

static void auto_plan_walks_the_tree(void **state)
{
    (void)state;
    check_plan(9, BG_PLAN_AUTO, BG_PLAN_FUSED_TREE, "removal auto (tree)");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fused_plan),
        cmocka_unit_test(multipass_plan),
        cmocka_unit_test(tree_plan),
        cmocka_unit_test(auto_plan_walks_the_tree),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
