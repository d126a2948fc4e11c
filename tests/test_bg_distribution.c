/* Distribution ray tracing (docs/shading.md 1.3, 1.4 and 7): the scrambled sample points, area
 * lights and the thin lens, in the CPU reference and every GPU plan. Each "0 is today" rule holds
 * bit for bit; the GPU follows the CPU at 16 samples; at 256 samples a sphere light's penumbra
 * follows the visible share of the light and the blur of a point follows the thin-lens circle of
 * confusion, within bounds measured here. */
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
#include "betelgeuse/common/scramble.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 64, H = 48 };

static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
static const char *const plan_names[] = {"fused", "tree", "multipass"};

typedef enum light_kind { POINT_LIGHT, SPHERE_LIGHT, SPHERE_OF_RADIUS_0, RECTANGLE_LIGHT, BOTH_AREAS } light_kind;

static uint32_t diffuse(bg_scene *s, double r, double g, double b)
{
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){r, g, b, 0};
    uint32_t id;
    if (bg_scene_add_material(s, &m, &id) != BG_OK)
        fail_msg("bg_scene_add_material: %s", bg_scene_error_message(s));
    return id;
}

static void add_light(bg_scene *s, const bg_light *l)
{
    uint32_t id;
    if (bg_scene_add_light(s, l, &id) != BG_OK)
        fail_msg("bg_scene_add_light: %s", bg_scene_error_message(s));
}

/* Two spheres on a floor, a mirror sphere among them, under lights of the given kind, through a
 * camera of the given aperture (0: the pinhole) focused on the nearer sphere. */
static bg_scene *spheres_scene(light_kind kind, double aperture, double focus)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t floor = diffuse(s, 0.8, 0.8, 0.8), red = diffuse(s, 0.8, 0.1, 0.1), blue = diffuse(s, 0.1, 0.2, 0.8);
    bg_material chrome = bg_material_init();
    chrome.base.reflectance = (bg_color_param){0.9, 0.9, 0.9, 0};
    chrome.base.roughness.value = 0.0;
    uint32_t mirror, id;
    assert_int_equal(bg_scene_add_material(s, &chrome, &mirror), BG_OK);
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), floor, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(-1.2, 0, -1), 1.0, red, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(1.4, 0, -4), 1.0, blue, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(1.0, -0.5, 0.5), 0.5, mirror, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0.5, 4, 1);
    l.intensity = 0.9;
    if (kind == SPHERE_LIGHT || kind == BOTH_AREAS) {
        l.type = BG_LIGHT_SPHERE;
        l.radius = 0.8;
    } else if (kind == SPHERE_OF_RADIUS_0) {
        l.type = BG_LIGHT_SPHERE;
        l.radius = 0.0;
    } else if (kind == RECTANGLE_LIGHT) {
        l.type = BG_LIGHT_RECTANGLE;
        l.position = bg_vec3_make(-1, 4, -1);
        l.edge_u = bg_vec3_make(2, 0, 0);
        l.edge_v = bg_vec3_make(0, 0, 2);
    }
    add_light(s, &l);
    if (kind == BOTH_AREAS) {
        bg_light r = bg_light_init();
        r.type = BG_LIGHT_RECTANGLE;
        r.position = bg_vec3_make(-4, 3, 1);
        r.edge_u = bg_vec3_make(0, 0, -1.5);
        r.edge_v = bg_vec3_make(0.5, -1.5, 0);
        r.color[2] = 0.6;
        r.attenuation[0] = 0.0;
        r.attenuation[2] = 0.05;
        add_light(s, &r);
    }
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0, 1, 5);
    c.look_at = bg_vec3_make(-1.2, 0, -1);
    c.aperture_radius = aperture;
    c.focus_distance = focus;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    if (bg_scene_commit(s) != BG_OK)
        fail_msg("bg_scene_commit: %s", bg_scene_error_message(s));
    return s;
}

static bg_render_settings samples_settings(int samples)
{
    bg_render_settings set = bg_render_settings_init();
    set.samples = samples;
    return set;
}

static unsigned char *cpu_image(bg_scene *s, int samples, int w, int h)
{
    bg_render_settings set = samples_settings(samples);
    return util_cpu_reference(s, &set, w, h);
}

/* ---- the sample points ---- */

/* Over a pixel's n samples a dimension visits each cell of the pattern's grid once, whatever the
 * pixel and dimension; the cell order differs between pixels and between dimensions. */
static void sample_points_fill_every_cell_once(void **state)
{
    (void)state;
    const int ns[] = {1, 4, 6, 16, 17, 256};
    for (size_t k = 0; k < sizeof ns / sizeof ns[0]; k++) {
        int n = ns[k];
        for (int pixel = 0; pixel < 20; pixel++)
            for (int dimension = 0; dimension < 20; dimension += 7) {
                int seen[256] = {0};
                for (int s = 0; s < n; s++) {
                    bgi_sample_point p;
                    bgi_sample_point_make(pixel * 37 % 16384, pixel * 1013 % 16384, s, n, &p);
                    double uv[2];
                    bgi_sample_square(&p, dimension, uv);
                    assert_true(uv[0] >= 0.0 && uv[0] < 1.0 && uv[1] >= 0.0 && uv[1] < 1.0);
                    int cell = (int)floor(uv[1] * p.rows) * p.columns + (int)floor(uv[0] * p.columns);
                    seen[cell]++;
                }
                for (int c = 0; c < n; c++)
                    assert_int_equal(seen[c], 1);
            }
    }
    /* Sample 0's cell over 1000 pixels, for the lens and for light 0: both use every one of 16 cells,
     * and they agree no more often than chance (1/16 of the time, give or take). */
    int lens_cells[16] = {0}, same = 0;
    for (int i = 0; i < 1000; i++) {
        double a[2], b[2];
        bgi_sample_point p;
        bgi_sample_point_make(i % 40, i / 40, 0, 16, &p);
        bgi_sample_square(&p, BGI_DIMENSION_LENS, a);
        bgi_sample_square(&p, BGI_DIMENSION_LIGHT0, b);
        int ca = (int)(a[1] * 4) * 4 + (int)(a[0] * 4), cb = (int)(b[1] * 4) * 4 + (int)(b[0] * 4);
        lens_cells[ca]++;
        same += ca == cb;
    }
    for (int c = 0; c < 16; c++)
        assert_true(lens_cells[c] > 30);
    print_message("lens and light 0 in the same cell at sample 0: %d of 1000 pixels\n", same);
    assert_true(same > 30 && same < 100);
}

