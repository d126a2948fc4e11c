/* Primary visibility by rasterisation (bg_render_settings.primary): the fused tree plan's camera
 * rays take their first hit from the rasterised map, and the image is the walk's, float for float,
 * on a closed mesh with shared edges and instances beside analytic shapes, with several samples per
 * pixel, in a window of a larger frame, orthographic, and on many spheres; BG_PRIMARY_AUTO takes it
 * for a coarse mesh and not for spheres; where it cannot run, BG_PRIMARY_RASTER is refused by name. */
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
#include "scenes/meshes.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 96, H = 80 };

static uint32_t material(bg_scene *scene, double r, double g, double b, double mirror)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    m.base.roughness.value = mirror > 0.0 ? 0.0 : 1.0;
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_material(scene, &m, &id), BG_OK);
    return id;
}

/* An icosphere (every edge shared by two triangles), two more instances of it, a sphere that
 * cuts into one of them and a plane under all: ties on every shared edge and where sphere and mesh
 * meet, a mirror's bounce on the GPU's walk. */
static bg_scene *mesh_scene(mesh *m, int level)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    const double a[3] = {0.05, 0.05, 0.05};
    assert_int_equal(bg_scene_set_ambient(s, a), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(3.0, 4.0, 5.0);
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.3, 0.6, 3.2);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    c.fov_y_degrees = 45.0;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    memset(m, 0, sizeof *m);
    mesh_icosphere_desc d = {level, 0, true, false};
    char why[256];
    if (mesh_icosphere(&d, m, why, sizeof why) != BG_OK)
        fail_msg("icosphere: %s", why);
    uint32_t mat = material(s, 0.8, 0.8, 0.2, 0.0);
    bg_mesh_desc md = bg_mesh_desc_init(mat);
    md.positions = m->positions;
    md.vertex_count = m->vertex_count;
    md.indices = m->indices;
    md.triangle_count = m->triangle_count;
    md.normals = m->normals;
    md.transform = bg_mat4_mul(bg_mat4_translate(-0.7, 0.0, 0.0), bg_mat4_scale(0.4, 0.4, 0.4));
    uint32_t first = 0;
    assert_int_equal(bg_scene_add_mesh(s, &md, &first), BG_OK);
    bg_mat4 t = bg_mat4_mul(bg_mat4_translate(0.7, 0.0, 0.0), bg_mat4_scale(0.4, 0.4, 0.4));
    assert_int_equal(bg_scene_add_mesh_instance(s, first, &t, material(s, 0.2, 0.4, 0.9, 0.3), true, &id), BG_OK);
    t = bg_mat4_mul(bg_mat4_translate(0.0, 0.6, -0.5), bg_mat4_scale(0.3, 0.3, 0.3));
    assert_int_equal(bg_scene_add_mesh_instance(s, first, &t, mat, true, &id), BG_OK);
    bg_object_desc sp = bg_object_desc_init(BG_SHAPE_SPHERE, material(s, 0.9, 0.2, 0.2, 0.0));
    sp.transform = bg_mat4_mul(bg_mat4_translate(-0.45, 0.0, 0.3), bg_mat4_scale(0.25, 0.25, 0.25));
    assert_int_equal(bg_scene_add_object(s, &sp, &id), BG_OK);
    bg_object_desc pl = bg_object_desc_init(BG_SHAPE_PLANE, material(s, 0.6, 0.6, 0.6, 0.0));
    pl.transform = bg_mat4_translate(0.0, -0.45, 0.0);
    assert_int_equal(bg_scene_add_object(s, &pl, &id), BG_OK);
    if (bg_scene_commit(s) != BG_OK)
        fail_msg("bg_scene_commit: %s", bg_scene_error_message(s));
    return s;
}

/* The float image of s with settings set and primary visibility `primary`; its stats in *stats. */
static float *render(bg_scene *s, bg_render_settings set, bg_primary_visibility primary, int w, int h,
                     bg_render_stats *stats, const char *label)
{
    bg_renderer *r = util_renderer(util_fx.ctx);
    float *px = calloc((size_t)w * (size_t)h * 4, sizeof *px);
    assert_non_null(px);
    bg_image img = {w, h, BG_PIXEL_RGBA32F, 0, px};
    set.primary = primary;
    util_render_gpu(r, util_fx.ctx, s, &set, &img, label);
    bg_renderer_get_stats(r, stats);
    bg_renderer_destroy(r);
    return px;
}

/* Rasterised and walked camera rays give the same floats on every pixel, and the stats say which
 * ran; both plans' images within... the same: no pixel went to the CPU. */
