/* The path integrator on the GPU (docs/shading.md 13, docs/gpu_pipeline.md "The path integrator"):
 * both fused plans draw it and follow the CPU reference at 16 samples (area lights met both ways,
 * glossy lobes, glass, a mesh, a lighting environment, the light loop, path_ambient); a box of
 * emitting white walls gives its exact radiance; the multipass plan refuses it by name; a Whitted
 * program and a path program of one scene are two programs; the tree plan's walks that run out
 * hand their pixels to the CPU's path. */
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
#include "scenes/path_box.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 48, H = 40 };

static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE};
static const char *const plan_names[] = {"fused", "tree"};

/* A new scene that builder builds and commits. */
static bg_scene *built(bg_status (*builder)(bg_scene *))
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (builder(s) != BG_OK)
        fail_msg("building the scene: %s", bg_scene_error_message(s));
    return s;
}

static void commit(bg_scene *s)
{
    if (bg_scene_commit(s) != BG_OK)
        fail_msg("bg_scene_commit: %s", bg_scene_error_message(s));
}

static bg_scene *cornell_box(void)
{
    return built(path_box_cornell);
}

/* Bounds of the GPU against the CPU at 16 samples (gpu_follows_cpu, below). Both draw the same
 * points, so a path follows the same ways in float and in double until a ray grazes an edge or a
 * choice (an event, roulette) falls within rounding of its bound; from there the two paths part,
 * each an unbiased sample of its own, and the pixel moves by up to that sample's share of it. The
 * rest is the error model of gpu_thresholds.h. Measured on llvmpipe over the four scenes, both plans
 * (RGBA8 sRGB, 48 x 40): every pixel within 2 steps, interior max 1, mean 0.015, PSNR 66.9 dB, no
 * pixel over 8 steps, the image means within 0.03 %. The bounds: interior max 8 (one parted path's
 * worth is what `over` counts), mean 0.05 and PSNR 55 dB (3x the mean error, 12 dB below), 10 of
 * the 1920 pixels over 8 steps, the image means within 0.2 % (7x). */
#define PATH_INTERIOR_MAX 8.0
#define PATH_MEAN 0.05
#define PATH_PSNR 55.0
#define PATH_OVER 0.005
#define PATH_MEAN_RELATIVE 0.002

static bg_render_settings path_settings(int samples, int max_depth)
{
    bg_render_settings set = bg_render_settings_init();
    set.integrator = BG_INTEGRATOR_PATH;
    set.samples = samples;
    set.max_depth = max_depth;
    set.threads = 2;
    return set;
}

/* The image of s in linear RGBA32F: on the CPU (plan < 0) or on plans[plan], which must draw it. */
static float *linear_image(bg_scene *s, const bg_render_settings *set, int w, int h, int plan)
{
    float *px = malloc((size_t)w * h * 16);
    assert_non_null(px);
    bg_image img = {w, h, BG_PIXEL_RGBA32F, 0, px};
    if (plan < 0) {
        if (bg_render_cpu(s, set, &img) != BG_OK)
            fail_msg("bg_render_cpu: %s", bg_scene_error_message(s));
        return px;
    }
    bg_render_settings own = *set;
    own.gpu_plan = plans[plan];
    bg_renderer *r = util_renderer(util_fx.ctx);
    util_render_gpu(r, util_fx.ctx, s, &own, &img, plan_names[plan]);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_int_equal(stats.plan, plans[plan]);
    bg_renderer_destroy(r);
    return px;
}

/* ---- the white box ---- */

/* A closed box of white Lambertian walls (C = 1, r = 1) that emit E: every hit adds E and every way
 * on is the f way with weight exactly 1 in exact arithmetic (rho = 1, f (L.n) / p_b = (1 / pi) (L.n)
 * / ((L.n) / pi)), and roulette keeps every path (q = 1), so each pixel is E (D + 1) after
 * D = max_depth bounces, whatever the samples. In float the weight is 1 to a few roundings a
 * bounce: 1e-5 relative is far above them and far below one bounce's E. */