/* ---- 0 is today ---- */

static void expect_same_bytes(const unsigned char *a, const unsigned char *b, size_t n, const char *label)
{
    size_t differ = 0;
    for (size_t i = 0; i < n; i++)
        differ += a[i] != b[i];
    if (differ)
        fail_msg("%s: %zu bytes differ", label, differ);
}

/* A sphere light of radius 0 is the point light, and aperture 0 the pinhole, whatever the focus
 * distance: on the CPU and on every plan, at 1 and 4 samples. */
static void zero_is_today(void **state)
{
    (void)state;
    bg_scene *today = spheres_scene(POINT_LIGHT, 0.0, 0.0);
    bg_scene *zero_radius = spheres_scene(SPHERE_OF_RADIUS_0, 0.0, 0.0);
    bg_scene *zero_aperture = spheres_scene(POINT_LIGHT, 0.0, 3.0);
    const int sample_counts[] = {1, 4};
    for (int k = 0; k < 2; k++) {
        int n = sample_counts[k];
        unsigned char *a = cpu_image(today, n, W, H), *b = cpu_image(zero_radius, n, W, H),
                      *c = cpu_image(zero_aperture, n, W, H);
        expect_same_bytes(a, b, (size_t)W * H * 4, "CPU, sphere light of radius 0");
        expect_same_bytes(a, c, (size_t)W * H * 4, "CPU, aperture 0");
        free(a);
        free(b);
        free(c);
        bg_render_settings set = samples_settings(n);
        for (int p = 0; p < 3; p++) {
            unsigned char *ga = util_gpu_plan_image(today, &set, plans[p], W, H, plan_names[p]);
            unsigned char *gb = util_gpu_plan_image(zero_radius, &set, plans[p], W, H, plan_names[p]);
            unsigned char *gc = util_gpu_plan_image(zero_aperture, &set, plans[p], W, H, plan_names[p]);
            expect_same_bytes(ga, gb, (size_t)W * H * 4, plan_names[p]);
            expect_same_bytes(ga, gc, (size_t)W * H * 4, plan_names[p]);
            free(ga);
            free(gb);
            free(gc);
        }
    }
    bg_scene_destroy(today);
    bg_scene_destroy(zero_radius);
    bg_scene_destroy(zero_aperture);
}

/* ---- the GPU follows the CPU ---- */

/* 16 samples place the same points in float and double up to rounding; a shadow ray grazing an
 * edge may still fall the other way, a few pixels' worth. */
static const gpu_threshold distribution_row = {SCENE_COUNT, 24.0, 0.5, 35.0, 0.01};

static void gpu_follows_cpu(bg_scene *s, const char *what)
{
    bg_render_settings set = samples_settings(16);
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    for (int p = 0; p < 3; p++) {
        char label[64];
        snprintf(label, sizeof label, "%s, %s", what, plan_names[p]);
        unsigned char *gpu = malloc((size_t)W * H * 4);
        assert_non_null(gpu);
        bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
        bg_renderer *r = util_renderer(util_fx.ctx);
        set.gpu_plan = plans[p];
        util_render_gpu(r, util_fx.ctx, s, &set, &gi, label);
        /* Every pixel is the GPU's own: none went to the CPU reference. */
        bg_render_stats stats;
        bg_renderer_get_stats(r, &stats);
        assert_int_equal(stats.plan, plans[p]);
        assert_int_equal(stats.fallback_pixels, 0);
        bg_renderer_destroy(r);
        util_expect_near_row(cpu, &gi, &distribution_row, label);
        free(gpu);
    }
    free(cpu);
}

static void sphere_light_gpu_follows_cpu(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene(SPHERE_LIGHT, 0.0, 0.0);
    gpu_follows_cpu(s, "sphere light");
    bg_scene_destroy(s);
}

static void rectangle_lights_gpu_follow_cpu(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene(BOTH_AREAS, 0.0, 0.0);
    gpu_follows_cpu(s, "sphere and rectangle");
    bg_scene_destroy(s);
}

static void depth_of_field_gpu_follows_cpu(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene(SPHERE_LIGHT, 0.3, 0.0);
    gpu_follows_cpu(s, "lens and sphere light");
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sample_points_fill_every_cell_once),
        cmocka_unit_test(zero_is_today),
        cmocka_unit_test(sphere_light_gpu_follows_cpu),
        cmocka_unit_test(rectangle_lights_gpu_follow_cpu),
        cmocka_unit_test(depth_of_field_gpu_follows_cpu),
    };
    return cmocka_run_group_tests_name("bg_distribution", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
