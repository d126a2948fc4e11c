/* Model files through the scene-file library: the small models of tests/data (an OBJ with its MTL,
 * a PLY, an STL, a glTF 2.0 with an embedded buffer) load with the counts they were written with and
 * render; the glTF brings its camera and light, the others get a camera framing them and a light;
 * a scene file places a model with its own transform and material. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"
#include "util_gpu.h"
#include "util_warnings.h"
#include "scenefile/scenefile_internal.h"

enum { W = 64, H = 48 };

static bg_scene *load(const char *path, bg_scenefile_result *r)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    char message[1024];
    bg_status st = bg_scenefile_load_any(path, NULL, s, r, message, sizeof message);
    if (st != BG_OK)
        fail_msg("%s: %s", path, message);
    return s;
}

/* Renders at W x H (the aspect of the file's camera does not matter for coverage) into out
 * (W * H * 4 bytes) and returns how many pixels are not the background. */
static size_t render(bg_scene *s, const bg_scenefile_result *r, unsigned char *out)
{
    bg_image im = {W, H, BG_PIXEL_RGBA8, 0, out};
    assert_int_equal(bg_render_cpu(s, &r->settings, &im), BG_OK);
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        n += out[4 * i] || out[4 * i + 1] || out[4 * i + 2];
    return n;
}

typedef struct model_case {
    const char *path;
    size_t meshes;
    uint64_t triangles, vertices;
    size_t materials;
} model_case;

/* Vertex counts after assimp's joining of identical vertices: the OBJ's 8 cube corners and 4 floor
 * corners, the PLY's 4, the STL's 12 (each facet carries its own normal, so no corner is shared). */
static const model_case models[] = {
    {"tests/data/two_boxes.obj", 2, 14, 12, 2},
    {"tests/data/tetra.ply", 1, 4, 4, 1},
    {"tests/data/tetra.stl", 1, 4, 12, 1},
    {"tests/data/tetra_pair.gltf", 2, 8, 8, 1},
    {"tests/data/bunny.ply", 1, 3674, 1839, 1},
};

static void every_model_loads_with_its_counts_and_renders(void **state)
{
    (void)state;
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    for (size_t i = 0; i < sizeof models / sizeof models[0]; i++) {
        const model_case *m = &models[i];
        bg_scenefile_result r;
        bg_scene *s = load(m->path, &r);
        if (r.summary.meshes != m->meshes || r.summary.triangles != m->triangles || r.summary.vertices != m->vertices ||
            r.summary.materials != m->materials)
            fail_msg("%s: %zu meshes, %llu triangles, %llu vertices, %zu materials; expected %zu, %llu, %llu, %zu",
                     m->path, r.summary.meshes, (unsigned long long)r.summary.triangles,
                     (unsigned long long)r.summary.vertices, r.summary.materials, m->meshes,
                     (unsigned long long)m->triangles, (unsigned long long)m->vertices, m->materials);
        assert_int_equal(r.summary.objects, m->meshes);
        assert_int_equal(r.summary.lights, 1);
        assert_true(r.summary.bounded);
        size_t lit = render(s, &r, px);
        /* The model covers a good part of the frame, and not all of it (it is framed, not filled). */
        if (lit < (size_t)W * H / 20 || lit == (size_t)W * H)
            fail_msg("%s: %zu of %d pixels lit", m->path, lit, W * H);
        print_message("%s: %zu meshes, %llu triangles, %llu vertices; %zu of %d pixels lit\n", m->path,
                      r.summary.meshes, (unsigned long long)r.summary.triangles,
                      (unsigned long long)r.summary.vertices, lit, W * H);
        bg_scene_destroy(s);
    }
    free(px);
}

