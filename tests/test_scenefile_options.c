/* What bg_scenefile_desc asks of a model beyond its file (the command's --up, --smooth, --camera,
 * --look-from, --look-at, --fov, --aperture and --focus-distance): a Z-up model turned to stand on
 * y, with its cameras; normals computed where a file has none, smooth across soft edges and creased
 * at sharp ones; the file's Nth camera or the framing one; the caller's camera parts (lens included)
 * over the chosen camera; and every bad value refused by its field. The models are tests/data's
 * (tests/data/README.md). Also the integrator a JSON scene's settings choose, which the command's
 * --integrator overrides as these options override a camera. */
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
#include "scenefile/scenefile_internal.h"

enum { W = 64, H = 64 };

/* The model loaded with d; the status, the scene in *out (NULL on failure) and the message. */
static bg_status load(const char *path, const bg_scenefile_desc *d, bg_scene **out, bg_scenefile_result *r,
                      char *message, size_t size)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_status st = bg_scenefile_load_any(path, d, s, r, message, size);
    if (st != BG_OK) {
        bg_scene_destroy(s);
        s = NULL;
    }
    *out = s;
    return st;
}

static bg_scene *load_ok(const char *path, const bg_scenefile_desc *d, bg_scenefile_result *r)
{
    char message[1024];
    bg_scene *s = NULL;
    if (load(path, d, &s, r, message, sizeof message) != BG_OK)
        fail_msg("%s: %s", path, message);
    return s;
}

static void render(bg_scene *s, const bg_scenefile_result *r, unsigned char *px)
{
    bg_render_settings set = r->settings;
    set.frame_width = W;
    set.frame_height = H;
    bg_image im = {W, H, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_render_cpu(s, &set, &im), BG_OK);
}

static bool near(bg_vec3 a, double x, double y, double z)
{
    return fabs(a.x - x) < 1e-6 && fabs(a.y - y) < 1e-6 && fabs(a.z - z) < 1e-6;
}

/* zup_tower.obj is 1 x 1 x 3 along +z. As its file has it, it lies along z; with up z it stands
 * 3 tall on y, with its foot (z = 0) at y = 0, and the framing camera looks at its middle. */
static void a_z_up_model_stands_on_y(void **state)
{
    (void)state;
    bg_scenefile_result r;
    bg_scene *s = load_ok("tests/data/zup_tower.obj", NULL, &r);
    assert_true(r.summary.bounds_max.z - r.summary.bounds_min.z == 3.0);
    assert_true(r.summary.bounds_max.y - r.summary.bounds_min.y == 1.0);
    bg_scene_destroy(s);

    bg_scenefile_desc d = {.up_axis = BG_SCENEFILE_UP_Z};
    s = load_ok("tests/data/zup_tower.obj", &d, &r);
    assert_true(r.summary.bounds_min.y == 0.0 && r.summary.bounds_max.y == 3.0);
    assert_true(r.summary.bounds_max.z - r.summary.bounds_min.z == 1.0);
    assert_true(near(r.camera.look_at, 0, 1.5, 0));
    /* Its foot is in the lower half of the frame and its top in the upper: it stands upright. */
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    render(s, &r, px);
    int top = H, bottom = -1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (px[4 * (y * W + x)] || px[4 * (y * W + x) + 1]) {
                top = y < top ? y : top;
                bottom = y > bottom ? y : bottom;
            }
    if (!(bottom - top > H / 2))
        fail_msg("the standing tower covers rows %d .. %d of %d", top, bottom, H);
    free(px);
    bg_scene_destroy(s);

    /* -z: upside down, standing on y in [-3, 0]; -y: turned over, x unchanged. */
    d.up_axis = BG_SCENEFILE_UP_NEG_Z;
    s = load_ok("tests/data/zup_tower.obj", &d, &r);
    assert_true(r.summary.bounds_min.y == -3.0 && r.summary.bounds_max.y == 0.0);
    bg_scene_destroy(s);
    d.up_axis = BG_SCENEFILE_UP_NEG_Y;
    s = load_ok("tests/data/zup_tower.obj", &d, &r);
    assert_true(r.summary.bounds_min.z == -3.0 && r.summary.bounds_max.z == 0.0);
    bg_scene_destroy(s);
}