static void expect_same(bg_scene *s, bg_render_settings set, int w, int h, const char *label)
{
    bg_render_stats walked, rastered;
    float *walk = render(s, set, BG_PRIMARY_WALK, w, h, &walked, label);
    float *raster = render(s, set, BG_PRIMARY_RASTER, w, h, &rastered, label);
    assert_int_equal(walked.plan, BG_PLAN_FUSED_TREE);
    assert_int_equal(rastered.plan, BG_PLAN_FUSED_TREE);
    if (walked.primary_raster || !rastered.primary_raster)
        fail_msg("%s: primary_raster is %d walking and %d rasterising", label, walked.primary_raster,
                 rastered.primary_raster);
    assert_int_equal(walked.fallback_pixels, 0);
    assert_int_equal(rastered.fallback_pixels, 0);
    size_t n = (size_t)w * (size_t)h * 4, differ = 0, first = n, lit = 0;
    for (size_t k = 0; k < n; k++) {
        if (memcmp(&walk[k], &raster[k], sizeof *walk) != 0) {
            differ++;
            if (first == n)
                first = k;
        }
        lit += walk[k] > 0.0f ? 1 : 0;
    }
    if (differ)
        fail_msg("%s: %zu of %zu floats differ, the first at pixel (%zu, %zu): walk %.9g, raster %.9g", label, differ, n,
                 first / 4 % (size_t)w, first / 4 / (size_t)w, walk[first], raster[first]);
    /* Not an empty frame on both sides. */
    if (lit < n / 8)
        fail_msg("%s: only %zu of %zu floats are lit", label, lit, n);
    free(walk);
    free(raster);
}

static bg_render_settings tree_settings(void)
{
    bg_render_settings set = bg_render_settings_init();
    set.gpu_plan = BG_PLAN_FUSED_TREE;
    return set;
}

static void mesh_instances_equal_the_walk(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    expect_same(s, tree_settings(), W, H, "mesh, instances, sphere, plane");
    bg_scene_destroy(s);
    mesh_free(&m);
}

/* Four samples per pixel: each sample's shift goes into the projection. */
static void samples_equal_the_walk(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    bg_render_settings set = tree_settings();
    set.samples = 4;
    expect_same(s, set, W, H, "4 samples");
    bg_scene_destroy(s);
    mesh_free(&m);
}

/* A window of a frame twice the size, off its centre. */
static void window_equals_the_walk(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    bg_render_settings set = tree_settings();
    set.frame_width = 2 * W;
    set.frame_height = 2 * H;
    set.window_x = W / 2 + 7;
    set.window_y = H / 3;
    expect_same(s, set, W, H, "window");
    bg_scene_destroy(s);
    mesh_free(&m);
}

static void orthographic_equals_the_walk(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.3, 0.6, 3.2);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    c.projection = BG_PROJECTION_ORTHOGRAPHIC;
    c.half_height = 1.0;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    expect_same(s, tree_settings(), W, H, "orthographic");
    bg_scene_destroy(s);
    mesh_free(&m);
}

/* A sphere beside the eye, whose box holds the eye: the box's six faces are drawn, not the three
 * that face an eye outside it. */