static void a_model_without_camera_or_light_gets_defaults(void **state)
{
    (void)state;
    bg_scenefile_result r;
    bg_scene *s = load("tests/data/two_boxes.obj", &r);
    assert_false(r.camera_from_file);
    assert_false(r.lights_from_file);
    /* The floor's map_Kd, a PNG beside the shipped scenes, found relative to the MTL file. */
    assert_int_equal(r.summary.textures, 1);
    /* Framed: the camera looks at the centre of the bounds (the floor's [-3, 3]^2 and the cube's
     * height 1) from outside them. */
    assert_true(r.camera.look_at.x == 0.0 && r.camera.look_at.y == 0.5 && r.camera.look_at.z == 0.0);
    double d = sqrt(pow(r.camera.position.x, 2) + pow(r.camera.position.y - 0.5, 2) + pow(r.camera.position.z, 2));
    assert_true(d > sqrt(3 * 3 + 0.5 * 0.5 + 3 * 3));
    /* MTL: the cube's Kd is red and its Ks gives it a coat; the centre of the frame is the cube. */
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    render(s, &r, px);
    const unsigned char *c = px + ((size_t)(H / 2) * W + W / 2) * 4;
    if (!(c[0] > c[1] + 40 && c[0] > c[2] + 40))
        fail_msg("the cube's centre pixel is (%d, %d, %d), not red", c[0], c[1], c[2]);
    free(px);
    bg_scene_destroy(s);
}

static void a_gltf_brings_its_camera_and_light(void **state)
{
    (void)state;
    bg_scenefile_result r;
    bg_scene *s = load("tests/data/tetra_pair.gltf", &r);
    assert_true(r.camera_from_file);
    assert_true(r.lights_from_file);
    /* The camera node: translation (0.75, 0.4, 4), looking down -z; yfov 0.7 rad, aspect 1.5. */
    assert_true(fabs(r.camera.position.x - 0.75) < 1e-6 && fabs(r.camera.position.z - 4) < 1e-6);
    assert_true(r.camera.look_at.z < r.camera.position.z);
    assert_true(fabs(r.camera.fov_y_degrees - 0.7 * 180 / 3.14159265358979) < 1e-4);
    assert_int_equal(r.image.width, 640);
    assert_int_equal(r.image.height, 427);
    /* Two nodes show one mesh: the second is an instance, 1.5 to the right. */
    assert_int_equal(r.summary.meshes, 2);
    assert_true(fabs(r.summary.bounds_max.x - 2.5) < 1e-6);
    bg_scene_destroy(s);
}

/* tests/data/tetra_pair.gltf's camera (yfov 0.7, aspect 1.5) as each assimp hands it over: 5.2.5
 * (Debian 12) gives mHorizontalFOV 1.05 = yfov * aspect; 5.3 and later (6.0.5 on Debian unstable)
 * 2 atan(1.5 tan 0.35), the full horizontal angle, which read by 5.2's rule gave 38.27 degrees
 * instead of 40.11. Both must give back the file's 0.7 rad, whichever assimp runs the suite. */
static void gltf_field_of_view_on_every_assimp(void **state)
{
    (void)state;
    const double yfov = 0.7, aspect = 1.5;
    const float assimp_5_2 = (float)(yfov * aspect);
    const float assimp_6 = (float)(2.0 * atan(aspect * tan(yfov / 2.0)));
    assert_true(fabs(bgi_sf_gltf_fov_y(assimp_5_2, aspect, 5, 2) - yfov) < 1e-6);
    assert_true(fabs(bgi_sf_gltf_fov_y(assimp_6, aspect, 6, 0) - yfov) < 1e-6);
    assert_true(fabs(bgi_sf_gltf_fov_y(assimp_6, aspect, 5, 3) - yfov) < 1e-6);
    /* The old rule on the new value is the fault that was seen. */
    assert_true(fabs(bgi_sf_gltf_fov_y(assimp_6, aspect, 5, 2) * 180 / 3.14159265358979 - 38.27) < 0.005);
    /* Without an aspect ratio every version passes yfov through. */
    assert_true(bgi_sf_gltf_fov_y(0.7, 0.0, 5, 2) == 0.7 && bgi_sf_gltf_fov_y(0.7, 0.0, 6, 0) == 0.7);
}

