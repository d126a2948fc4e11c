/* The GPU renderer's float range (docs/gpu_pipeline.md, "Float range"): a scene whose lengths lie
 * inside it renders as the CPU does at both ends, and an object, light or camera value beyond it is
 * refused (BG_ERR_LIMIT) by handle and field, where the GPU would miss the object or diverge (a
 * sphere of radius 1e19 vanished, aperture 1e10 gave noise), while the CPU renders the same scene. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"
#include "util_gpu.h"

enum { W = 96, H = 72 };

/* paper_earth_shadow scaled: its farthest length (the light) is about 10 units, so 1e14 puts it at
 * the top of the range and 1e-14 its smallest (the sphere) near the bottom. */
static void scaled_scenes_at_the_ends_match_cpu(void **state)
{
    (void)state;
    static const double scales[] = {1e-14, 1e14};
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        scene_params p = {0};
        p.scale = scales[i];
        assert_int_equal(scenes_build_ex(SCENE_PAPER_EARTH_SHADOW, &p, s), BG_OK);
        bg_render_settings set = bg_render_settings_init();
        unsigned char *cpu = util_cpu_reference(s, &set, W, H);
        for (size_t k = 0; k < sizeof plans / sizeof plans[0]; k++) {
            char label[64];
            snprintf(label, sizeof label, "scale %g, plan %d", scales[i], (int)plans[k]);
            unsigned char *gpu = util_gpu_plan_image(s, &set, plans[k], W, H, label);
            bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
            util_expect_near(cpu, &gi, SCENE_PAPER_EARTH_SHADOW, label);
            free(gpu);
        }
        free(cpu);
        bg_scene_destroy(s);
    }
}

typedef enum range_case {
    BIG_SPHERE,
    SMALL_SPHERE,
    BIG_SPHERE_LIGHT,
    SMALL_RECTANGLE_LIGHT,
    FAR_LIGHT,
    FAR_PLANE,
    FAR_BOX,
    WIDE_LENS,
    WIDE_ORTHOGRAPHIC,
    RANGE_CASES
} range_case;

static const struct {
    const char *name;
    const char *expect; /* in the message, after the item's name */
} cases[RANGE_CASES] = {
    {"sphere of radius 1e16", "overall scale 1e+16 is outside [1e-15, 1e15]"},
    {"sphere of radius 1e-16", "overall scale 1e-16 is outside [1e-15, 1e15]"},
    {"sphere light of radius 1e20", "radius 1e+20 is outside"},
    {"rectangle light with an edge of 1e-16", "edge_u length 1e-16 is outside"},
    {"point light 1e16 away", "position's distance from the camera 1e+16 is beyond 1e15"},
    {"plane 1e16 below the camera", "plane's distance from the camera 1e+16 is beyond 1e15"},
    {"box reaching 2e16 away", "box's reach from the camera 2e+16 is beyond 1e15"},
    {"aperture 2000 times the focus distance", "aperture_radius 2000 is more than 1000 times"},
    {"orthographic half_height 1e16", "half_height 1e+16 is outside"},
};

/* A lit unit sphere seen from 5 units, and the case's item; *item gets the item's handle text. */
static bg_scene *case_scene(range_case c, char *item, size_t size)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat, id = 0;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    uint32_t sphere;
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1.0, mat, &sphere), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(2, 4, 5);
    uint32_t light;
    assert_int_equal(bg_scene_add_light(s, &l, &light), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0, 0, 5);
    cam.look_at = bg_vec3_make(0, 0, 0);
    const char *kind = "object";
    switch (c) {
    case BIG_SPHERE:
    case SMALL_SPHERE:
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, -3, 0), c == BIG_SPHERE ? 1e16 : 1e-16, mat, &id),
                         BG_OK);
        break;
    case BIG_SPHERE_LIGHT:
    case SMALL_RECTANGLE_LIGHT:
    case FAR_LIGHT: {
        bg_light a = bg_light_init();
        a.position = bg_vec3_make(-2, 3, 2);
        if (c == BIG_SPHERE_LIGHT) {
            a.type = BG_LIGHT_SPHERE;
            a.radius = 1e20;
        } else if (c == SMALL_RECTANGLE_LIGHT) {
            a.type = BG_LIGHT_RECTANGLE;
            a.edge_u = bg_vec3_make(1e-16, 0, 0);
            a.edge_v = bg_vec3_make(0, 0, 1);
        } else {
            a.position = bg_vec3_make(0, 1e16, 0);
        }
        assert_int_equal(bg_scene_add_light(s, &a, &id), BG_OK);
        kind = "light";
        break;
    }
    case FAR_PLANE:
        assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -1e16, 0), bg_vec3_make(0, 1, 0), mat, &id), BG_OK);
        break;
    case FAR_BOX: {
        bg_object_desc d = bg_object_desc_init(BG_SHAPE_BOX, mat);
        d.transform = bg_mat4_translate(2e16, 0, 0);
        assert_int_equal(bg_scene_add_object(s, &d, &id), BG_OK);
        break;
    }
    case WIDE_LENS:
        cam.aperture_radius = 2000.0;
        cam.focus_distance = 1.0;
        kind = "camera";
        break;
    case WIDE_ORTHOGRAPHIC:
        cam.projection = BG_PROJECTION_ORTHOGRAPHIC;
        cam.half_height = 1e16;
        kind = "camera";
        break;
    case RANGE_CASES:
        break;
    }
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    if (strcmp(kind, "camera") == 0)
        snprintf(item, size, "camera: ");
    else
        snprintf(item, size, "%s %u: ", kind, (unsigned)id);
    return s;
}

static void beyond_the_range_is_refused_by_name(void **state)
{
    (void)state;
    bg_render_settings set = bg_render_settings_init();
    size_t bytes = (size_t)W * H * 4;
    unsigned char *px = malloc(bytes);
    assert_non_null(px);
    for (int c = 0; c < RANGE_CASES; c++) {
        char item[64];
        bg_scene *s = case_scene((range_case)c, item, sizeof item);
        bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
        bg_renderer *r = util_fx.renderer;
        bg_renderer_clear_error(r);
        bg_status st = (bg_render_gpu)(r, s, &set, &img);
        const char *msg = bg_renderer_error_message(r);
        print_message("%s: %s\n", cases[c].name, msg);
        if (st != BG_ERR_LIMIT)
            fail_msg("%s: bg_render_gpu gave %s, not BG_ERR_LIMIT", cases[c].name, bg_status_string(st));
        if (!strstr(msg, item) || !strstr(msg, cases[c].expect))
            fail_msg("%s: the message does not name \"%s\" and \"%s\"", cases[c].name, item, cases[c].expect);
        /* The CPU reference renders the same scene: the limit is the GPU's alone. */
        bg_render_settings cpu = set;
        cpu.threads = 1;
        assert_int_equal(bg_render_cpu(s, &cpu, &img), BG_OK);
        bg_scene_destroy(s);
    }
    /* The renderer goes on: an in-range scene renders after the refusals. */
    bg_renderer_clear_error(util_fx.renderer);
    bg_scene *ok = util_scene(SCENE_PAPER_EARTH);
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    util_render_gpu(util_fx.renderer, util_fx.ctx, ok, &set, &img, "in range after the refusals");
    bg_scene_destroy(ok);
    free(px);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(scaled_scenes_at_the_ends_match_cpu),
        cmocka_unit_test(beyond_the_range_is_refused_by_name),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
