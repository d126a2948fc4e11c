/* The fused plan's tree variant (BG_PLAN_FUSED_TREE): BG_PLAN_AUTO choosing it for scenes of many
 * objects, within the thresholds against the CPU reference; one program for every count of objects
 * of the same kinds, so that adding, moving or recolouring objects compiles nothing; the same image
 * from a cached program and after a value round trip; pixels whose walks would outrun the shader's
 * loop limit rendered by the CPU reference instead of cut short; and trees beyond the GL's texture
 * size refused clearly. (The shared scenes with the variant forced are in test_bg_gpu_plans.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/scene/scene_internal.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 160, H = 120 };

/* many_spheres beyond the shared table's 16 spheres has more silhouettes: at 64 spheres one pixel on
 * a sphere's rim is 6/255 from the CPU reference in both fused variants (75.9 dB over every pixel),
 * none inside. Rims are the silhouette allowance: the error model's common row (gpu_thresholds.h). */
static const gpu_threshold many_spheres_row = {SCENE_MANY_SPHERES, 2.0, 0.004, 69.0, 0.001};

static void expect_within(bg_scene *s, const bg_render_settings *set, const bg_image *img, const char *label)
{
    unsigned char *cpu = util_cpu_reference(s, set, img->width, img->height);
    util_expect_near_row(cpu, img, &many_spheres_row, label);
    free(cpu);
}

static bg_render_stats render(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_image *img,
                              const char *label)
{
    util_render_gpu(r, util_fx.ctx, s, set, img, label);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    return stats;
}

static bg_scene *spheres_scene(int n)
{
    scene_params p = {0};
    p.spheres = n;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(scenes_build_ex(SCENE_MANY_SPHERES, &p, s), BG_OK);
    return s;
}

/* Renders with BG_PLAN_AUTO, expects the tree variant with every pixel its own, within the
 * many_spheres thresholds; returns the programs the render built. */
static int tree_render(bg_renderer *r, bg_scene *s, bg_image *img, const char *label)
{
    bg_render_settings set = bg_render_settings_init();
    bg_render_stats st = render(r, s, &set, img, label);
    if (st.plan != BG_PLAN_FUSED_TREE)
        fail_msg("%s: BG_PLAN_AUTO ran plan %d, not the tree variant", label, (int)st.plan);
    assert_int_equal(st.passes[BG_PASS_INTERSECT], 1);
    if (st.fallback_pixels != 0)
        fail_msg("%s: %llu pixels went to the CPU reference", label, (unsigned long long)st.fallback_pixels);
    expect_within(s, &set, img, label);
    return st.programs_compiled;
}