#define WHITE_BOX_E 0.25
#define WHITE_BOX_TOLERANCE 1e-5

static void white_box_gives_e_times_bounces(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (path_box_white(s, WHITE_BOX_E) != BG_OK)
        fail_msg("path_box_white: %s", bg_scene_error_message(s));
    const int depths[] = {0, 2, 5};
    for (size_t k = 0; k < sizeof depths / sizeof depths[0]; k++) {
        bg_render_settings set = path_settings(4, depths[k]);
        double exact = WHITE_BOX_E * (depths[k] + 1);
        for (int plan = 0; plan < 2; plan++) {
            float *px = linear_image(s, &set, 16, 12, plan);
            double worst = 0.0;
            for (int i = 0; i < 16 * 12; i++)
                for (int c = 0; c < 3; c++) {
                    double e = fabs(px[4 * i + c] - exact);
                    worst = e > worst ? e : worst;
                }
            print_message("white box, max_depth %d, %-5s: largest error %.3g of %.3f\n", depths[k], plan_names[plan], worst,
                          exact);
            assert_true(worst <= WHITE_BOX_TOLERANCE * exact);
            free(px);
        }
    }
    bg_scene_destroy(s);
}

/* ---- the plans ---- */

/* The multipass plan does not draw the path integrator: forced, or chosen by BG_PLAN_AUTO for a
 * setting only it has, it refuses by naming settings.integrator; BG_PLAN_AUTO otherwise takes a
 * fused plan. */
static void multipass_refuses_path(void **state)
{
    (void)state;
    bg_scene *s = built(path_box_cornell);
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = path_settings(1, 2);
    set.gpu_plan = BG_PLAN_MULTIPASS;
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    print_message("forced multipass: %s\n", bg_renderer_error_message(r));
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.integrator"));
    bg_renderer_destroy(r); /* a renderer keeps its first error */
    r = util_renderer(util_fx.ctx);
    set.gpu_plan = BG_PLAN_AUTO;
    set.dmax = 100.0; /* the multipass plan's depth scale: BG_PLAN_AUTO would take that plan */
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    print_message("auto with dmax: %s\n", bg_renderer_error_message(r));
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.integrator"));
    assert_non_null(strstr(bg_renderer_error_message(r), "settings.dmax"));
    bg_renderer_destroy(r);
    r = util_renderer(util_fx.ctx);
    set.dmax = 0.0;
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "auto");
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_true(stats.plan == BG_PLAN_FUSED || stats.plan == BG_PLAN_FUSED_TREE);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* One renderer, one scene: the Whitted image, the path image (a program of its own: one compile),
 * and the Whitted image again, the cached Whitted program's (no compile), byte for byte the first. */
static void whitted_and_path_are_two_programs(void **state)
{
    (void)state;
    bg_scene *s = built(path_box_cornell);
    for (int plan = 0; plan < 2; plan++) {
        unsigned char a[W * H * 4], b[W * H * 4], c[W * H * 4];
        bg_image ia = {W, H, BG_PIXEL_RGBA8, 0, a}, ib = {W, H, BG_PIXEL_RGBA8, 0, b}, ic = {W, H, BG_PIXEL_RGBA8, 0, c};
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_settings whitted = bg_render_settings_init(), path = path_settings(1, 3);
        whitted.gpu_plan = path.gpu_plan = plans[plan];
        bg_render_stats stats;
        util_render_gpu(r, util_fx.ctx, s, &whitted, &ia, "whitted");
        util_render_gpu(r, util_fx.ctx, s, &path, &ib, "path");
        bg_renderer_get_stats(r, &stats);
        assert_int_equal(stats.programs_compiled, 1);
        util_render_gpu(r, util_fx.ctx, s, &whitted, &ic, "whitted again");
        assert_memory_equal(a, c, sizeof a);
        assert_memory_not_equal(a, b, sizeof a);
        bg_renderer_destroy(r);
    }
    bg_scene_destroy(s);
}

