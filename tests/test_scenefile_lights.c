/* Area lights and the thin lens in a JSON scene: a sphere light, a rectangle light and a lens load
 * into the bg_light and bg_camera values a C builder gives them (the scene has no getters, so the
 * two scenes' CPU images are compared bit for bit, at several samples so that every sample point of
 * the lights and the lens is used); and the format's zeros are the library's: a sphere of radius 0
 * and an aperture of 0 are the point light and the pinhole. */
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
#include "betelgeuse_scenefile.h"

enum { W = 48, H = 36, SAMPLES = 4 };

/* A floor and a ball the lights shade; the lights and camera come after. */
static const char *const objects = "\"objects\": [{\"plane\": {}}, {\"sphere\": {\"center\": [0, 1, 0]}}]";

static float *render(bg_scene *scene)
{
    bg_render_settings set = bg_render_settings_init();
    set.frame_width = W;
    set.frame_height = H;
    set.samples = SAMPLES;
    float *px = malloc((size_t)W * H * 4 * sizeof *px);
    assert_non_null(px);
    bg_image im = {W, H, BG_PIXEL_RGBA32F, 0, px};
    if (bg_render_cpu(scene, &set, &im) != BG_OK)
        fail_msg("render: %s", bg_scene_error_message(scene));
    return px;
}

static bg_scene *load(const char *lights_and_camera, bg_scenefile_result *r)
{
    char text[2048], message[1024];
    snprintf(text, sizeof text, "{%s, %s}", objects, lights_and_camera);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (bg_scenefile_load_string(text, NULL, s, r, message, sizeof message) != BG_OK)
        fail_msg("%s: %s", text, message);
    return s;
}

/* The objects of the text above, built in C, with the given lights and camera. */
static bg_scene *build(const bg_light *lights, int count, const bg_camera *camera)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat, id;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    bg_object_desc plane = bg_object_desc_init(BG_SHAPE_PLANE, mat);
    assert_int_equal(bg_scene_add_object(s, &plane, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 1, 0), 1.0, mat, &id), BG_OK);
    for (int i = 0; i < count; i++)
        assert_int_equal(bg_scene_add_light(s, &lights[i], &id), BG_OK);
    assert_int_equal(bg_scene_set_camera(s, camera), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

static size_t differing(const float *a, const float *b)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        n += memcmp(a + 4 * i, b + 4 * i, 4 * sizeof *a) != 0;
    return n;
}

static void area_lights_and_a_lens_load_as_built(void **state)
{
    (void)state;
    bg_scenefile_result r;
    bg_scene *loaded = load("\"lights\": ["
                            "{\"sphere\": {\"center\": [-2, 4, 1], \"radius\": 0.75}, \"color\": [1, 0.9, 0.8],"
                            " \"intensity\": 0.7},"
                            "{\"type\": \"rectangle\", \"rectangle\": {\"corner\": [1, 3, -1], \"edge_u\": [1.5, 0, 0],"
                            " \"edge_v\": [0, 0, 2]}, \"intensity\": 0.6, \"attenuation\": [0.5, 0, 0.1]}],"
                            "\"camera\": {\"position\": [0, 2, 6], \"look_at\": [0, 1, 0], \"aperture_radius\": 0.2,"
                            " \"focus_distance\": 4.5}",
                            &r);
    assert_int_equal(r.summary.lights, 2);
    assert_true(r.lights_from_file);

    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0, 2, 6);
    cam.look_at = bg_vec3_make(0, 1, 0);
    cam.aperture_radius = 0.2;
    cam.focus_distance = 4.5;
    assert_memory_equal(&r.camera, &cam, sizeof cam);

    bg_light l[2] = {bg_light_init(), bg_light_init()};
    l[0].type = BG_LIGHT_SPHERE;
    l[0].position = bg_vec3_make(-2, 4, 1);
    l[0].radius = 0.75;
    l[0].color[1] = 0.9;
    l[0].color[2] = 0.8;
    l[0].intensity = 0.7;
    l[1].type = BG_LIGHT_RECTANGLE;
    l[1].position = bg_vec3_make(1, 3, -1);
    l[1].edge_u = bg_vec3_make(1.5, 0, 0);
    l[1].edge_v = bg_vec3_make(0, 0, 2); /* edge_u x edge_v = (0, -3, 0): down, at the floor */
    l[1].intensity = 0.6;
    l[1].attenuation[0] = 0.5;
    l[1].attenuation[2] = 0.1;
    bg_scene *built = build(l, 2, &cam);

    float *a = render(loaded), *b = render(built);
    size_t diff = differing(a, b);
    if (diff)
        fail_msg("%zu of %d pixels differ from the builder's", diff, W * H);

    /* The comparison sees the shapes and the lens: point lights and a pinhole give another image. */
    bg_scene_destroy(built);
    l[0].type = l[1].type = BG_LIGHT_POINT;
    cam.aperture_radius = 0;
    built = build(l, 2, &cam);
    float *c = render(built);
    size_t changed = differing(a, c);
    if (changed < (size_t)W * H / 4)
        fail_msg("only %zu of %d pixels change without the shapes and the lens", changed, W * H);
    print_message("sphere light, rectangle light and lens: %d pixels as built; %zu differ from points and a "
                  "pinhole\n", W * H, changed);
    free(a);
    free(b);
    free(c);
    bg_scene_destroy(built);
    bg_scene_destroy(loaded);
}

