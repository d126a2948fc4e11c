/* The example scenes of the distribution effects (examples/scenes/json: area_lights, depth_of_field,
 * glossy, environment) and of the path integrator (cornell_box, window_room) at 16 samples: every
 * GPU plan follows the CPU reference within the distribution thresholds, and the multipass refuses
 * the environment and the path integrator by name. */
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

enum { W = 64, H = 48 };

/* The rows of test_bg_distribution: the same sample points in float and double; a shadow ray or a
 * lens ray grazing an edge may still fall the other way, a few pixels' worth. */
static const gpu_threshold effects_row = {SCENE_COUNT, 24.0, 0.5, 35.0, 0.01};

static void scene_follows_cpu(const char *name)
{
    char path[256], message[1024];
    snprintf(path, sizeof path, "examples/scenes/json/%s.json", name);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    if (bg_scenefile_load(path, NULL, s, &r, message, sizeof message) != BG_OK)
        fail_msg("%s", message);
    bg_render_settings set = r.settings;
    set.samples = 16;
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
    static const char *const names[] = {"fused", "tree", "multipass"};
    /* What the multipass refuses, the first reason it finds: an environment, then the integrator. */
    const char *refused = strcmp(name, "environment") == 0 || strcmp(name, "window_room") == 0 ? "environment"
                          : set.integrator == BG_INTEGRATOR_PATH                               ? "settings.integrator"
                                                                                               : NULL;
    for (int p = 0; p < 3; p++) {
        char label[64];
        snprintf(label, sizeof label, "%s, %s", name, names[p]);
        if (refused && plans[p] == BG_PLAN_MULTIPASS) {
            util_expect_multipass_refuses(s, &set, refused);
            continue;
        }
        unsigned char *gpu = util_gpu_plan_image(s, &set, plans[p], W, H, label);
        bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
        util_expect_near_row(cpu, &gi, &effects_row, label);
        free(gpu);
    }
    free(cpu);
    bg_scene_destroy(s);
}

static void area_lights(void **state)
{
    (void)state;
    scene_follows_cpu("area_lights");
}

static void depth_of_field(void **state)
{
    (void)state;
    scene_follows_cpu("depth_of_field");
}

static void glossy(void **state)
{
    (void)state;
    scene_follows_cpu("glossy");
}

static void environment(void **state)
{
    (void)state;
    scene_follows_cpu("environment");
}

static void cornell_box(void **state)
{
    (void)state;
    scene_follows_cpu("cornell_box");
}

static void window_room(void **state)
{
    (void)state;
    scene_follows_cpu("window_room");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(area_lights),
        cmocka_unit_test(depth_of_field),
        cmocka_unit_test(glossy),
        cmocka_unit_test(environment),
        cmocka_unit_test(cornell_box),
        cmocka_unit_test(window_room),
    };
    return cmocka_run_group_tests_name("scenefile_effects", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
