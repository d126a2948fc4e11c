/* glTF alphaMode MASK and doubleSided, as the command loads them, judged by the rendered colours on
 * the CPU reference and every GPU plan: a MASK quad over a floor shows the floor through its hole
 * and casts a shadow with a lit hole; a single-sided quad seen from behind is not there, and a
 * double-sided one is lit on its back. The models are those of tests/data/make_side_models.py,
 * each with its own camera and light. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_warnings.h"

enum { W = 64, H = 64 };

/* The renderers compared: the CPU reference, then every GPU plan. */
static const bg_gpu_plan plans[] = {BG_PLAN_FUSED_TREE, BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
#define RENDERERS (1 + (int)(sizeof plans / sizeof plans[0]))
static const char *const renderer_name[RENDERERS] = {"cpu", "tree", "fused", "multipass"};

/* The model of tests/data as a whole scene, rendered by renderer k at W x H (RGBA8, top row first). */
static unsigned char *render(const char *model, int k)
{
    char path[256], message[1024];
    snprintf(path, sizeof path, "tests/data/%s", model);
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    bg_scenefile_result r;
    bg_scenefile_desc d;
    memset(&d, 0, sizeof d);
    if (bg_scenefile_load_model(path, &d, scene, &r, message, sizeof message) != BG_OK)
        fail_msg("%s: %s", model, message);
    assert_true(r.camera_from_file && r.lights_from_file);
    bg_render_settings set = r.settings;
    set.threads = 2;
    unsigned char *px = k == 0 ? util_cpu_reference(scene, &set, W, H)
                               : util_gpu_plan_image(scene, &set, plans[k - 1], W, H, renderer_name[k]);
    bg_scene_destroy(scene);
    return px;
}

static const unsigned char *at(const unsigned char *px, int x, int y)
{
    return px + 4 * (y * W + x);
}

static bool reddish(const unsigned char *p)
{
    return p[0] > 2 * p[1] + 20 && p[0] > 2 * p[2] + 20;
}

static bool greenish(const unsigned char *p)
{
    return p[1] > 2 * p[0] + 20 && p[1] > 2 * p[2] + 20;
}

/* The column of the point at x on a plane at distance `distance` from the camera (60 degrees). */
static int column_of(double x, double distance)
{
    return (int)(W / 2.0 + x / (distance * 0.57735026918962576) * W / 2.0);
}

/* Camera at z = 6, light at (4, 0, 4): the quad [-1, 1]^2 at z = 0 with a hole of half-width 1/2 (its
 * coverage bilinear, so the hole's corners round off), the floor at z = -1 (distance 7). The quad's
 * shadow covers floor x in [-2.25, 0.25] and the hole's lit patch x in [-1.625, -0.375]: floor x =
 * -2.0 is in shadow beside the quad, x = -1.45 lit through the hole beside the quad, x = 1.5 lit. */
static void mask_quad_over_a_floor(void **state)
{
    (void)state;
    for (int k = 0; k < RENDERERS; k++) {
        unsigned char *px = render("mask_over_floor.gltf", k);
        const unsigned char *hole = at(px, W / 2, H / 2), *leaf = at(px, column_of(0.75, 6.0), H / 2);
        const unsigned char *shade = at(px, column_of(-2.0, 7.0), H / 2), *patch = at(px, column_of(-1.45, 7.0), H / 2);
        const unsigned char *lit = at(px, column_of(1.5, 7.0), H / 2);
        print_message("%s: hole (%d, %d, %d), leaf (%d, %d, %d), shadow %d, lit patch in it %d, lit floor %d\n",
                      renderer_name[k], hole[0], hole[1], hole[2], leaf[0], leaf[1], leaf[2], shade[0], patch[0], lit[0]);
        assert_true(reddish(hole));
        assert_true(greenish(leaf));
        assert_true(reddish(shade) && reddish(patch) && reddish(lit));
        assert_true(shade[0] * 3 < patch[0] * 2);
        assert_true(shade[0] * 3 < lit[0] * 2);
        free(px);
    }
}

/* A quad facing +z seen and lit from -z: single-sided, it is not there (the background, black);
 * double-sided, its back is lit as its front would be. */
static void sides_seen_from_behind(void **state)
{
    (void)state;
    for (int k = 0; k < RENDERERS; k++) {
        unsigned char *one = render("one_sided_back.gltf", k), *two = render("two_sided_back.gltf", k);
        const unsigned char *a = at(one, W / 2, H / 2), *b = at(two, W / 2, H / 2);
        print_message("%s: single-sided back (%d, %d, %d), double-sided back (%d, %d, %d)\n", renderer_name[k], a[0],
                      a[1], a[2], b[0], b[1], b[2]);
        assert_true(a[0] == 0 && a[1] == 0 && a[2] == 0);
        assert_true(greenish(b) && b[1] > 200);
        free(one);
        free(two);
    }
}

/* A normal map cannot be taken (no renderer perturbs normals): a warning names the material. */
static void normal_map_is_left_out_with_a_warning(void **state)
{
    (void)state;
    util_warnings warning = {0, ""};
    char message[512];
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    bg_scenefile_desc d;
    memset(&d, 0, sizeof d);
    d.logger = (bg_logger){util_warnings_collect, &warning};
    bg_scenefile_result r;
    assert_int_equal(bg_scenefile_load_model("tests/data/normal_mapped.gltf", &d, scene, &r, message, sizeof message),
                     BG_OK);
    print_message("warnings: %s", warning.all);
    assert_int_equal(warning.count, 1);
    assert_non_null(strstr(warning.all, "\"bumpy\""));
    assert_non_null(strstr(warning.all, "normal (or bump) map is left out"));
    bg_scene_destroy(scene);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mask_quad_over_a_floor),
        cmocka_unit_test(sides_seen_from_behind),
        cmocka_unit_test(normal_map_is_left_out_with_a_warning),
    };
    return cmocka_run_group_tests_name("scenefile_sides", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