/* Radius 0 is the point light and aperture 0 the pinhole, bit for bit, whatever the focus. */
static void the_zeros_are_a_point_light_and_a_pinhole(void **state)
{
    (void)state;
    bg_scenefile_result r;
    bg_scene *zeros = load("\"lights\": [{\"sphere\": {\"center\": [1, 4, 2], \"radius\": 0}}],"
                           "\"camera\": {\"position\": [0, 2, 6], \"aperture_radius\": 0, \"focus_distance\": 3}",
                           &r);
    assert_true(r.camera.aperture_radius == 0 && r.camera.focus_distance == 3);
    bg_scene *plain = load("\"lights\": [{\"position\": [1, 4, 2]}], \"camera\": {\"position\": [0, 2, 6]}", &r);
    assert_true(r.camera.aperture_radius == 0 && r.camera.focus_distance == 0);
    float *a = render(zeros), *b = render(plain);
    size_t diff = differing(a, b);
    if (diff)
        fail_msg("%zu of %d pixels differ between the zeros and the point light with a pinhole", diff, W * H);
    free(a);
    free(b);
    bg_scene_destroy(zeros);
    bg_scene_destroy(plain);
}

/* "visible": the light's shape is drawn glowing in its colour times intensity, and everything else
 * stays as it was (the shape casts no shadow, and emission lights nothing else); a point light has
 * no shape to show. */
