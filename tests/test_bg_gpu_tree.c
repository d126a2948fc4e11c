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
#include "betelgeuse/common/encoding.h"
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
    bg_scene *s = util_many_spheres(64);
    assert_true(tree_render(r, s, &img, "64 spheres") >= 1);
    bg_scene_destroy(s);
    s = util_many_spheres(1024);
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
    bg_scene *s = util_many_spheres(64);
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

/* The frame's RGBA8 bytes from what a texture read returns (rows bottom first). */
static void flip_rows(const unsigned char *bottom_first, unsigned char *top_first, int w, int h)
{
    for (int y = 0; y < h; y++)
        memcpy(top_first + (size_t)y * w * 4, bottom_first + (size_t)(h - 1 - y) * w * 4, (size_t)w * 4);
}

/* The tube at several samples, the tree plan forced: a pixel whose walk runs out in any sample is the
 * CPU reference's for all of them (shared/fallback.c), found from the sum's alpha at the frame's end,
 * with one sync and the image's 4 bytes a pixel read back. The image is within the thresholds of the
 * CPU reference at the same samples and keeps no mark; every way to the frame agrees with it bit for
 * bit and counts the same CPU pixels: the float image (encoded on the host), the RGBA8 texture, the
 * accumulation in one call and one sample a call, whose CPU pixels only grow, call by call, to the
 * frame's (a pixel joins them when a sample of it first runs out). */
static void walks_that_run_out_at_several_samples(void **state)
{
    (void)state;
    enum { TW = 48, TH = 36 };
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_tube_scene();
    unsigned char px[TW * TH * 4], got[TW * TH * 4], raw[TW * TH * 4];
    float fpx[TW * TH * 4];
    bg_image img = {TW, TH, BG_PIXEL_RGBA8, 0, px}, fimg = {TW, TH, BG_PIXEL_RGBA32F, 0, fpx};
    bg_image gimg = {TW, TH, BG_PIXEL_RGBA8, 0, got};
    macs_texture_desc td;
    memset(&td, 0, sizeof td);
    td.width = TW;
    td.height = TH;
    td.format = MACS_FORMAT_RGBA8;
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(util_fx.ctx, &td, &t), MACS_OK);
    /* 2 and 4 samples: each sample of a pixel that runs out walks the whole step budget, so 16
     * samples took 70 s of the suite's 85 and showed nothing 4 do not. */
    for (int samples = 2; samples <= 4; samples *= 2) {
        char label[64];
        snprintf(label, sizeof label, "tube, %d samples", samples);
        bg_render_settings set = util_plan_settings(BG_PLAN_FUSED_TREE, samples);
        render(r, s, &set, &img, label);
        bg_render_stats st = render(r, s, &set, &img, label); /* cached: the frame's own GL work */
        uint64_t cpu = st.fallback_pixels;
        print_message("%s: %llu of %d pixels from the CPU reference; read back %llu B, %llu sync(s)\n", label,
                      (unsigned long long)cpu, TW * TH, (unsigned long long)st.gl_work.readback_bytes,
                      (unsigned long long)st.gl_work.syncs);
        if (cpu == 0 || cpu == (uint64_t)TW * TH)
            fail_msg("%s: %llu pixels went to the CPU reference; some (not all) should", label,
                     (unsigned long long)cpu);
        assert_int_equal(st.gl_work.syncs, 1);
        assert_int_equal(st.gl_work.readback_bytes, (uint64_t)TW * TH * 4);
        for (int i = 0; i < TW * TH; i++)
            if (px[4 * i + 3] != 255)
                fail_msg("%s: pixel %d kept the mark (alpha %d)", label, i, px[4 * i + 3]);
        expect_within(s, &set, &img, label);

        /* The float image: the same CPU pixels, and each byte the host's encoding of its value. */
        bg_render_stats fst = render(r, s, &set, &fimg, label);
        assert_int_equal(fst.fallback_pixels, cpu);
        int differ = 0;
        for (int i = 0; i < TW * TH; i++) {
            for (int c = 0; c < 3; c++)
                differ += px[4 * i + c] != bgi_encode_channel(fpx[4 * i + c], set.encoding);
            differ += fpx[4 * i + 3] != 1.0f;
        }
        assert_int_equal(differ, 0);

        /* Into an RGBA8 texture: one read of the packed marks. */
        util_expect_render_ok(r, bg_render_gpu_to_texture(r, s, &set, t), "to a texture");
        bg_renderer_get_stats(r, &st);
        assert_int_equal(st.fallback_pixels, cpu);
        assert_int_equal(st.gl_work.syncs, 1);
        assert_int_equal(macs_texture_read(t, raw, 0), MACS_OK);
        flip_rows(raw, got, TW, TH);
        assert_memory_equal(got, px, sizeof px);

        /* The accumulation, in one call and one sample a call. */
        bg_accumulation *a = NULL;
        util_expect_render_ok(r, bg_accumulation_create(r, TW, TH, &a), "bg_accumulation_create");
        util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 0, samples), "every sample");
        bg_renderer_get_stats(r, &st);
        assert_int_equal(st.fallback_pixels, cpu);
        assert_int_equal(st.gl_work.syncs, 1);
        util_expect_render_ok(r, bg_accumulation_resolve(r, a, &set, &gimg), "bg_accumulation_resolve");
        assert_memory_equal(got, px, sizeof px);
        uint64_t before = 0;
        for (int i = 0; i < samples; i++) {
            util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, i, 1), "one sample");
            bg_renderer_get_stats(r, &st);
            if (st.fallback_pixels < before)
                fail_msg("%s: sample %d: %llu CPU pixels after %llu", label, i, (unsigned long long)st.fallback_pixels,
                         (unsigned long long)before);
            before = st.fallback_pixels;
        }
        assert_int_equal(before, cpu);
        util_expect_render_ok(r, bg_accumulation_resolve(r, a, &set, &gimg), "bg_accumulation_resolve");
        assert_memory_equal(got, px, sizeof px);
        util_expect_render_ok(r, bg_accumulation_resolve_to_texture(r, a, &set, t), "resolve to a texture");
        assert_int_equal(macs_texture_read(t, raw, 0), MACS_OK);
        flip_rows(raw, got, TW, TH);
        assert_memory_equal(got, px, sizeof px);
        bg_accumulation_destroy(a);
    }
    macs_texture_destroy(t);
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
    bg_scene *s = util_many_spheres(4096);
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
    s = util_many_spheres(64);
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
        cmocka_unit_test(walks_that_run_out_at_several_samples),
        cmocka_unit_test(no_bounded_objects),
        cmocka_unit_test(tree_beyond_the_texture_size),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