/* ---- the GPU follows the CPU ---- */

static uint32_t add_material(bg_scene *s, const bg_material *m)
{
    uint32_t id;
    if (bg_scene_add_material(s, m, &id) != BG_OK)
        fail_msg("bg_scene_add_material: %s", bg_scene_error_message(s));
    return id;
}

static void add_sphere(bg_scene *s, bg_vec3 c, double r, uint32_t mat)
{
    uint32_t id;
    if (bg_scene_add_sphere(s, c, r, mat, &id) != BG_OK)
        fail_msg("bg_scene_add_sphere: %s", bg_scene_error_message(s));
}

/* The Cornell-like box with a glossy coated sphere (its lobe of roughness 0.2 both drawn by the f
 * way's mix and traced as the glossy reflection) and a visible sphere light beside the panel. */
static bg_scene *glossy_box(void)
{
    bg_scene *s = built(path_box_cornell);
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){0.2, 0.3, 0.8, 0};
    m.base.roughness.value = 0.6;
    m.has_coat = true;
    m.coat.reflectance = (bg_color_param){0.05, 0.05, 0.05, 0};
    m.coat.roughness.value = 0.2;
    m.glossy = true;
    add_sphere(s, bg_vec3_make(0.45, -0.6, -0.45), 0.4, add_material(s, &m));
    bg_light l = bg_light_init();
    l.type = BG_LIGHT_SPHERE;
    l.visible = true;
    l.radius = 0.12;
    l.position = bg_vec3_make(0.6, 0.6, -0.6);
    l.intensity = 0.05;
    l.color[1] = 0.8;
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    commit(s);
    return s;
}

/* The box with a glass sphere (every way on: f of its little opaque share, reflection, refraction)
 * and two point lights beside the panel: 3 lights x 8 casters, more shadow tests than the unrolled
 * fused plan inlines, so its lights are a loop (GPU_FUSED_UNROLLED_SHADOW_TESTS). */
static bg_scene *glass_box(void)
{
    bg_scene *s = built(path_box_cornell);
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){0.9, 0.9, 0.9, 0};
    m.base.roughness.value = 0.0;
    m.transparency.value = 0.9;
    m.ior = 1.5;
    add_sphere(s, bg_vec3_make(0.35, -0.5, -0.2), 0.45, add_material(s, &m));
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0.5, 0.7, 0.5);
    l.intensity = 0.3;
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    l.position = bg_vec3_make(-0.6, -0.2, 0.6);
    l.color[0] = 0.4;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    commit(s);
    return s;
}

/* The box with a smooth white icosphere of 320 triangles (a mesh object: its rays leave from offset
 * origins and it may shadow itself) in place of nothing, beside the sphere. */
static bg_scene *mesh_box(void)
{
    bg_scene *s = built(path_box_cornell);
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_icosphere_desc d = {2, 0, true, false};
    char why[256];
    if (mesh_icosphere(&d, &m, why, sizeof why) != BG_OK)
        fail_msg("icosphere: %s", why);
    bg_material white = bg_material_init();
    white.base.reflectance = (bg_color_param){0.8, 0.8, 0.7, 0};
    white.base.roughness.value = 0.7;
    bg_mesh_desc md = bg_mesh_desc_init(add_material(s, &white));
    md.positions = m.positions;
    md.vertex_count = m.vertex_count;
    md.indices = m.indices;
    md.triangle_count = m.triangle_count;
    md.normals = m.normals;
    md.transform = bg_mat4_mul(bg_mat4_translate(0.45, -0.55, -0.4), bg_mat4_scale(0.4, 0.4, 0.4));
    uint32_t id;
    if (bg_scene_add_mesh(s, &md, &id) != BG_OK)
        fail_msg("bg_scene_add_mesh: %s", bg_scene_error_message(s));
    mesh_free(&m);
    commit(s);
    return s;
}

