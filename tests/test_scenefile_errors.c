/* Broken scene files: each is refused with the right status and a message that names the file,
 * the JSON path of the bad value and the reason; the logger hears the same message; good files
 * with nothing in them give the documented defaults. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"

typedef struct broken {
    const char *json;
    bg_status status;
    const char *expect[3]; /* substrings of the message, besides the file name */
} broken;

static const broken cases[] = {
    /* bad JSON */
    {"{\"camera\": {\"fov_y\": 45,}}", BG_ERR_INVALID_ARGUMENT, {"line 1, column 2", "not valid JSON (near", NULL}},
    {"{\n  \"image\": {\"width\": 64\n", BG_ERR_INVALID_ARGUMENT, {"line 3, column 1", "not valid JSON", NULL}},
    {"", BG_ERR_INVALID_ARGUMENT, {"not valid JSON", NULL}},
    {"[1, 2]", BG_ERR_INVALID_ARGUMENT, {"must be an object (got an array)", NULL}},
    /* unknown and repeated keys */
    {"{\"lihgts\": []}", BG_ERR_INVALID_ARGUMENT, {"lihgts: unknown key \"lihgts\"", "known: camera, image", NULL}},
    {"{\"objects\": [{\"sphere\": {\"radius_\": 1}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].sphere.radius_: unknown key", "known: center, radius", NULL}},
    {"{\"camera\": {\"fov_y\": 40, \"fov_y\": 50}}", BG_ERR_INVALID_ARGUMENT, {"camera.fov_y: the key is given twice", NULL}},
    {"{\"objects\": [{\"box\": {}, \"transform\": [{\"shear\": 1}]}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].transform[0].shear: unknown key", NULL}},
    {"{\"materials\": {\"m\": {\"base\": {\"color\": 1}}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.base.color: unknown key", NULL}},
    /* wrong types */
    {"{\"objects\": [{\"sphere\": {\"radius\": \"big\"}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].sphere.radius: must be a number (got a string)", NULL}},
    {"{\"objects\": {\"sphere\": {}}}", BG_ERR_INVALID_ARGUMENT, {"objects: must be an array", NULL}},
    {"{\"camera\": {\"position\": [0, 1]}}", BG_ERR_INVALID_ARGUMENT,
     {"camera.position: must be an array of 3 numbers (got 2 elements)", NULL}},
    {"{\"camera\": {\"up\": [0, true, 0]}}", BG_ERR_INVALID_ARGUMENT, {"camera.up[1]: must be a number (got a boolean)", NULL}},
    {"{\"objects\": [{\"box\": {}, \"casts_shadows\": 1}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].casts_shadows: must be true or false (got a number)", NULL}},
    {"{\"lights\": [{\"type\": \"spot\"}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].type: \"spot\" is not one of \"point\", \"directional\", \"sphere\", \"rectangle\"", NULL}},
    /* an area light's shape key: its own keys only, one shape, never beside "position", a "type"
     * that agrees, and no area type without its key */
    {"{\"lights\": [{\"sphere\": {\"centre\": [0, 1, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].sphere.centre: unknown key", "known: center, radius", NULL}},
    {"{\"lights\": [{\"rectangle\": {\"edge_w\": [0, 1, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].rectangle.edge_w: unknown key", "known: corner, edge_u, edge_v", NULL}},
    {"{\"lights\": [{\"sphere\": 1}]}", BG_ERR_INVALID_ARGUMENT, {"lights[0].sphere: must be an object", NULL}},
    {"{\"lights\": [{}, {\"sphere\": {}, \"rectangle\": {}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[1]: has two shapes, \"sphere\" and \"rectangle\"", NULL}},
    {"{\"lights\": [{\"position\": [0, 1, 0], \"sphere\": {\"radius\": 1}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0]: has both \"position\" and \"sphere\"", "\"sphere.center\"", NULL}},
    {"{\"lights\": [{\"rectangle\": {}, \"position\": [0, 1, 0]}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0]: has both \"position\" and \"rectangle\"", "\"rectangle.corner\"", NULL}},
    {"{\"lights\": [{\"type\": \"point\", \"sphere\": {}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].type: \"point\" does not match the \"sphere\" key", NULL}},
    {"{\"lights\": [{\"type\": \"sphere\", \"rectangle\": {}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].type: \"sphere\" does not match the \"rectangle\" key", NULL}},
    {"{\"lights\": [{\"type\": \"rectangle\", \"position\": [0, 1, 0]}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0]: type \"rectangle\" needs a \"rectangle\" key", NULL}},
    {"{\"objects\": [{\"material\": \"m\"}]}", BG_ERR_INVALID_ARGUMENT, {"objects[0]: has no shape", NULL}},
    {"{\"objects\": [{\"box\": {}, \"sphere\": {}}]}", BG_ERR_INVALID_ARGUMENT, {"objects[0]: has two shapes", NULL}},
    {"{\"objects\": [{\"box\": {\"size\": 2}}]}", BG_ERR_INVALID_ARGUMENT, {"objects[0].box.size: unknown key", "known: none", NULL}},
    /* out of range and non-finite */
    {"{\"objects\": [{\"sphere\": {\"radius\": -1}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].sphere.radius: must be > 0 (got -1)", NULL}},
    {"{\"objects\": [{\"sphere\": {\"radius\": 1e999}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].sphere.radius: must be a finite number", NULL}},
    {"{\"objects\": [{\"sphere\": {\"center\": [0, -1e400, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].sphere.center[1]: must be a finite number", NULL}},
    {"{\"materials\": {\"m\": {\"base\": {\"roughness\": 1.5}}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.base.roughness: must be in [0, 1] (got 1.5)", NULL}},
    {"{\"materials\": {\"m\": {\"emission\": [1, -2, 0]}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.emission[1]: must be >= 0 (got -2)", NULL}},
    {"{\"materials\": {\"m\": {\"ior\": 0}}}", BG_ERR_INVALID_ARGUMENT, {"materials.m.ior: must be > 0 (got 0)", NULL}},
    {"{\"materials\": {\"m\": {\"sides\": \"back\"}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.sides", "\"back\" is not one of \"solid\", \"front\", \"both\"", NULL}},
    {"{\"materials\": {\"m\": {\"coverage_cutoff\": 1.5}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.coverage_cutoff: must be in [0, 1] (got 1.5)", NULL}},
    {"{\"materials\": {\"m\": {\"coverage\": {\"channel\": 4}}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.coverage.channel", NULL}},
    {"{\"camera\": {\"fov_y\": 180}}", BG_ERR_INVALID_ARGUMENT, {"camera.fov_y: must be in (0, 180) (got 180)", NULL}},
    {"{\"image\": {\"width\": 0}}", BG_ERR_INVALID_ARGUMENT, {"image.width: must be in 1 .. 16384 (got 0)", NULL}},
    {"{\"image\": {\"samples\": 2.5}}", BG_ERR_INVALID_ARGUMENT, {"image.samples: must be a whole number (got 2.5)", NULL}},
    {"{\"image\": {\"samples\": 257}}", BG_ERR_INVALID_ARGUMENT, {"image.samples: must be in 1 .. 256 (got 257)", NULL}},
    {"{\"settings\": {\"max_depth\": 65}}", BG_ERR_INVALID_ARGUMENT, {"settings.max_depth: must be in 0 .. 64 (got 65)", NULL}},
    {"{\"settings\": {\"ambient\": -0.5}}", BG_ERR_INVALID_ARGUMENT, {"settings.ambient: must be >= 0 (got -0.5)", NULL}},
    {"{\"settings\": {\"background\": [0, -1, 0]}}", BG_ERR_INVALID_ARGUMENT,
     {"settings.background[1]: must be >= 0 (got -1)", NULL}},
    {"{\"settings\": {\"encoding\": \"gamma\"}}", BG_ERR_INVALID_ARGUMENT,
     {"settings.encoding: \"gamma\" is not one of \"srgb\", \"linear\"", NULL}},
    {"{\"settings\": {\"integrator\": \"bidirectional\"}}", BG_ERR_INVALID_ARGUMENT,
     {"settings.integrator: \"bidirectional\" is not one of \"whitted\", \"path\"", NULL}},
    {"{\"settings\": {\"integrator\": \"Path\"}}", BG_ERR_INVALID_ARGUMENT,
     {"settings.integrator: \"Path\" is not one of", NULL}},
    {"{\"settings\": {\"integrator\": 1}}", BG_ERR_INVALID_ARGUMENT, {"settings.integrator: must be a string", NULL}},
    {"{\"settings\": {\"path_ambient\": 1}}", BG_ERR_INVALID_ARGUMENT,
     {"settings.path_ambient: must be true or false (got a number)", NULL}},
    {"{\"settings\": {\"integrator_\": \"path\"}}", BG_ERR_INVALID_ARGUMENT,
     {"settings.integrator_: unknown key", "integrator, path_ambient", NULL}},
    {"{\"lights\": [{}, {\"attenuation\": [0, 0, 0]}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[1].attenuation: must not be all zero", NULL}},
    {"{\"lights\": [{\"spot_cutoff_degrees\": 120, \"direction\": [0, -1, 0]}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].spot_cutoff_degrees: must be in (0, 90], or 180", NULL}},
    {"{\"lights\": [{\"sphere\": {\"radius\": -0.5}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].sphere.radius: must be in [0, 1e+100] (got -0.5)", NULL}},
    {"{\"lights\": [{\"sphere\": {\"center\": [0, 1e999, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].sphere.center[1]: must be a finite number", NULL}},
    {"{\"lights\": [{\"rectangle\": {\"edge_u\": [0, 1]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].rectangle.edge_u: must be an array of 3 numbers (got 2 elements)", NULL}},
    /* the library refuses a rectangle's cone too; the file names the key */
    {"{\"lights\": [{\"rectangle\": {}, \"spot_cutoff_degrees\": 45, \"direction\": [0, -1, 0]}]}",
     BG_ERR_INVALID_ARGUMENT,
     {"lights[0].spot_cutoff_degrees: must be 180: a rectangle light has no spot cone (got 45)", NULL}},
    {"{\"camera\": {\"aperture_radius\": -0.1}}", BG_ERR_INVALID_ARGUMENT,
     {"camera.aperture_radius: must be >= 0 (got -0.1)", NULL}},
    {"{\"camera\": {\"focus_distance\": [4]}}", BG_ERR_INVALID_ARGUMENT,
     {"camera.focus_distance: must be a number (got an array)", NULL}},
    {"{\"camera\": {\"focus_distance\": -2}}", BG_ERR_INVALID_ARGUMENT,
     {"camera.focus_distance: must be >= 0 (got -2)", NULL}},
    {"{\"camera\": {\"aperture\": 0.1}}", BG_ERR_INVALID_ARGUMENT,
     {"camera.aperture: unknown key", "aperture_radius, focus_distance", NULL}},
    {"{\"objects\": [{\"box\": {}, \"transform\": [{\"scale\": [1, 0, 1]}]}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].transform[0].scale: must not be zero", NULL}},
    {"{\"objects\": [{\"box\": {}, \"transform\": {\"rotate\": {\"axis\": [0, 0, 0], \"degrees\": 5}}}]}",
     BG_ERR_INVALID_ARGUMENT, {"objects[0].transform.rotate.axis: must not be zero", NULL}},
    {"{\"objects\": [{\"plane\": {\"normal\": [0, 0, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].plane.normal: must not be zero", NULL}},
    {"{\"objects\": [{\"box\": {}, \"uv\": {\"scale\": [1, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].uv.scale[1]: must be > 0 (got 0)", NULL}},
    /* values each fine alone that the scene refuses together, named by the scene's own reason */
    {"{\"camera\": {\"position\": [1, 2, 3], \"look_at\": [1, 2, 3]}}", BG_ERR_INVALID_ARGUMENT,
     {"camera: the camera refused: ", "look_at", NULL}},
    {"{\"lights\": [{\"rectangle\": {\"edge_u\": [1, 0, 0], \"edge_v\": [-3, 0, 0]}}]}", BG_ERR_INVALID_ARGUMENT,
     {"lights[0].rectangle: the light refused: ", "parallel", NULL}},
    {"{\"objects\": [{\"box\": {}, \"transform\": {\"matrix\": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}}]}",
     BG_ERR_INVALID_ARGUMENT, {"objects[0]: the object refused: ", "affine", NULL}},
    {"{\"objects\": [{\"box\": {}, \"transform\": {\"matrix\": [[1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}}]}",
     BG_ERR_INVALID_ARGUMENT, {"objects[0].transform.matrix[0]: must be an array of 4 numbers (got 3 elements)", NULL}},
    /* references */
    {"{\"objects\": [{\"sphere\": {}, \"material\": \"gold\"}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].material: no material is named \"gold\"", NULL}},
    {"{\"materials\": {\"m\": {\"base\": {\"reflectance\": {\"texture\": \"wood\"}}}}}", BG_ERR_INVALID_ARGUMENT,
     {"materials.m.base.reflectance.texture: no texture is named \"wood\"", NULL}},
    {"{\"objects\": [{\"mesh\": {\"file\": \"two_boxes.obj\"}, \"uv\": {}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].uv: applies to analytic shapes only", NULL}},
    /* missing files, resolved against the base folder */
    {"{\"textures\": {\"t\": {\"file\": \"nope.png\"}}}", BG_ERR_IO, {"textures.t.file: ", "tests/data/nope.png", NULL}},
    {"{\"textures\": {\"t\": {}}}", BG_ERR_INVALID_ARGUMENT, {"textures.t: \"file\" is required", NULL}},
    {"{\"objects\": [{\"mesh\": {\"file\": \"missing.obj\"}}]}", BG_ERR_IO,
     {"objects[0].mesh.file: model file \"tests/data/missing.obj\": cannot open: ", NULL}},
    {"{\"objects\": [{\"mesh\": {\"file\": \"README.md\"}}]}", BG_ERR_INVALID_ARGUMENT,
     {"objects[0].mesh.file: cannot read model file \"tests/data/README.md\"", NULL}},
};