static void a_scene_file_places_a_model(void **state)
{
    (void)state;
    static const char json[] =
        "{\"materials\": {\"gold\": {\"base\": {\"reflectance\": [0.9, 0.7, 0.2], \"roughness\": 0.3}}},"
        " \"objects\": [{\"mesh\": {\"file\": \"tetra.ply\", \"normals\": \"flat\"}, \"material\": \"gold\","
        "   \"transform\": [{\"scale\": 2}, {\"translate\": [10, 0, 0]}], \"casts_shadows\": false},"
        "  {\"mesh\": {\"file\": \"two_boxes.obj\"}}],"
        " \"camera\": {\"position\": [11, 2, 4], \"look_at\": [11, 0.5, 0]},"
        " \"lights\": [{\"position\": [11, 5, 5]}]}";
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_desc d = {.base_dir = "tests/data", .name = "placed.json"};
    bg_scenefile_result r;
    char message[1024];
    if (bg_scenefile_load_string(json, &d, s, &r, message, sizeof message) != BG_OK)
        fail_msg("%s", message);
    assert_int_equal(r.summary.meshes, 3);
    assert_int_equal(r.summary.triangles, 4 + 14);
    /* The given material replaces the file's (none for the PLY): gold, plus the OBJ's two. */
    assert_int_equal(r.summary.materials, 3);
    assert_true(r.summary.bounds_max.x == 12.0 && r.summary.bounds_min.x == -3.0);
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    assert_true(render(s, &r, px) > (size_t)W * H / 20);
    free(px);
    bg_scene_destroy(s);
}

static bg_status load_text_as(const char *suffix, const char *text, char *message, size_t size)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/bg_scenefile_%ld%s", (long)getpid(), suffix);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    bg_status st = bg_scenefile_load_model(path, NULL, s, &r, message, size);
    remove(path);
    bg_scene_destroy(s);
    assert_non_null(strstr(message, path));
    return st;
}

/* Model files that exist but are not models, or hold nothing to render, are bad input naming the
 * file and the reason (assimp's, where it gives one); a missing one is BG_ERR_IO. */
static void a_broken_model_is_refused(void **state)
{
    (void)state;
    char message[1024];
    assert_int_equal(load_text_as(".stl", "garbage garbage\n\x01\x02", message, sizeof message), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "cannot read model file"));
    assert_int_equal(load_text_as(".ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0\n1\n2\n",
                                  message, sizeof message),
                     BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "contains no faces"));
    assert_int_equal(load_text_as(".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n", message, sizeof message),
                     BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "holds no triangles"));
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    assert_int_equal(bg_scenefile_load_model("tests/data/none.obj", NULL, s, &r, message, sizeof message), BG_ERR_IO);
    assert_non_null(strstr(message, "tests/data/none.obj: model file \"tests/data/none.obj\": cannot open: "));
    bg_scene_destroy(s);
}


static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* What the MTL mapping leaves out it says, to the logger: a colour texture in a format not read (a
 * WebP), every map other than the colour one, and a texture file that is missing (the material keeps
 * its factors, as model viewers render it). */