static void visible_area_lights_are_drawn(void **state)
{
    (void)state;
    const char *lights[2] = {
        "\"camera\": {\"position\": [0, 1, 6], \"look_at\": [0, 1, 0]}, \"lights\": ["
        "{\"sphere\": {\"center\": [-1.5, 1.5, 0], \"radius\": 0.5}, \"color\": [1, 0.5, 0.25]},"
        "{\"rectangle\": {\"corner\": [1, 2, -0.5], \"edge_u\": [1, 0, 0], \"edge_v\": [0, 0, 1]}}]",
        "\"camera\": {\"position\": [0, 1, 6], \"look_at\": [0, 1, 0]}, \"lights\": ["
        "{\"sphere\": {\"center\": [-1.5, 1.5, 0], \"radius\": 0.5}, \"color\": [1, 0.5, 0.25], \"visible\": true},"
        "{\"rectangle\": {\"corner\": [1, 2, -0.5], \"edge_u\": [1, 0, 0], \"edge_v\": [0, 0, 1]}, \"visible\": true}]"};
    bg_scenefile_result r;
    bg_scene *hidden = load(lights[0], &r), *shown = load(lights[1], &r);
    float *a = render(hidden), *b = render(shown);
    /* The sphere light's centre is seen at about column 14, row 12 of 48 x 36 (the ball of the
     * objects above stands at the middle). */
    const float *c = b + ((size_t)12 * W + 14) * 4, *bg = a + ((size_t)12 * W + 14) * 4;
    print_message("sphere light's centre: hidden %.3f %.3f %.3f, visible %.3f %.3f %.3f\n", bg[0], bg[1], bg[2], c[0],
                  c[1], c[2]);
    assert_true(fabsf(c[0] - 1.0f) < 1e-6f && fabsf(c[1] - 0.5f) < 1e-6f && fabsf(c[2] - 0.25f) < 1e-6f);
    assert_true(bg[0] == 0.0f);
    /* Below the horizon of the shapes, nothing changes: the shapes cast no shadow. */
    size_t changed_below = 0;
    for (int y = H / 2; y < H; y++)
        for (int x = 0; x < W; x++)
            changed_below += memcmp(a + ((size_t)y * W + x) * 4, b + ((size_t)y * W + x) * 4, 4 * sizeof *a) != 0;
    assert_int_equal(changed_below, 0);
    free(a);
    free(b);
    bg_scene_destroy(hidden);
    bg_scene_destroy(shown);
    bg_scene *s = NULL;
    char message[1024];
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(bg_scenefile_load_string("{\"lights\": [{\"position\": [0, 1, 0], \"visible\": true}]}", NULL, s,
                                              &r, message, sizeof message),
                     BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "lights[0].visible"));
    bg_scene_destroy(s);
}

/* A visible rectangle whose shape no renderer can draw (edges of 1e-120 or 1e200, a 1000 x 1e-4
 * strip) is refused by the call that adds it, naming the shape, and in a scene file naming lights[i]:
 * before, the add took it and every later commit failed on "the shape of visible light 0". The
 * same rectangles are accepted when they only light the scene, and an ordinary visible one commits. */
static void undrawable_visible_shapes_are_refused_when_added(void **state)
{
    (void)state;
    static const struct {
        double u, v;
        const char *why;
    } cases[] = {{1e-120, 1e-120, "outside [1e-100, 1e100]"}, {1e200, 1e200, "is not finite"},
                 {1000, 1e-4, "is singular"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        bg_light l = bg_light_init();
        l.type = BG_LIGHT_RECTANGLE;
        l.edge_u = bg_vec3_make(cases[i].u, 0, 0);
        l.edge_v = bg_vec3_make(0, 0, cases[i].v);
        uint32_t h;
        assert_int_equal(bg_scene_add_light(s, &l, &h), BG_OK); /* not drawn: it only lights */
        l.visible = true;
        assert_int_equal(bg_scene_add_light(s, &l, &h), BG_ERR_INVALID_ARGUMENT);
        print_message("%s\n", bg_scene_error_message(s));
        assert_non_null(strstr(bg_scene_error_message(s), "bg_scene_add_light: visible shape (edge_u, edge_v)"));
        assert_non_null(strstr(bg_scene_error_message(s), cases[i].why));
        assert_int_equal(bg_scene_commit(s), BG_OK); /* the refused light left nothing behind */
        bg_scene_destroy(s);

        char json[256], message[1024];
        snprintf(json, sizeof json, "{\"lights\": [{\"rectangle\": {\"corner\": [0, 3, 0], \"edge_u\": [%g, 0, 0], "
                 "\"edge_v\": [0, 0, %g]}, \"visible\": true}]}", cases[i].u, cases[i].v);
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        bg_scenefile_result r;
        assert_int_equal(bg_scenefile_load_string(json, NULL, s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
        print_message("%s\n", message);
        assert_non_null(strstr(message, "lights[0]"));
        assert_non_null(strstr(message, cases[i].why));
        bg_scene_destroy(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(area_lights_and_a_lens_load_as_built),
        cmocka_unit_test(the_zeros_are_a_point_light_and_a_pinhole),
        cmocka_unit_test(visible_area_lights_are_drawn),
        cmocka_unit_test(undrawable_visible_shapes_are_refused_when_added),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