/* 64 and 1024 spheres: the tree, and one program for both (the count is not in it). */
static void auto_walks_a_tree(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    bg_scene *s = spheres_scene(64);
    assert_true(tree_render(r, s, &img, "64 spheres") >= 1);
    bg_scene_destroy(s);
    s = spheres_scene(1024);
    assert_int_equal(tree_render(r, s, &img, "1024 spheres"), 0);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* Moving an object or the camera, recolouring a material and adding an object of a kind the tree
 * has change values or the tree, not the program; a round trip gives back the first image. */
static void recommits_keep_the_program(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    size_t bytes = (size_t)W * H * 4;
    unsigned char *first = malloc(bytes), *px = malloc(bytes);
    assert_non_null(first);
    assert_non_null(px);
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, first};
    bg_scene *s = spheres_scene(64);
    bg_mat4 here = bg_mat4_mul(bg_mat4_translate(0.1, 0.0, 0.2), bg_mat4_scale(0.3, 0.3, 0.3));
    bg_mat4 there = bg_mat4_mul(bg_mat4_translate(0.4, 0.3, -0.5), bg_mat4_scale(0.3, 0.3, 0.3));
    assert_int_equal(bg_scene_set_transform(s, 5, &here), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    tree_render(r, s, &img, "64 spheres");
    img.pixels = px;
    assert_int_equal(tree_render(r, s, &img, "cached"), 0);
    /* Equal on any conforming driver: the same program on the same uniforms and tree textures (GL 2.1 appendix A, rule 4). */
    assert_memory_equal(first, px, bytes);

    assert_int_equal(bg_scene_set_transform(s, 5, &there), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(tree_render(r, s, &img, "a sphere moved"), 0);
    bg_camera cam = bgi_scene_committed(s)->camera.camera, moved = cam;
    moved.position.x += 0.25;
    assert_int_equal(bg_scene_set_camera(s, &moved), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(tree_render(r, s, &img, "camera moved"), 0);
    bg_material m = bgi_scene_committed(s)->materials[0], red = m;
    red.base.reflectance.r = 0.9;
    red.base.reflectance.g = 0.1;
    assert_int_equal(bg_scene_set_material(s, 1, &red), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(tree_render(r, s, &img, "material recoloured"), 0);

    /* Back where everything was: the first image, bit for bit on any conforming driver (the CPU builds
     * the same tree textures and uniforms from the same commit, the same program reads them). */
    assert_int_equal(bg_scene_set_material(s, 1, &m), BG_OK);
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_set_transform(s, 5, &here), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(tree_render(r, s, &img, "round trip"), 0);
    assert_memory_equal(first, px, bytes);

    /* One more sphere of a material already in use: a new tree, the same program. */
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_sphere(s, (bg_vec3){0.0, 0.0, 1.0}, 0.2, 1, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(tree_render(r, s, &img, "a sphere added"), 0);

    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    free(first);
    free(px);
}

/* On util_tube_scene, the pixels down the axis run out of walk steps: those pixels must come from
 * the CPU reference, the rest from the GPU, the whole within the many_spheres thresholds, in either
 * output format. */
static void walks_that_run_out_go_to_the_cpu(void **state)
{
    (void)state;
    enum { TW = 48, TH = 36 };
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_tube_scene();
    unsigned char px[TW * TH * 4];
    float fpx[TW * TH * 4];
    bg_image img = {TW, TH, BG_PIXEL_RGBA8, 0, px}, fimg = {TW, TH, BG_PIXEL_RGBA32F, 0, fpx};
    bg_render_settings set = bg_render_settings_init();
    bg_render_stats st = render(r, s, &set, &img, "tube");
    assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
    print_message("tube: %llu of %d pixels from the CPU reference\n", (unsigned long long)st.fallback_pixels,
                  TW * TH);
    if (st.fallback_pixels == 0 || st.fallback_pixels == (uint64_t)TW * TH)
        fail_msg("tube: %llu pixels went to the CPU reference; some (not all) should",
                 (unsigned long long)st.fallback_pixels);
    for (int i = 0; i < TW * TH; i++)
        if (px[4 * i + 3] != 255)
            fail_msg("tube: pixel %d kept the shader's mark (alpha %d)", i, px[4 * i + 3]);
    expect_within(s, &set, &img, "tube");

    bg_render_stats fst = render(r, s, &set, &fimg, "tube float");
    assert_int_equal(fst.fallback_pixels, st.fallback_pixels);
    for (int i = 0; i < TW * TH; i++)
        if (fpx[4 * i + 3] != 1.0f)
            fail_msg("tube float: pixel %d has alpha %g", i, (double)fpx[4 * i + 3]);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* A scene of unbounded objects only: the variant has no tree to walk and renders like the rest. */
static void no_bounded_objects(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t mat = 0;
    bg_material m = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_plane(s, (bg_vec3){0.0, -1.0, 0.0}, (bg_vec3){0.0, 1.0, 0.0}, mat, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = (bg_vec3){0.0, 3.0, 0.0};
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    bg_renderer *r = util_renderer(util_fx.ctx);
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init();
    set.gpu_plan = BG_PLAN_FUSED_TREE;
    assert_int_equal(render(r, s, &set, &img, "a plane").plan, BG_PLAN_FUSED_TREE);
    util_expect_within(s, &set, &img, SCENE_PAPER_EARTH_SHADOW, "a plane, tree variant");
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* A tree whose nodes need more texture rows than GL allows: the forced variant fails and says so,
 * and the renderer renders the next frame. */
static void tree_beyond_the_texture_size(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_texture_size = 64;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = spheres_scene(4096);
    unsigned char px[48 * 36 * 4];
    bg_image img = {48, 36, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init();
    set.gpu_plan = BG_PLAN_FUSED_TREE;
    /* The refusal is the test: the library's own call, which no limit profile turns into a skip. */
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    const char *msg = bg_renderer_error_message(r);
    if (!strstr(msg, "BG_PLAN_FUSED_TREE") || !strstr(msg, "nodes") || !strstr(msg, "64"))
        fail_msg("unclear message: \"%s\"", msg);
    bg_renderer_clear_error(r);
    bg_scene_destroy(s);
    s = spheres_scene(64);
    util_render_gpu(r, ctx, s, &set, &img, "64 spheres after the limit");
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(auto_walks_a_tree),
        cmocka_unit_test(recommits_keep_the_program),
        cmocka_unit_test(walks_that_run_out_go_to_the_cpu),
        cmocka_unit_test(no_bounded_objects),
        cmocka_unit_test(tree_beyond_the_texture_size),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