/* A 32 x 16 sky: a blue gradient above, dark ground below, a small bright sun. */
static uint32_t sky_texture(bg_scene *s)
{
    enum { EW = 32, EH = 16 };
    static float texels[EW * EH * 4];
    for (int y = 0; y < EH; y++)
        for (int x = 0; x < EW; x++) {
            float *t = texels + ((size_t)y * EW + x) * 4;
            double up = 1.0 - (y + 0.5) / EH * 2.0;
            t[0] = up > 0.0 ? (float)(0.3 + 0.2 * up) : 0.08f;
            t[1] = up > 0.0 ? (float)(0.5 + 0.2 * up) : 0.07f;
            t[2] = up > 0.0 ? (float)(0.9 + 0.1 * up) : 0.05f;
            t[3] = 1.0f;
            if (x >= 22 && x < 24 && y >= 4 && y < 6)
                t[0] = t[1] = t[2] = 40.0f;
        }
    bg_image img = {EW, EH, BG_PIXEL_RGBA32F, 0, texels};
    uint32_t id;
    if (bg_scene_add_texture(s, &img, NULL, &id) != BG_OK)
        fail_msg("bg_scene_add_texture: %s", bg_scene_error_message(s));
    return id;
}

/* A diffuse sphere and a glossy one on a grey floor under a sky that lights them (importance). */
static bg_scene *sky_spheres(void)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    const double none[3] = {0, 0, 0};
    assert_int_equal(bg_scene_set_ambient(s, none), BG_OK);
    bg_material floor = bg_material_init(), clay = bg_material_init(), gloss = bg_material_init();
    floor.base.reflectance = (bg_color_param){0.5, 0.5, 0.5, 0};
    floor.base.roughness.value = 1.0;
    clay.base.reflectance = (bg_color_param){0.8, 0.5, 0.3, 0};
    clay.base.roughness.value = 1.0;
    gloss.base.reflectance = (bg_color_param){0.7, 0.7, 0.7, 0};
    gloss.base.roughness.value = 0.3;
    gloss.glossy = true;
    uint32_t id;
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), add_material(s, &floor), &id),
                     BG_OK);
    add_sphere(s, bg_vec3_make(-0.8, 0, -0.5), 1.0, add_material(s, &clay));
    add_sphere(s, bg_vec3_make(1.2, -0.3, 0.2), 0.7, add_material(s, &gloss));
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0, 1, 5);
    c.look_at = bg_vec3_make(0, -0.2, 0);
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    bg_environment e = bg_environment_init();
    e.texture = sky_texture(s);
    e.lights = true;
    if (bg_scene_set_environment(s, &e) != BG_OK)
        fail_msg("bg_scene_set_environment: %s", bg_scene_error_message(s));
    commit(s);
    return s;
}

static double mean_of(const float *px, int n, int c)
{
    double m = 0.0;
    for (int i = 0; i < n; i++)
        m += px[4 * i + c];
    return m / n;
}

/* 16 samples put the same points into both renderers; a path then follows the same ways up to
 * float rounding, until a ray grazes an edge or a choice (an event, roulette) falls within rounding
 * of its bound and the two paths part, each then an unbiased sample of its own: a few pixels'
 * worth, measured below. */
static const gpu_threshold path_row = {SCENE_COUNT, PATH_INTERIOR_MAX, PATH_MEAN, PATH_PSNR, PATH_OVER};

static void gpu_follows_cpu_with(bg_scene *(*make)(void), bool ambient, const char *what)
{
    bg_scene *s = make();
    bg_render_settings set = path_settings(16, 5);
    set.path_ambient = ambient;
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    float *cpu_linear = linear_image(s, &set, W, H, -1);
    for (int plan = 0; plan < 2; plan++) {
        char label[64];
        snprintf(label, sizeof label, "%s, %s", what, plan_names[plan]);
        unsigned char *gpu = util_gpu_plan_image(s, &set, plans[plan], W, H, label);
        bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
        util_expect_near_row(cpu, &gi, &path_row, label);
        float *gpu_linear = linear_image(s, &set, W, H, plan);
        for (int c = 0; c < 3; c++) {
            double a = mean_of(cpu_linear, W * H, c), b = mean_of(gpu_linear, W * H, c);
            print_message("%s: mean of channel %d, CPU %.5f, GPU %.5f (%+.3f %%)\n", label, c, a, b,
                          100.0 * (b - a) / a);
            assert_true(fabs(b - a) <= PATH_MEAN_RELATIVE * a);
        }
        free(gpu_linear);
        free(gpu);
    }
    free(cpu_linear);
    free(cpu);
    bg_scene_destroy(s);
}