typedef struct heard {
    int errors;
    char last[2048];
} heard;

static void listen(bg_log_level level, const char *message, void *user)
{
    heard *h = user;
    if (level == BG_LOG_ERROR) {
        h->errors++;
        snprintf(h->last, sizeof h->last, "%s", message);
    }
}

static void every_broken_file_is_refused_by_path_and_reason(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const broken *c = &cases[i];
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        heard h = {0, ""};
        bg_scenefile_desc d = {.logger = {listen, &h}, .base_dir = "tests/data", .name = "bad.json"};
        bg_scenefile_result r;
        char message[1024];
        bg_status st = bg_scenefile_load_string(c->json, &d, s, &r, message, sizeof message);
        if (st != c->status)
            fail_msg("case %zu (%s): status %d, expected %d; message: %s", i, c->json, st, c->status, message);
        if (strncmp(message, "bad.json: ", 10) != 0)
            fail_msg("case %zu: message does not start with the file name: %s", i, message);
        for (int k = 0; k < 3 && c->expect[k]; k++)
            if (!strstr(message, c->expect[k]))
                fail_msg("case %zu (%s): message lacks \"%s\": %s", i, c->json, c->expect[k], message);
        assert_int_equal(h.errors, 1);
        assert_string_equal(h.last, message);
        bg_scene_destroy(s);
    }
    print_message("%zu broken files refused, each naming its path\n", sizeof cases / sizeof cases[0]);
}