/* The file's cameras turn with the model: the front camera at (0.3, 0.3, 4) looking down -z is,
 * with z up, at (0.3, 4, -0.3) looking down -y. */
static void a_files_camera_turns_with_its_model(void **state)
{
    (void)state;
    bg_scenefile_desc d = {.up_axis = BG_SCENEFILE_UP_Z};
    bg_scenefile_result r;
    bg_scene *s = load_ok("tests/data/two_cameras.gltf", &d, &r);
    assert_true(r.camera_from_file);
    if (!near(r.camera.position, 0.3, 4, -0.3))
        fail_msg("camera at (%g, %g, %g)", r.camera.position.x, r.camera.position.y, r.camera.position.z);
    assert_true(r.camera.look_at.y < 4 && fabs(r.camera.look_at.x - 0.3) < 1e-6);
    bg_scene_destroy(s);
}

/* two_cameras.gltf: camera 1 in front (z = 4, yfov 0.7), camera 2 at the side (x = 4, looking down
 * -x, yfov 0.5). 0 is the first; a number beyond the file's count is refused with the count. */
static void camera_number_picks_the_files_camera(void **state)
{
    (void)state;
    const double deg = 180 / 3.14159265358979323846;
    bg_scenefile_result r;
    bg_scene *s = load_ok("tests/data/two_cameras.gltf", NULL, &r);
    assert_int_equal(r.file_cameras, 2);
    assert_int_equal(r.camera_number, 1);
    assert_true(near(r.camera.position, 0.3, 0.3, 4));
    bg_scene_destroy(s);

    bg_scenefile_desc d = {.camera = 2};
    s = load_ok("tests/data/two_cameras.gltf", &d, &r);
    assert_int_equal(r.camera_number, 2);
    if (!near(r.camera.position, 4, 0.3, 0.3))
        fail_msg("camera 2 at (%g, %g, %g)", r.camera.position.x, r.camera.position.y, r.camera.position.z);
    assert_true(r.camera.look_at.x < 4 && fabs(r.camera.look_at.z - 0.3) < 1e-6);
    assert_true(fabs(r.camera.fov_y_degrees - 0.5 * deg) < 1e-4);
    /* Its aspect ratio 1 sets the image's. */
    assert_int_equal(r.image.width, r.image.height);
    bg_scene_destroy(s);

    d.camera = BG_SCENEFILE_CAMERA_FRAME;
    s = load_ok("tests/data/two_cameras.gltf", &d, &r);
    assert_false(r.camera_from_file);
    assert_int_equal(r.camera_number, 0);
    assert_int_equal(r.file_cameras, 2);
    assert_true(near(r.camera.look_at, 0.5, 0.5, 0.5));
    bg_scene_destroy(s);

    char message[1024];
    d.camera = 3;
    assert_int_equal(load("tests/data/two_cameras.gltf", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    if (!strstr(message, "desc->camera") || !strstr(message, "has 2 cameras"))
        fail_msg("%s", message);
    d.camera = 1;
    assert_int_equal(load("tests/data/tetra.ply", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    if (!strstr(message, "desc->camera") || !strstr(message, "no camera"))
        fail_msg("%s", message);
}

/* The caller's camera parts replace the chosen camera's, each alone; the framing camera fits the
 * model into the asked field of view. A camera left looking at itself is refused by name. */
static void the_callers_camera_parts_replace_the_files(void **state)
{
    (void)state;
    bg_vec3 from = bg_vec3_make(0, 0.3, 9), at = bg_vec3_make(0.3, 0.3, 0.3);
    bg_scenefile_desc d = {.look_from = &from};
    bg_scenefile_result r;
    bg_scene *s = load_ok("tests/data/two_cameras.gltf", &d, &r);
    assert_true(near(r.camera.position, 0, 0.3, 9));
    assert_true(r.camera.look_at.z < 4); /* the file camera's own point, one unit ahead of it */
    bg_scene_destroy(s);

    d = (bg_scenefile_desc){.look_at = &at, .fov_y_degrees = 30};
    s = load_ok("tests/data/two_cameras.gltf", &d, &r);
    assert_true(near(r.camera.position, 0.3, 0.3, 4) && near(r.camera.look_at, 0.3, 0.3, 0.3));
    assert_true(r.camera.fov_y_degrees == 30);
    bg_scene_destroy(s);

    /* A narrow and a wide framing camera both keep the bunny in the frame, the narrow one from
     * further away. */
    double dist[2];
    const double fovs[2] = {10, 90};
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    for (int i = 0; i < 2; i++) {
        d = (bg_scenefile_desc){.fov_y_degrees = fovs[i]};
        s = load_ok("tests/data/bunny.ply", &d, &r);
        assert_true(r.camera.fov_y_degrees == fovs[i]);
        bg_vec3 p = r.camera.position, c = r.camera.look_at;
        dist[i] = sqrt((p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y) + (p.z - c.z) * (p.z - c.z));
        render(s, &r, px);
        size_t lit = 0;
        for (size_t k = 0; k < (size_t)W * H; k++)
            lit += px[4 * k] || px[4 * k + 1] || px[4 * k + 2];
        if (lit < (size_t)W * H / 10 || lit > (size_t)W * H * 9 / 10)
            fail_msg("fov %g: %zu of %d pixels lit", fovs[i], lit, W * H);
        bg_scene_destroy(s);
    }
    free(px);
    assert_true(dist[0] > 5 * dist[1]);

    char message[1024];
    from = bg_vec3_make(0.3, 0.3, 0.3);
    d = (bg_scenefile_desc){.look_from = &from, .look_at = &at};
    assert_int_equal(load("tests/data/two_cameras.gltf", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    if (!strstr(message, "desc->look_from and desc->look_at") || !strstr(message, "its own position"))
        fail_msg("%s", message);
    /* Straight down along the camera's up. */
    from = bg_vec3_make(0.3, 5, 0.3);
    assert_int_equal(load("tests/data/two_cameras.gltf", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    if (!strstr(message, "along the camera's up"))
        fail_msg("%s", message);
    /* A JSON scene's camera is replaced the same way. */
    bg_scene *js = NULL;
    assert_int_equal(bg_scene_create(NULL, &js), BG_OK);
    from = bg_vec3_make(1, 2, 3);
    d = (bg_scenefile_desc){.look_from = &from, .fov_y_degrees = 20};
    assert_int_equal(bg_scenefile_load_string("{\"camera\": {\"position\": [0, 0, 5]}}", &d, js, &r, message,
                                              sizeof message),
                     BG_OK);
    assert_true(near(r.camera.position, 1, 2, 3) && r.camera.fov_y_degrees == 20);
    assert_int_equal(r.file_cameras, 1);
    bg_scene_destroy(js);

    /* The lens likewise, each part alone; 0 is a value asked for, not "the file's": it turns the
     * file's lens into a pinhole. */
    const char *lens = "{\"camera\": {\"aperture_radius\": 0.25, \"focus_distance\": 6}}";
    const double zero = 0.0, focus = 2.5;
    d = (bg_scenefile_desc){.aperture_radius = &zero};
    assert_int_equal(bg_scene_create(NULL, &js), BG_OK);
    assert_int_equal(bg_scenefile_load_string(lens, &d, js, &r, message, sizeof message), BG_OK);
    assert_true(r.camera.aperture_radius == 0 && r.camera.focus_distance == 6);
    bg_scene_destroy(js);
    d = (bg_scenefile_desc){.focus_distance = &focus};
    assert_int_equal(bg_scene_create(NULL, &js), BG_OK);
    assert_int_equal(bg_scenefile_load_string(lens, &d, js, &r, message, sizeof message), BG_OK);
    assert_true(r.camera.aperture_radius == 0.25 && r.camera.focus_distance == 2.5);
    bg_scene_destroy(js);
    /* A model's camera (here the framing one) takes the lens as well. */
    d = (bg_scenefile_desc){.aperture_radius = &focus, .focus_distance = &zero};
    s = load_ok("tests/data/tetra.ply", &d, &r);
    assert_true(r.camera.aperture_radius == 2.5 && r.camera.focus_distance == 0);
    bg_scene_destroy(s);
}

/* Bad values are refused by their field before any file is read; the model options are refused for
 * a JSON scene. */
static void bad_values_are_refused_by_field(void **state)
{
    (void)state;
    static const struct {
        bg_scenefile_desc d;
        const char *field;
    } bad[] = {
        {{.up_axis = (bg_scenefile_up)99}, "desc->up_axis"},
        {{.smooth_angle_degrees = -1}, "desc->smooth_angle_degrees"},
        {{.smooth_angle_degrees = 181}, "desc->smooth_angle_degrees"},
        {{.camera = -2}, "desc->camera"},
        {{.fov_y_degrees = 180}, "desc->fov_y_degrees"},
        {{.fov_y_degrees = -5}, "desc->fov_y_degrees"},
    };
    char message[1024];
    bg_scene *s = NULL;
    bg_scenefile_result r;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(load("tests/data/tetra.ply", &bad[i].d, &s, &r, message, sizeof message),
                         BG_ERR_INVALID_ARGUMENT);
        if (!strstr(message, bad[i].field))
            fail_msg("%s: %s", bad[i].field, message);
    }
    bg_vec3 nan3 = bg_vec3_make(NAN, 0, 0);
    bg_scenefile_desc d = {.look_at = &nan3};
    assert_int_equal(load("tests/data/tetra.ply", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc->look_at: must be finite"));
    const double negative = -0.5, infinite = INFINITY;
    d = (bg_scenefile_desc){.aperture_radius = &negative};
    assert_int_equal(load("tests/data/tetra.ply", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc->aperture_radius: must be finite and >= 0 (got -0.5)"));
    d = (bg_scenefile_desc){.focus_distance = &infinite};
    assert_int_equal(load("tests/data/tetra.ply", &d, &s, &r, message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc->focus_distance: must be finite and >= 0"));

    const bg_scenefile_desc model_only[] = {{.up_axis = BG_SCENEFILE_UP_Z}, {.smooth_angle_degrees = 30},
                                            {.camera = 1}};
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        assert_int_equal(bg_scenefile_load_string("{}", &model_only[i], s, &r, message, sizeof message),
                         BG_ERR_INVALID_ARGUMENT);
        if (!strstr(message, "applies to model files only"))
            fail_msg("%s", message);
        bg_scene_destroy(s);
    }
}

static bool parallel(const float *n, double x, double y, double z)
{
    double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    double l2 = sqrt(x * x + y * y + z * z);
    return len > 0 && fabs((n[0] * x + n[1] * y + n[2] * z) / (len * l2) - 1) < 1e-6;
}

/* The cube [-1, 1]^3 as 8 shared corners and 12 triangles. Fully smooth (180), the corners stay 8,
 * each with one normal pointing out of it; creased at 60 degrees, every corner splits into its
 * three faces' copies (24 vertices), each corner of a triangle with its face's normal. */
static void a_crease_keeps_a_cubes_faces_flat(void **state)
{
    (void)state;
    static const float corners[24] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                      -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
    static const uint32_t quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                         {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    static const double face_normal[6][3] = {{0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
    for (int pass = 0; pass < 2; pass++) {
        double angle = pass == 0 ? 180 : 60;
        float *p = malloc(sizeof corners), *uv = malloc(8 * 2 * sizeof *uv), *n = NULL;
        assert_true(p && uv);
        memcpy(p, corners, sizeof corners);
        for (int v = 0; v < 8; v++)
            uv[2 * v] = (float)v, uv[2 * v + 1] = 0.5f;
        uint32_t idx[36];
        for (int f = 0; f < 6; f++) {
            const uint32_t *q = quads[f];
            uint32_t tri[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
            memcpy(&idx[6 * f], tri, sizeof tri);
        }
        size_t nv = 8;
        assert_int_equal(bgi_sf_crease_normals(&p, &uv, &nv, idx, 12, angle, &n), BG_OK);
        assert_int_equal(nv, pass == 0 ? 8 : 24);
        for (int i = 0; i < 36; i++) {
            int f = i / 6, original = (int)quads[f][(int[]){0, 1, 2, 0, 2, 3}[i % 6]];
            const float *np = &n[3 * idx[i]], *pp = &p[3 * idx[i]];
            /* Each corner keeps its position and its texture coordinates, copied or not. */
            assert_memory_equal(pp, &corners[3 * original], 3 * sizeof *pp);
            assert_true(uv[2 * idx[i]] == (float)original);
            /* Fully smooth, a corner's normal points out of its corner (area-weighted, so not
             * along the diagonal: the triangulation gives one face two triangles there and another
             * one), and every triangle at a corner shares it. */
            bool ok = pass == 0 ? pp[0] * np[0] > 0 && pp[1] * np[1] > 0 && pp[2] * np[2] > 0 &&
                                      memcmp(np, &n[3 * original], 3 * sizeof *np) == 0
                                : parallel(np, face_normal[f][0], face_normal[f][1], face_normal[f][2]);
            if (!ok)
                fail_msg("angle %g, corner %d of face %d: normal (%g, %g, %g)", angle, i, f, np[0], np[1], np[2]);
        }
        free(p);
        free(uv);
        free(n);
    }
}

/* The largest step between neighbouring pixels in the middle of the frame (green channel), away
 * from the rim, where the light grazes and shadow rays meet the facets whatever the normals. */
static int largest_step(const unsigned char *px)
{
    int most = 0;
    for (int y = H / 2 - 4; y < H / 2 + 4; y++)
        for (int x = W / 2 - 11; x < W / 2 + 12; x++) {
            const unsigned char *a = &px[4 * (y * W + x - 1)], *b = &px[4 * (y * W + x)];
            if (!(a[1] && b[1]))
                continue;
            int step = abs((int)a[1] - (int)b[1]);
            most = step > most ? step : most;
        }
    return most;
}

/* ico_no_normals.ply (80 flat faces) without smoothing shows its facets: steps between pixels at
 * their edges. Smoothed, the shade runs in a gradient with small steps only. The cube under a
 * 60-degree crease renders as its flat self, and smoothed fully it does not. */
static void smoothing_shades_a_faceted_sphere_and_keeps_a_cube(void **state)
{
    (void)state;
    unsigned char *flat = malloc((size_t)W * H * 4), *smooth = malloc((size_t)W * H * 4);
    assert_true(flat && smooth);
    bg_scenefile_result r;
    bg_scene *s = load_ok("tests/data/ico_no_normals.ply", NULL, &r);
    render(s, &r, flat);
    bg_scene_destroy(s);
    bg_scenefile_desc d = {.smooth_angle_degrees = 180};
    s = load_ok("tests/data/ico_no_normals.ply", &d, &r);
    assert_int_equal(r.summary.vertices, 42);
    render(s, &r, smooth);
    bg_scene_destroy(s);
    int flat_step = largest_step(flat), smooth_step = largest_step(smooth);
    print_message("ico sphere: largest step %d flat, %d smooth\n", flat_step, smooth_step);
    if (!(flat_step >= 20 && smooth_step * 2 <= flat_step))
        fail_msg("largest step %d flat, %d smooth", flat_step, smooth_step);

    s = load_ok("tests/data/cube_no_normals.ply", NULL, &r);
    render(s, &r, flat);
    bg_scene_destroy(s);
    d.smooth_angle_degrees = 60;
    s = load_ok("tests/data/cube_no_normals.ply", &d, &r);
    render(s, &r, smooth);
    bg_scene_destroy(s);
    int most = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        most = abs((int)flat[i] - (int)smooth[i]) > most ? abs((int)flat[i] - (int)smooth[i]) : most;
    if (most > 2)
        fail_msg("the creased cube differs from the flat one by %d", most);
    d.smooth_angle_degrees = 180;
    s = load_ok("tests/data/cube_no_normals.ply", &d, &r);
    render(s, &r, smooth);
    bg_scene_destroy(s);
    most = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        most = abs((int)flat[i] - (int)smooth[i]) > most ? abs((int)flat[i] - (int)smooth[i]) : most;
    if (most < 20)
        fail_msg("the fully smoothed cube differs from the flat one by only %d", most);
    free(flat);
    free(smooth);
}

/* settings.integrator and settings.path_ambient reach bg_scenefile_result.settings as written; absent,
 * they are bg_render_settings_init()'s. path_ambient is kept under "whitted" too, for a caller that
 * switches to path (test_scenefile_errors holds the bad values). */
static void the_settings_choose_the_integrator(void **state)
{
    (void)state;
    static const struct {
        const char *settings;
        bg_integrator integrator;
        bool path_ambient;
    } cases[] = {
        {"{}", BG_INTEGRATOR_WHITTED, false},
        {"{\"integrator\": \"whitted\"}", BG_INTEGRATOR_WHITTED, false},
        {"{\"integrator\": \"path\"}", BG_INTEGRATOR_PATH, false},
        {"{\"integrator\": \"path\", \"path_ambient\": true}", BG_INTEGRATOR_PATH, true},
        {"{\"path_ambient\": true, \"integrator\": \"path\", \"max_depth\": 7}", BG_INTEGRATOR_PATH, true},
        {"{\"integrator\": \"path\", \"path_ambient\": false}", BG_INTEGRATOR_PATH, false},
        {"{\"path_ambient\": true}", BG_INTEGRATOR_WHITTED, true},
    };
    bg_render_settings defaults = bg_render_settings_init();
    assert_int_equal(defaults.integrator, BG_INTEGRATOR_WHITTED);
    assert_false(defaults.path_ambient);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char json[256], message[512];
        snprintf(json, sizeof json, "{\"settings\": %s, \"objects\": [{\"sphere\": {}}]}", cases[i].settings);
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        bg_scenefile_result r;
        if (bg_scenefile_load_string(json, NULL, s, &r, message, sizeof message) != BG_OK)
            fail_msg("%s: %s", json, message);
        if (r.settings.integrator != cases[i].integrator || r.settings.path_ambient != cases[i].path_ambient)
            fail_msg("%s: integrator %d, path_ambient %d", json, (int)r.settings.integrator,
                     (int)r.settings.path_ambient);
        /* The rest of the settings stay the defaults the file does not change. */
        assert_true(r.settings.min_weight == defaults.min_weight);
        assert_int_equal(r.settings.encoding, defaults.encoding);
        bg_scene_destroy(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_z_up_model_stands_on_y),
        cmocka_unit_test(a_files_camera_turns_with_its_model),
        cmocka_unit_test(camera_number_picks_the_files_camera),
        cmocka_unit_test(the_callers_camera_parts_replace_the_files),
        cmocka_unit_test(bad_values_are_refused_by_field),
        cmocka_unit_test(a_crease_keeps_a_cubes_faces_flat),
        cmocka_unit_test(smoothing_shades_a_faceted_sphere_and_keeps_a_cube),
        cmocka_unit_test(the_settings_choose_the_integrator),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