static void gpu_follows_cpu(bg_scene *(*make)(void), const char *what)
{
    gpu_follows_cpu_with(make, false, what);
}

/* The box under a dim ambient light, which settings.path_ambient adds at every hit. */
static bg_scene *ambient_box(void)
{
    bg_scene *s = built(path_box_cornell);
    const double dim[3] = {0.05, 0.04, 0.06};
    assert_int_equal(bg_scene_set_ambient(s, dim), BG_OK);
    commit(s);
    return s;
}

static void cornell_box_gpu_follows_cpu(void **state)
{
    (void)state;
    gpu_follows_cpu(cornell_box, "Cornell box");
    gpu_follows_cpu_with(ambient_box, true, "Cornell box, path_ambient");
}

static void glossy_gpu_follows_cpu(void **state)
{
    (void)state;
    gpu_follows_cpu(glossy_box, "glossy sphere");
}

static void glass_gpu_follows_cpu(void **state)
{
    (void)state;
    gpu_follows_cpu(glass_box, "glass sphere");
}

static void mesh_gpu_follows_cpu(void **state)
{
    (void)state;
    gpu_follows_cpu(mesh_box, "mesh");
}

static void environment_gpu_follows_cpu(void **state)
{
    (void)state;
    gpu_follows_cpu(sky_spheres, "sky");
}

/* On util_tube_scene the tree plan's walks down the axis run out of steps under the path integrator
 * too: those pixels come from the CPU reference's path (shared/fallback.c), the rest from the GPU;
 * none keeps the shader's mark, and the whole is within the bounds above. */
static void walks_that_run_out_go_to_the_cpu(void **state)
{
    (void)state;
    enum { TW = 48, TH = 36 };
    bg_scene *s = util_tube_scene();
    bg_render_settings set = path_settings(4, 2);
    set.gpu_plan = BG_PLAN_FUSED_TREE;
    unsigned char px[TW * TH * 4];
    bg_image img = {TW, TH, BG_PIXEL_RGBA8, 0, px};
    bg_renderer *r = util_renderer(util_fx.ctx);
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "tube");
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
    print_message("tube, path: %llu of %d pixels from the CPU reference\n", (unsigned long long)st.fallback_pixels,
                  TW * TH);
    if (st.fallback_pixels == 0 || st.fallback_pixels == (uint64_t)TW * TH)
        fail_msg("tube: %llu pixels went to the CPU reference; some (not all) should",
                 (unsigned long long)st.fallback_pixels);
    for (int i = 0; i < TW * TH; i++)
        if (px[4 * i + 3] != 255)
            fail_msg("tube: pixel %d kept the shader's mark (alpha %d)", i, px[4 * i + 3]);
    unsigned char *cpu = util_cpu_reference(s, &set, TW, TH);
    util_expect_near_row(cpu, &img, &path_row, "tube, path");
    free(cpu);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(white_box_gives_e_times_bounces),
        cmocka_unit_test(multipass_refuses_path),
        cmocka_unit_test(whitted_and_path_are_two_programs),
        cmocka_unit_test(cornell_box_gpu_follows_cpu),
        cmocka_unit_test(glossy_gpu_follows_cpu),
        cmocka_unit_test(glass_gpu_follows_cpu),
        cmocka_unit_test(mesh_gpu_follows_cpu),
        cmocka_unit_test(environment_gpu_follows_cpu),
        cmocka_unit_test(walks_that_run_out_go_to_the_cpu),
    };
    return cmocka_run_group_tests_name("bg_gpu_path", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