static void calls_without_their_arguments_are_refused(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    char message[256];
    assert_int_equal(bg_scenefile_load(NULL, NULL, s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_string_equal(message, "bg_scenefile_load: path is NULL");
    assert_int_equal(bg_scenefile_load_string("{}", NULL, NULL, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_string_equal(message, "bg_scenefile_load_string: scene is NULL");
    assert_int_equal(bg_scenefile_load_model("x.obj", NULL, s, NULL, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_string_equal(message, "bg_scenefile_load_model: out is NULL");
    assert_int_equal(bg_scenefile_load_any(NULL, NULL, s, &r, NULL, 0), BG_ERR_INVALID_ARGUMENT);

    assert_int_equal(bg_scenefile_load("no/such/scene.json", NULL, s, &r, message, sizeof message), BG_ERR_IO);
    assert_non_null(strstr(message, "no/such/scene.json: cannot open: "));
    /* A small buffer gets the message's start, terminated; no buffer at all is fine. */
    char tiny[8];
    assert_int_equal(bg_scenefile_load_string("{\"x\": 1}", NULL, s, &r, tiny, sizeof tiny), BG_ERR_INVALID_ARGUMENT);
    assert_string_equal(tiny, "<string");
    assert_int_equal(bg_scenefile_load_string("{\"x\": 1}", NULL, s, &r, NULL, 0), BG_ERR_INVALID_ARGUMENT);
    bg_scene_destroy(s);
}

static void an_empty_scene_has_the_defaults(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    char message[256];
    assert_int_equal(bg_scenefile_load_string("{}", NULL, s, &r, message, sizeof message), BG_OK);
    assert_string_equal(message, "");
    assert_int_equal(r.image.width, 640);
    assert_int_equal(r.image.height, 480);
    assert_int_equal(r.image.samples, 1);
    bg_camera cam = bg_camera_init();
    assert_memory_equal(&r.camera, &cam, sizeof cam);
    bg_render_settings defaults = bg_render_settings_init();
    assert_int_equal(r.settings.max_depth, defaults.max_depth);
    assert_int_equal(r.settings.integrator, BG_INTEGRATOR_WHITTED);
    assert_false(r.settings.path_ambient);
    assert_false(r.camera_from_file);
    assert_false(r.summary.bounded);
    assert_int_equal(r.summary.objects, 0);
    assert_int_equal(bg_scene_commit_count(s), 1);

    /* An object without a material gets the default one, added once for all. */
    assert_int_equal(bg_scenefile_load_string("{\"objects\": [{\"box\": {}}, {\"sphere\": {\"center\": [3, 0, 0]}}],"
                                              " \"settings\": {\"encoding\": \"linear\"}}",
                                              NULL, s, &r, message, sizeof message),
                     BG_OK);
    assert_int_equal(r.summary.objects, 2);
    assert_int_equal(r.summary.materials, 1);
    assert_int_equal(r.settings.encoding, BG_ENCODING_LINEAR);
    assert_true(r.summary.bounded);
    assert_true(r.summary.bounds_min.x == -1.0 && r.summary.bounds_max.x == 4.0);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_broken_file_is_refused_by_path_and_reason),
        cmocka_unit_test(calls_without_their_arguments_are_refused),
        cmocka_unit_test(an_empty_scene_has_the_defaults),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