static void eye_inside_a_box_equals_the_walk(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    bg_object_desc sp = bg_object_desc_init(BG_SHAPE_SPHERE, material(s, 0.3, 0.9, 0.3, 0.0));
    sp.transform = bg_mat4_translate(-0.5, -0.2, 3.2); /* radius 1, the eye at (0.3, 0.6, 3.2) */
    uint32_t id;
    assert_int_equal(bg_scene_add_object(s, &sp, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    expect_same(s, tree_settings(), W, H, "eye inside a box");
    bg_scene_destroy(s);
    mesh_free(&m);
}

/* 64 spheres over a plane: the same floats; BG_PRIMARY_AUTO walks them (measured not to pay). */
static void spheres_equal_the_walk(void **state)
{
    (void)state;
    bg_scene *s = util_many_spheres(64);
    expect_same(s, tree_settings(), W, H, "64 spheres");
    bg_render_stats st;
    free(render(s, bg_render_settings_init(), BG_PRIMARY_AUTO, W, H, &st, "64 spheres, AUTO"));
    assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
    assert_false(st.primary_raster);
    bg_scene_destroy(s);
}

/* BG_PRIMARY_AUTO rasterises a mesh of at most one footprint triangle per 8 pixels: 3 x 1280
 * triangles and a sphere's box (12) in 200 x 160 pixels, not in 96 x 80. */
static void auto_takes_small_meshes(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    bg_render_stats st;
    free(render(s, bg_render_settings_init(), BG_PRIMARY_AUTO, 200, 160, &st, "AUTO, 200 x 160"));
    assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
    assert_true(st.primary_raster);
    free(render(s, bg_render_settings_init(), BG_PRIMARY_AUTO, W, H, &st, "AUTO, 96 x 80"));
    assert_false(st.primary_raster);
    expect_same(s, tree_settings(), 200, 160, "mesh, 200 x 160");
    bg_scene_destroy(s);
    mesh_free(&m);
}

/* The GL work of rasterised frames: the map's two draws of every footprint (one draw for the boxes,
 * one per mesh object) and the fused pass; each mesh's vertices uploaded once, at its first frame;
 * a camera move re-uploads the boxes (camera-relative) and never a mesh. */
static void work_of_the_map(void **state)
{
    (void)state;
    mesh m;
    bg_scene *s = mesh_scene(&m, 3);
    bg_renderer *r = util_renderer(util_fx.ctx);
    float px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, px};
    bg_render_settings set = tree_settings();
    set.primary = BG_PRIMARY_RASTER;
    const uint64_t vertex = 12 * sizeof(float), mesh_bytes = (uint64_t)m.triangle_count * 3 * vertex;
    const uint64_t box_bytes = 36 * vertex; /* one sphere: at most six faces */
    bg_render_stats st;
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "first frame");
    bg_renderer_get_stats(r, &st);
    assert_true(st.primary_raster);
    if (st.gl_work.vertex_bytes < mesh_bytes || st.gl_work.vertex_bytes > mesh_bytes + box_bytes)
        fail_msg("first frame: %llu vertex bytes, not the mesh's %llu and a box's at most %llu",
                 (unsigned long long)st.gl_work.vertex_bytes, (unsigned long long)mesh_bytes,
                 (unsigned long long)box_bytes);
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "second frame");
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.gl_work.vertex_bytes, 0);
    assert_int_equal(st.gl_work.draws, 2 * (1 + 3) + 1);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.5, 0.7, 3.0);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    c.fov_y_degrees = 45.0;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "after a camera move");
    bg_renderer_get_stats(r, &st);
    assert_true(st.gl_work.vertex_bytes > 0 && st.gl_work.vertex_bytes <= box_bytes);
    assert_int_equal(st.programs_compiled, 0);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
    mesh_free(&m);
}

/* bg_render_gpu fails with status and a message naming needle; the image is untouched. */
static void expect_refused(bg_scene *s, const bg_render_settings *set, bg_status status, const char *needle)
{
    bg_renderer *r = util_renderer(util_fx.ctx);
    unsigned char px[8 * 8 * 4];
    memset(px, 0x5a, sizeof px);
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    bg_status st = bg_render_gpu(r, s, set, &img);
    assert_int_equal(st, status);
    const char *msg = bg_renderer_error_message(r);
    if (!strstr(msg, needle))
        fail_msg("message \"%s\" does not name \"%s\"", msg, needle);
    for (size_t k = 0; k < sizeof px; k++)
        assert_int_equal(px[k], 0x5a);
    bg_renderer_destroy(r);
}

static void refusals_name_the_reason(void **state)
{
    (void)state;
    bg_scene *s = util_many_spheres(16);
    bg_render_settings set = bg_render_settings_init();
    set.primary = (bg_primary_visibility)7;
    expect_refused(s, &set, BG_ERR_INVALID_ARGUMENT, "settings.primary 7");
    set.primary = BG_PRIMARY_RASTER;
    set.gpu_plan = BG_PLAN_MULTIPASS;
    expect_refused(s, &set, BG_ERR_LIMIT, "BG_PRIMARY_RASTER");
    set.gpu_plan = BG_PLAN_FUSED;
    expect_refused(s, &set, BG_ERR_LIMIT, "BG_PLAN_FUSED_TREE");
    set.gpu_plan = BG_PLAN_FUSED_TREE;
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.0, 2.0, 8.0);
    c.aperture_radius = 0.1;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    expect_refused(s, &set, BG_ERR_LIMIT, "aperture");
    /* AUTO keeps the walk for the lens, and renders. */
    bg_render_stats st;
    free(render(s, tree_settings(), BG_PRIMARY_AUTO, 16, 16, &st, "lens, AUTO"));
    assert_false(st.primary_raster);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mesh_instances_equal_the_walk),
        cmocka_unit_test(samples_equal_the_walk),
        cmocka_unit_test(window_equals_the_walk),
        cmocka_unit_test(orthographic_equals_the_walk),
        cmocka_unit_test(eye_inside_a_box_equals_the_walk),
        cmocka_unit_test(spheres_equal_the_walk),
        cmocka_unit_test(auto_takes_small_meshes),
        cmocka_unit_test(work_of_the_map),
        cmocka_unit_test(refusals_name_the_reason),
    };
    return cmocka_run_group_tests_name("bg_gpu_primary", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