static void model_materials_say_what_they_leave_out(void **state)
{
    (void)state;
    char obj[64], mtl[64];
    snprintf(obj, sizeof obj, "/tmp/bg_sf_%ld.obj", (long)getpid());
    snprintf(mtl, sizeof mtl, "/tmp/bg_sf_%ld.mtl", (long)getpid());
    char text[256];
    snprintf(text, sizeof text, "mtllib %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n", strrchr(mtl, '/') + 1);
    write_file(obj, text);
    char webp[64];
    snprintf(webp, sizeof webp, "/tmp/bg_sf_%ld.webp", (long)getpid());
    write_file(webp, "RIFF\x1a\x01\x01\x01WEBPVP8 ");
    char mtl_text[256];
    snprintf(mtl_text, sizeof mtl_text, "newmtl m\nKd 1 1 1\nmap_Kd %s\nmap_Bump bump.png\n", strrchr(webp, '/') + 1);
    write_file(mtl, mtl_text);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    util_warnings w = {0, ""};
    bg_scenefile_desc d = {.logger = {util_warnings_collect, &w}};
    bg_scenefile_result r;
    char message[1024];
    bg_status st = bg_scenefile_load_model(obj, &d, s, &r, message, sizeof message);
    bg_scene_destroy(s);
    if (st != BG_OK)
        fail_msg("%s", message);
    remove(webp);
    if (w.count != 2 || !strstr(w.all, "material \"m\": its base colour texture \"bg_sf_") ||
        !strstr(w.all, ".webp\" is left out (WebP images are not read; PNG and JPEG are)") ||
        !strstr(w.all, "its normal (or bump) map is left out: the renderers shade with the mesh's interpolated "
                       "normals and have no normal mapping"))
        fail_msg("%d warnings:\n%s", w.count, w.all);

    write_file(mtl, "newmtl m\nKd 1 1 1\nmap_Kd no_such_texture.png\n");
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    util_warnings missing = {0, ""};
    d.logger.user = &missing;
    st = bg_scenefile_load_model(obj, &d, s, &r, message, sizeof message);
    bg_scene_destroy(s);
    remove(obj);
    remove(mtl);
    if (st != BG_OK)
        fail_msg("%s", message);
    print_message("%s", missing.all);
    assert_int_equal(r.summary.textures, 0);
    assert_int_equal(missing.count, 1);
    assert_non_null(strstr(missing.all, "material \"m\": its base colour texture file \"/tmp/no_such_texture.png\" "
                                        "is missing; the material keeps its factors"));
}

/* Texture paths as Windows exporters write them: ".\\tex.png" and "maps\\tex.png" resolve beside the
 * model, and a drive path ("C:\\art\\tex.png") is looked for beside it by its file name, with a
 * warning. Each loads the texture (the summary counts it). */
static void windows_texture_paths_resolve_beside_the_model(void **state)
{
    (void)state;
    char dir[] = "/tmp/bg_sf_win_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128], maps[128];
    snprintf(maps, sizeof maps, "%s/maps", dir);
    assert_int_equal(mkdir(maps, 0700), 0);
    unsigned char texel[4 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    bg_image image = {2, 2, BG_PIXEL_RGBA8, 0, texel};
    snprintf(path, sizeof path, "%s/tex.png", dir);
    assert_int_equal(bg_png_save(path, &image, NULL, 0), BG_OK);
    snprintf(path, sizeof path, "%s/maps/tex.png", dir);
    assert_int_equal(bg_png_save(path, &image, NULL, 0), BG_OK);
    static const struct {
        const char *map;
        int warnings;
    } cases[] = {{".\\tex.png", 0}, {".\\.\\tex.png", 0}, {"maps\\tex.png", 0}, {".\\maps\\tex.png", 0},
                 {"C:\\art\\tex.png", 1}};
    char obj[128], mtl[128], text[256];
    snprintf(obj, sizeof obj, "%s/m.obj", dir);
    snprintf(mtl, sizeof mtl, "%s/m.mtl", dir);
    write_file(obj, "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n");
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(text, sizeof text, "newmtl m\nKd 1 1 1\nmap_Kd %s\n", cases[i].map);
        write_file(mtl, text);
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        util_warnings w = {0, ""};
        bg_scenefile_desc d = {.logger = {util_warnings_collect, &w}};
        bg_scenefile_result r;
        char message[1024];
        bg_status st = bg_scenefile_load_model(obj, &d, s, &r, message, sizeof message);
        bg_scene_destroy(s);
        if (st != BG_OK)
            fail_msg("map_Kd %s: %s", cases[i].map, message);
        if (r.summary.textures != 1 || w.count != cases[i].warnings)
            fail_msg("map_Kd %s: %d textures (want 1), %d warnings (want %d):\n%s", cases[i].map,
                     (int)r.summary.textures, w.count, cases[i].warnings, w.all);
        if (cases[i].warnings)
            assert_non_null(strstr(w.all, "is a path on another system's drive; it is looked for beside the model"));
    }
    remove(obj);
    remove(mtl);
    remove(path);
    snprintf(path, sizeof path, "%s/tex.png", dir);
    remove(path);
    rmdir(maps);
    rmdir(dir);
}

/* An STL repeats every corner for each face (24 vertices for an octahedron's 8 faces, each with its
 * facet normal): smoothing welds them first, so the command's smooth angle (--smooth) and a JSON
 * mesh's "normals": "smooth" both give the 6 shared vertices and the same image, which differs from
 * the faceted one. Before the weld, --smooth left an STL byte-identical. */
static void stl_smoothing_welds_its_vertices(void **state)
{
    (void)state;
    static const double v[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    char dir[] = "/tmp/bg_sf_stl_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char stl[128], text[4096];
    snprintf(stl, sizeof stl, "%s/octa.stl", dir);
    size_t n = (size_t)snprintf(text, sizeof text, "solid octa\n");
    for (int t = 0; t < 8; t++) {
        const double *a = v[f[t][0]], *b = v[f[t][1]], *c = v[f[t][2]];
        double nx = a[0] + b[0] + c[0], ny = a[1] + b[1] + c[1], nz = a[2] + b[2] + c[2];
        double len = sqrt(nx * nx + ny * ny + nz * nz);
        n += (size_t)snprintf(text + n, sizeof text - n, "facet normal %g %g %g\nouter loop\n", nx / len, ny / len,
                              nz / len);
        for (int k = 0; k < 3; k++)
            n += (size_t)snprintf(text + n, sizeof text - n, "vertex %g %g %g\n", v[f[t][k]][0], v[f[t][k]][1],
                                  v[f[t][k]][2]);
        n += (size_t)snprintf(text + n, sizeof text - n, "endloop\nendfacet\n");
    }
    snprintf(text + n, sizeof text - n, "endsolid octa\n");
    write_file(stl, text);
    enum { W = 48, H = 36 };
    unsigned char *image[3];
    size_t vertices[3];
    for (int way = 0; way < 3; way++) {
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        bg_scenefile_result r;
        char message[1024];
        bg_status st;
        if (way < 2) { /* the file as it is, then with the command's smooth angle */
            bg_scenefile_desc d = {.smooth_angle_degrees = way == 1 ? 180.0 : 0.0};
            st = bg_scenefile_load_model(stl, &d, s, &r, message, sizeof message);
        } else { /* a JSON scene's key, with the camera the model load framed */
            char json[512];
            snprintf(json, sizeof json, "{\"camera\": {\"position\": [2.2, 1.6, 3.0], \"look_at\": [0, 0, 0]},"
                     "\"lights\": [{\"position\": [3, 4, 5]}],"
                     "\"objects\": [{\"mesh\": {\"file\": \"%s\", \"normals\": \"smooth\"}}]}", stl);
            st = bg_scenefile_load_string(json, NULL, s, &r, message, sizeof message);
        }
        if (st != BG_OK)
            fail_msg("way %d: %s", way, message);
        vertices[way] = (size_t)r.summary.vertices;
        bg_render_settings set = r.settings;
        if (way < 2) {
            /* The same view as the JSON scene's, so that images compare. */
            bg_camera cam = bg_camera_init();
            cam.position = bg_vec3_make(2.2, 1.6, 3.0);
            cam.look_at = bg_vec3_make(0, 0, 0);
            assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
            assert_int_equal(bg_scene_commit(s), BG_OK);
        }
        set.samples = 1;
        image[way] = util_cpu_reference(s, &set, W, H);
        bg_scene_destroy(s);
    }
    print_message("vertices: file %zu, --smooth %zu, \"smooth\" %zu\n", vertices[0], vertices[1], vertices[2]);
    assert_int_equal(vertices[0], 24);
    assert_int_equal(vertices[1], 6);
    assert_int_equal(vertices[2], 6);
    assert_true(memcmp(image[0], image[1], (size_t)W * H * 4) != 0);
    remove(stl);
    rmdir(dir);
    for (int way = 0; way < 3; way++)
        free(image[way]);
}

/* An orthographic glTF camera (xmag 2.4, ymag 1.6) stays orthographic: its half-height is ymag and
 * the image takes its aspect xmag / ymag. Before, it became a 45-degree perspective camera without a
 * word. A JSON camera says the same with "projection" and "half_height"; a lens on it, a bad name or
 * a half-height of 0 is refused by its path, and so is a field of view asked of it (the command's
 * --fov), which it would ignore. */
static void orthographic_cameras_load(void **state)
{
    (void)state;
    bg_scenefile_result r;
    bg_scene *s = load("tests/data/tetra_ortho.gltf", &r);
    assert_true(r.camera_from_file);
    assert_int_equal(r.camera.projection, BG_PROJECTION_ORTHOGRAPHIC);
    assert_true(fabs(r.camera.half_height - 1.6) < 1e-6);
    assert_int_equal(r.image.width, 640);
    assert_int_equal(r.image.height, 427);
    bg_scene_destroy(s);
    bg_scenefile_desc fov = {0};
    fov.fov_y_degrees = 30.0;
    char why[512];
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_status fov_st = bg_scenefile_load_any("tests/data/tetra_ortho.gltf", &fov, s, &r, why, sizeof why);
    bg_scene_destroy(s);
    print_message("%s\n", why);
    if (fov_st != BG_ERR_INVALID_ARGUMENT || !strstr(why, "desc->fov_y_degrees: the camera is orthographic"))
        fail_msg("a field of view on an orthographic camera: status %d, \"%s\"", fov_st, why);

    static const char ok[] = "{\"camera\": {\"position\": [0, 0, 5], \"projection\": \"orthographic\", "
                             "\"half_height\": 2.5}, \"objects\": [{\"sphere\": {}}]}";
    char message[1024];
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (bg_scenefile_load_string(ok, NULL, s, &r, message, sizeof message) != BG_OK)
        fail_msg("%s", message);
    assert_int_equal(r.camera.projection, BG_PROJECTION_ORTHOGRAPHIC);
    assert_true(r.camera.half_height == 2.5);
    bg_scene_destroy(s);
    static const struct {
        const char *camera, *words;
    } bad[] = {
        {"\"projection\": \"fisheye\"", "camera.projection: \"fisheye\" is not one of \"perspective\", \"orthographic\""},
        {"\"projection\": \"orthographic\", \"half_height\": 0", "camera.half_height"},
        {"\"projection\": \"orthographic\", \"aperture_radius\": 0.2", "depth of field needs a perspective camera"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char json[256];
        snprintf(json, sizeof json, "{\"camera\": {%s}, \"objects\": [{\"sphere\": {}}]}", bad[i].camera);
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        bg_status st = bg_scenefile_load_string(json, NULL, s, &r, message, sizeof message);
        bg_scene_destroy(s);
        print_message("%s\n", message);
        if (st == BG_OK || !strstr(message, bad[i].words))
            fail_msg("%s: status %d, message \"%s\" lacks \"%s\"", bad[i].camera, st, message, bad[i].words);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_model_loads_with_its_counts_and_renders),
        cmocka_unit_test(a_model_without_camera_or_light_gets_defaults),
        cmocka_unit_test(a_gltf_brings_its_camera_and_light),
        cmocka_unit_test(gltf_field_of_view_on_every_assimp),
        cmocka_unit_test(orthographic_cameras_load),
        cmocka_unit_test(a_scene_file_places_a_model),
        cmocka_unit_test(a_broken_model_is_refused),
        cmocka_unit_test(model_materials_say_what_they_leave_out),
        cmocka_unit_test(windows_texture_paths_resolve_beside_the_model),
        cmocka_unit_test(stl_smoothing_welds_its_vertices),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
