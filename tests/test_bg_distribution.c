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

typedef enum light_kind { POINT_LIGHT, SPHERE_LIGHT, SPHERE_OF_RADIUS_0, RECTANGLE_LIGHT, BOTH_AREAS, VISIBLE_AREAS } light_kind;

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

/* How the mirror sphere reflects: a perfect mirror; the same with glossy set (roughness 0); glossy
 * with roughness 0.15, beside a glossy coated sphere and a glossy glass sphere; the same three
 * materials without glossy (their specular shares perfect mirrors). */
typedef enum reflection { MIRROR, GLOSSY_ROUGHNESS_0, GLOSSY, SHARP } reflection;

/* Two spheres on a floor, a mirror sphere among them, under lights of the given kind, through a
 * camera of the given aperture (0: the pinhole) focused on the nearer sphere. */
static bg_scene *spheres_scene_of(light_kind kind, double aperture, double focus, reflection reflect)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t floor = diffuse(s, 0.8, 0.8, 0.8), red = diffuse(s, 0.8, 0.1, 0.1), blue = diffuse(s, 0.1, 0.2, 0.8);
    bg_material chrome = bg_material_init();
    chrome.base.reflectance = (bg_color_param){0.9, 0.9, 0.9, 0};
    bool rough = reflect == GLOSSY || reflect == SHARP, glossy = reflect == GLOSSY || reflect == GLOSSY_ROUGHNESS_0;
    chrome.base.roughness.value = rough ? 0.15 : 0.0;
    chrome.glossy = glossy;
    uint32_t mirror, id;
    assert_int_equal(bg_scene_add_material(s, &chrome, &mirror), BG_OK);
    if (rough) {
        bg_material varnish = bg_material_init(), frost = bg_material_init();
        varnish.base.reflectance = (bg_color_param){0.2, 0.6, 0.2, 0};
        varnish.has_coat = true;
        varnish.coat.roughness.value = 0.05;
        varnish.glossy = glossy;
        frost.base.roughness.value = 0.1;
        frost.transparency.value = 0.8;
        frost.glossy = glossy;
        uint32_t mv, mf;
        assert_int_equal(bg_scene_add_material(s, &varnish, &mv), BG_OK);
        assert_int_equal(bg_scene_add_material(s, &frost, &mf), BG_OK);
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(-0.2, -0.6, 1.2), 0.4, mv, &id), BG_OK);
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(2.4, -0.4, -0.5), 0.6, mf, &id), BG_OK);
    }
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), floor, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(-1.2, 0, -1), 1.0, red, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(1.4, 0, -4), 1.0, blue, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(1.0, -0.5, 0.5), 0.5, mirror, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0.5, 4, 1);
    l.intensity = 0.9;
    bool both = kind == BOTH_AREAS || kind == VISIBLE_AREAS;
    if (kind == SPHERE_LIGHT || both) {
        l.type = BG_LIGHT_SPHERE;
        l.radius = 0.8;
        l.visible = kind == VISIBLE_AREAS;
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
    if (both) {
        bg_light r = bg_light_init();
        r.visible = kind == VISIBLE_AREAS;
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

static bg_scene *spheres_scene(light_kind kind, double aperture, double focus)
{
    return spheres_scene_of(kind, aperture, focus, MIRROR);
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
        bgi_sample_square(&p, BGI_DIMENSION_LIGHT(0), b);
        int ca = (int)(a[1] * 4) * 4 + (int)(a[0] * 4), cb = (int)(b[1] * 4) * 4 + (int)(b[0] * 4);
        lens_cells[ca]++;
        same += ca == cb;
    }
    for (int c = 0; c < 16; c++)
        assert_true(lens_cells[c] > 30);
    print_message("lens and light 0 in the same cell at sample 0: %d of 1000 pixels\n", same);
    assert_true(same > 30 && same < 100);
}

/* Every bit of a dimension's key reaches its permutation of the cells: over 4096 pixels (whose
 * 12-bit keys cover about 1 - 1/e of the 4096 values), the lens's order of 16 cells takes 2746
 * distinct permutations. Keys whose rounds reused bits gave at most 1024. */
static int compare_orders(const void *a, const void *b)
{
    return memcmp(a, b, 16);
}

static void sample_orders_use_every_key_bit(void **state)
{
    (void)state;
    enum { PIXELS = 4096 };
    unsigned char(*orders)[16] = malloc(sizeof *orders * PIXELS);
    assert_non_null(orders);
    for (int i = 0; i < PIXELS; i++)
        for (int s = 0; s < 16; s++) {
            bgi_sample_point p;
            bgi_sample_point_make(i % 64, i / 64, s, 16, &p);
            double uv[2];
            bgi_sample_square(&p, BGI_DIMENSION_LENS, uv);
            orders[i][s] = (unsigned char)((int)(uv[1] * 4) * 4 + (int)(uv[0] * 4));
        }
    qsort(orders, PIXELS, sizeof *orders, compare_orders);
    int distinct = 1;
    for (int i = 1; i < PIXELS; i++)
        distinct += memcmp(orders[i], orders[i - 1], 16) != 0;
    free(orders);
    print_message("distinct orders of 16 cells over %d pixels: %d\n", PIXELS, distinct);
    assert_true(distinct > 2300);
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

/* Two GPU images of one plan whose programs differ but whose formulas agree to the value (an
 * effect at 0 reduces to today's terms through x * 0 = 0, x + 0 = x and x * 1 = x, which GL 2.1
 * section 2.1.1 requires of every implementation): GL does not promise other programs the same
 * rounding (GL 2.1 appendix A, rule 4 covers one program only), so beyond equal bytes (Mesa) they
 * are held to the error model's floor for float evaluations of the same formulas: the common row of
 * gpu_thresholds.h. */
static const gpu_threshold twin_row = {SCENE_COUNT, 2.0, 0.004, 69.0, 0.001};

static void expect_gpu_twins8(const unsigned char *a, const unsigned char *b, int w, int h, const char *label)
{
    if (memcmp(a, b, (size_t)w * h * 4) == 0)
        return;
    bg_image img = {w, h, BG_PIXEL_RGBA8, 0, (void *)b};
    util_expect_near_row(a, &img, &twin_row, label);
}

/* A sphere light of radius 0 is the point light, and aperture 0 the pinhole, whatever the focus
 * distance: on the CPU (byte for byte) and on every plan (byte for byte on Mesa, expect_gpu_twins8
 * on any driver), at 1 and 4 samples. */
static void zero_is_today(void **state)
{
    (void)state;
    bg_scene *today = spheres_scene(POINT_LIGHT, 0.0, 0.0);
    bg_scene *zero_radius = spheres_scene(SPHERE_OF_RADIUS_0, 0.0, 0.0);
    bg_scene *zero_aperture = spheres_scene(POINT_LIGHT, 0.0, 3.0);
    bg_scene *zero_roughness = spheres_scene_of(POINT_LIGHT, 0.0, 0.0, GLOSSY_ROUGHNESS_0);
    const int sample_counts[] = {1, 4};
    for (int k = 0; k < 2; k++) {
        int n = sample_counts[k];
        unsigned char *a = cpu_image(today, n, W, H), *b = cpu_image(zero_radius, n, W, H),
                      *c = cpu_image(zero_aperture, n, W, H), *d = cpu_image(zero_roughness, n, W, H);
        expect_same_bytes(a, b, (size_t)W * H * 4, "CPU, sphere light of radius 0");
        expect_same_bytes(a, c, (size_t)W * H * 4, "CPU, aperture 0");
        expect_same_bytes(a, d, (size_t)W * H * 4, "CPU, glossy of roughness 0");
        free(a);
        free(b);
        free(c);
        free(d);
        bg_render_settings set = samples_settings(n);
        for (int p = 0; p < 3; p++) {
            unsigned char *ga = util_gpu_plan_image(today, &set, plans[p], W, H, plan_names[p]);
            unsigned char *gb = util_gpu_plan_image(zero_radius, &set, plans[p], W, H, plan_names[p]);
            unsigned char *gc = util_gpu_plan_image(zero_aperture, &set, plans[p], W, H, plan_names[p]);
            unsigned char *gd = util_gpu_plan_image(zero_roughness, &set, plans[p], W, H, plan_names[p]);
            expect_gpu_twins8(ga, gb, W, H, plan_names[p]);
            expect_gpu_twins8(ga, gc, W, H, plan_names[p]);
            expect_gpu_twins8(ga, gd, W, H, plan_names[p]);
            free(ga);
            free(gb);
            free(gc);
            free(gd);
        }
    }
    bg_scene_destroy(today);
    bg_scene_destroy(zero_radius);
    bg_scene_destroy(zero_aperture);
    bg_scene_destroy(zero_roughness);
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

/* Visible area lights are drawn, by every plan alike, and light the rest as the hidden ones do. */
static void visible_lights_gpu_follow_cpu(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene(VISIBLE_AREAS, 0.0, 0.0), *hidden = spheres_scene(BOTH_AREAS, 0.0, 0.0);
    gpu_follows_cpu(s, "visible area lights");
    unsigned char *a = cpu_image(s, 4, W, H), *b = cpu_image(hidden, 4, W, H);
    size_t differ = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        differ += memcmp(a + 4 * i, b + 4 * i, 4) != 0;
    /* The sphere light is in view above the scene: its disc and nothing else changes. */
    print_message("visible against hidden lights: %zu pixels differ\n", differ);
    assert_true(differ > 10 && differ < (size_t)W * H / 4);
    free(a);
    free(b);
    bg_scene_destroy(hidden);
    bg_scene_destroy(s);
}

static void glossy_reflection_gpu_follows_cpu(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene_of(POINT_LIGHT, 0.0, 0.0, GLOSSY);
    gpu_follows_cpu(s, "glossy");
    /* The lobe blurs what the three spheres reflect: against the same materials reflecting as
     * mirrors, many pixels change. */
    bg_scene *sharp = spheres_scene_of(POINT_LIGHT, 0.0, 0.0, SHARP);
    unsigned char *a = cpu_image(s, 16, W, H), *b = cpu_image(sharp, 16, W, H);
    int changed = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        changed += abs(a[i] - b[i]) > 8;
    print_message("glossy against mirrors: %d channels differ by more than 8\n", changed);
    assert_true(changed > 100);
    free(a);
    free(b);
    bg_scene_destroy(sharp);
    bg_scene_destroy(s);
}

static void depth_of_field_gpu_follows_cpu(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene(SPHERE_LIGHT, 0.3, 0.0);
    gpu_follows_cpu(s, "lens and sphere light");
    bg_scene_destroy(s);
}

/* ---- convergence ---- */

/* Renders s at w x h, 256 samples, linear float: on the CPU (plan < 0) or on a GPU plan. */
static float *linear_image(bg_scene *s, int w, int h, int plan)
{
    float *px = malloc((size_t)w * h * 16);
    assert_non_null(px);
    bg_image img = {w, h, BG_PIXEL_RGBA32F, 0, px};
    bg_render_settings set = samples_settings(256);
    if (plan < 0) {
        if (bg_render_cpu(s, &set, &img) != BG_OK)
            fail_msg("bg_render_cpu: %s", bg_scene_error_message(s));
        return px;
    }
    set.gpu_plan = plans[plan];
    bg_renderer *r = util_renderer(util_fx.ctx);
    util_render_gpu(r, util_fx.ctx, s, &set, &img, plan_names[plan]);
    bg_renderer_destroy(r);
    return px;
}

/* The penumbra scene: a white floor (y = 0, reflectance C = 0.8, no ambient light), an opaque
 * half-plane y = OCCLUDER_Y, x < 0 above it, and a sphere light of radius LIGHT_R at height LIGHT_Y
 * above x = 0, attenuation none, intensity 1; the camera looks straight down from y = 1.5 at the strip
 * x in [-0.87, 0.87] that holds the penumbra. */
#define LIGHT_Y 4.0
#define LIGHT_R 0.5
#define OCCLUDER_Y 2.0
#define FLOOR_C 0.8
/* Twice the largest errors measured (docs/shading.md 7.1). */
#define WHITE_IMPORTANCE_MAX_ERROR 0.15
#define WHITE_UNIFORM_MAX_ERROR 0.035
/* Twice the largest error measured (docs/shading.md 7). */
#define PENUMBRA_MAX_ERROR 0.016

static bg_scene *penumbra_scene(void)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    const double none[3] = {0, 0, 0};
    assert_int_equal(bg_scene_set_ambient(s, none), BG_OK);
    uint32_t white = diffuse(s, FLOOR_C, FLOOR_C, FLOOR_C), id;
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, 0, 0), bg_vec3_make(0, 1, 0), white, &id), BG_OK);
    bg_object_desc o = bg_object_desc_init(BG_SHAPE_RECTANGLE, white);
    o.transform = bg_mat4_mul(bg_mat4_translate(-1000, OCCLUDER_Y, 0), bg_mat4_scale(1000, 1, 1000));
    assert_int_equal(bg_scene_add_object(s, &o, &id), BG_OK);
    bg_light l = bg_light_init();
    l.type = BG_LIGHT_SPHERE;
    l.position = bg_vec3_make(0, LIGHT_Y, 0);
    l.radius = LIGHT_R;
    add_light(s, &l);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0, 1.5, 0);
    c.look_at = bg_vec3_make(0, 0, 0);
    c.up = bg_vec3_make(0, 0, -1);
    c.fov_y_degrees = 2.0 * atan(0.87 / 1.5 * 4.0 / 64.0) * 180.0 / 3.14159265358979323846;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

/* The exact radiance of floor point (x, 0, z): C times the mean, over the light's cone of
 * directions (uniform in solid angle, as both renderers sample it), of the cosine at the floor over
 * the directions the half-plane lets through: C pi F_visible / Omega, F_visible the form factor of
 * the part of the sphere seen past the occluder's edge. On each ring of the cone (fixed angle from
 * its axis) the visible arc and the integral of the cosine over it are closed forms; the rings are
 * summed by the midpoint rule, n of them. */
static double penumbra_exact(double x, double z, int n)
{
    const double pi = 3.14159265358979323846;
    double c[3] = {-x, LIGHT_Y, -z};
    double d = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double w[3] = {c[0] / d, c[1] / d, c[2] / d};
    /* Any orthonormal a, b across w. */
    double h[3] = {0.0, 0.0, 1.0}, a[3], b[3];
    a[0] = h[1] * w[2] - h[2] * w[1];
    a[1] = h[2] * w[0] - h[0] * w[2];
    a[2] = h[0] * w[1] - h[1] * w[0];
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= la;
    b[0] = w[1] * a[2] - w[2] * a[1];
    b[1] = w[2] * a[0] - w[0] * a[2];
    b[2] = w[0] * a[1] - w[1] * a[0];
    double sin_a = LIGHT_R / d, top = 1.0 - sqrt(1.0 - sin_a * sin_a);
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double t = (i + 0.5) / n * top, cos_t = 1.0 - t, sin_t = sqrt(t * (2.0 - t));
        /* A direction passes the edge when its crossing of y = OCCLUDER_Y has x >= 0, i.e.
         * g = x dir_y + OCCLUDER_Y dir_x >= 0 (dir_y > 0 in the cone): g = al + rho cos(phi - psi). */
        double al = cos_t * (x * w[1] + OCCLUDER_Y * w[0]);
        double be = sin_t * (x * a[1] + OCCLUDER_Y * a[0]), ga = sin_t * (x * b[1] + OCCLUDER_Y * b[0]);
        double rho = sqrt(be * be + ga * ga), psi = atan2(ga, be);
        /* dir_y = p + q cos phi + r sin phi, integrated over the visible arc psi +- delta. */
        double p = cos_t * w[1], q = sin_t * a[1], r = sin_t * b[1];
        double delta = al >= rho ? pi : al <= -rho ? 0.0 : acos(-al / rho);
        double arc = delta >= pi ? 2.0 * pi * p : 2.0 * delta * p + 2.0 * sin(delta) * (q * cos(psi) + r * sin(psi));
        sum += arc / (2.0 * pi);
    }
    return FLOOR_C * sum / n;
}

/* At 256 samples the penumbra of a sphere light follows the exact visible share of it: the largest
 * error of a pixel in linear radiance along the strip, on the CPU and on every plan. */
static void sphere_penumbra_converges(void **state)
{
    (void)state;
    enum { PW = 64, PH = 4 };
    bg_scene *s = penumbra_scene();
    /* The camera maps the floor linearly: x = 1.5 sx and z = -1.5 sy (docs/shading.md 1). */
    double tx = 0.87 / 1.5, ty = tx * PH / PW;
    double exact[PW];
    for (int i = 0; i < PW; i++) {
        double x = 1.5 * (2.0 * (i + 0.5) / PW - 1.0) * tx;
        exact[i] = 0.0;
        for (int j = 0; j < PH; j++)
            exact[i] += penumbra_exact(x, -1.5 * (1.0 - 2.0 * (j + 0.5) / PH) * ty, 4000) / PH;
    }
    /* The strip crosses the whole penumbra: fully shadowed at its left end, fully lit at its right,
     * where the sum is the closed form of a whole sphere above the horizon, F = (R / D)^2 cos theta,
     * and Omega = 2 pi (1 - cos alpha). */
    assert_true(exact[0] == 0.0);
    double x = 1.5 * (2.0 * (PW - 0.5) / PW - 1.0) * tx, d = sqrt(x * x + LIGHT_Y * LIGHT_Y);
    double form = LIGHT_R * LIGHT_R / (d * d) * (LIGHT_Y / d);
    double omega = 2.0 * 3.14159265358979323846 * (1.0 - sqrt(1.0 - LIGHT_R * LIGHT_R / (d * d)));
    double closed = FLOOR_C * 3.14159265358979323846 * form / omega, summed = penumbra_exact(x, 0.0, 4000);
    print_message("fully lit: closed form %.6f, rings summed %.6f\n", closed, summed);
    assert_true(fabs(closed - summed) < 1e-6);
    for (int plan = -1; plan < 3; plan++) {
        float *px = linear_image(s, PW, PH, plan);
        double worst = 0.0, mean = 0.0;
        for (int i = 0; i < PW; i++) {
            double v = 0.0;
            for (int j = 0; j < PH; j++)
                v += px[((size_t)j * PW + i) * 4] / (double)PH;
            double e = fabs(v - exact[i]);
            worst = e > worst ? e : worst;
            mean += e / PW;
        }
        print_message("penumbra, %-9s largest error %.4f, mean %.4f (lit 0.77)\n", plan < 0 ? "CPU" : plan_names[plan],
                      worst, mean);
        assert_true(worst < PENUMBRA_MAX_ERROR);
        free(px);
    }
    bg_scene_destroy(s);
}

/* The circle of confusion: a small emissive sphere (radius DOT_R) on the axis at distance DOT_Z
 * before a camera focused at FOCUS with aperture APERTURE, on black. Through a thin lens a point at
 * distance z spreads over a disc of radius A |z - f| / (z f) in the units of the image plane at
 * distance 1 (the thin-lens formula), here in pixels R_coc = that x (H / 2) / tan(fov / 2). The disc
 * is uniform (the lens points are uniform on the lens), so its intensity-weighted mean of squared
 * distance from the centre is R_coc^2 / 2; the sphere's own image (a disc of radius r_img) and the
 * pixel's box filter add r_img^2 / 2 and 1/6, which are taken off before the comparison. */
#define DOT_Z 4.0
#define DOT_R 0.1
#define FOCUS 8.0
#define APERTURE 0.5
/* Measured 0.06 % (docs/shading.md 1.4); an earlier pairing of the lens cells gave 0.34 %. */
#define COC_MAX_ERROR 0.005

static void circle_of_confusion_follows_thin_lens(void **state)
{
    (void)state;
    enum { CW = 64, CH = 64 };
    const double fov = 20.0, tan_half = tan(fov * 3.14159265358979323846 / 360.0);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material glow = bg_material_init();
    glow.base.reflectance = (bg_color_param){0, 0, 0, 0};
    glow.ambient = (bg_color_param){0, 0, 0, 0};
    glow.emission = (bg_color_param){1, 1, 1, 0};
    uint32_t m, id;
    assert_int_equal(bg_scene_add_material(s, &glow, &m), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, -DOT_Z), DOT_R, m, &id), BG_OK);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0, 0, 0);
    c.look_at = bg_vec3_make(0, 0, -1);
    c.fov_y_degrees = fov;
    c.aperture_radius = APERTURE;
    c.focus_distance = FOCUS;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    double px_per_unit = CH / 2.0 / tan_half;
    double coc = APERTURE * fabs(DOT_Z - FOCUS) / (DOT_Z * FOCUS) * px_per_unit;
    double dot = DOT_R / DOT_Z * px_per_unit;
    for (int plan = -1; plan < 3; plan++) {
        float *px = linear_image(s, CW, CH, plan);
        double total = 0.0, second = 0.0, cx = 0.0, cy = 0.0;
        for (int y = 0; y < CH; y++)
            for (int x = 0; x < CW; x++) {
                double v = px[((size_t)y * CW + x) * 4], dx = x + 0.5 - CW / 2.0, dy = y + 0.5 - CH / 2.0;
                total += v;
                cx += v * dx;
                cy += v * dy;
                second += v * (dx * dx + dy * dy);
            }
        double measured = sqrt(2.0 * (second / total - dot * dot / 2.0 - 1.0 / 6.0));
        print_message("circle of confusion, %-9s radius %.3f px (thin lens %.3f), centre (%.3f, %.3f)\n",
                      plan < 0 ? "CPU" : plan_names[plan], measured, coc, cx / total, cy / total);
        assert_true(fabs(measured - coc) < COC_MAX_ERROR * coc);
        assert_true(fabs(cx / total) < 0.3 && fabs(cy / total) < 0.3);
        free(px);
    }
    bg_scene_destroy(s);
}

/* ---- the environment ---- */

/* A 64 x 32 equirectangular sky: a blue gradient, a dark ground half, and a small bright sun up and
 * to the right (the image's rows top first, as a caller's image has them). */
static uint32_t sky_texture(bg_scene *s, bool sun)
{
    enum { EW = 64, EH = 32 };
    static float texels[EW * EH * 4];
    for (int y = 0; y < EH; y++)
        for (int x = 0; x < EW; x++) {
            float *t = texels + ((size_t)y * EW + x) * 4;
            double up = 1.0 - (y + 0.5) / EH * 2.0; /* cos theta, roughly */
            t[0] = up > 0.0 ? (float)(0.3 + 0.2 * up) : 0.08f;
            t[1] = up > 0.0 ? (float)(0.5 + 0.2 * up) : 0.07f;
            t[2] = up > 0.0 ? (float)(0.9 + 0.1 * up) : 0.05f;
            t[3] = 1.0f;
            if (sun && x >= 44 && x < 47 && y >= 8 && y < 11)
                t[0] = t[1] = t[2] = 60.0f;
        }
    bg_image img = {EW, EH, BG_PIXEL_RGBA32F, 0, texels};
    uint32_t id;
    if (bg_scene_add_texture(s, &img, NULL, &id) != BG_OK)
        fail_msg("bg_scene_add_texture: %s", bg_scene_error_message(s));
    return id;
}

static void set_environment(bg_scene *s, uint32_t texture, bool lights, bg_environment_sampling sampling)
{
    bg_environment e = bg_environment_init();
    e.texture = texture;
    e.lights = lights;
    e.sampling = sampling;
    if (bg_scene_set_environment(s, &e) != BG_OK)
        fail_msg("bg_scene_set_environment: %s", bg_scene_error_message(s));
    assert_int_equal(bg_scene_commit(s), BG_OK);
}

/* The spheres scene seen against the sky, lit by it (or not) and by its point light. */
static void environment_gpu_follows_cpu(void **state)
{
    (void)state;
    const struct {
        bool lights;
        bg_environment_sampling sampling;
        const char *name;
    } cases[] = {{false, BG_ENVIRONMENT_IMPORTANCE, "sky seen"},
                 {true, BG_ENVIRONMENT_IMPORTANCE, "sky lighting, importance"},
                 {true, BG_ENVIRONMENT_UNIFORM, "sky lighting, uniform"}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        bg_scene *s = spheres_scene_of(POINT_LIGHT, 0.0, 0.0, GLOSSY);
        set_environment(s, sky_texture(s, true), cases[c].lights, cases[c].sampling);
        bg_render_settings set = samples_settings(16);
        unsigned char *cpu = util_cpu_reference(s, &set, W, H);
        for (int p = 0; p < 2; p++) {
            char label[64];
            snprintf(label, sizeof label, "%s, %s", cases[c].name, plan_names[p]);
            unsigned char *gpu = util_gpu_plan_image(s, &set, plans[p], W, H, label);
            bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
            util_expect_near_row(cpu, &gi, &distribution_row, label);
            free(gpu);
        }
        util_expect_multipass_refuses_environment(s, &set);
        free(cpu);
        bg_scene_destroy(s);
    }
}

/* Under a uniform white environment of radiance 1 a white Lambertian floor (C = 0.8, nothing
 * else) returns exactly C: both samplings converge to it; their largest pixel error at 256
 * samples is printed and bounded. */
static void white_environment_lights_floor_exactly(void **state)
{
    (void)state;
    for (int sampling = 0; sampling < 2; sampling++) {
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        const double none[3] = {0, 0, 0};
        assert_int_equal(bg_scene_set_ambient(s, none), BG_OK);
        uint32_t white = diffuse(s, FLOOR_C, FLOOR_C, FLOOR_C), id;
        assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, 0, 0), bg_vec3_make(0, 1, 0), white, &id), BG_OK);
        float texels[8 * 4 * 4];
        for (int i = 0; i < 8 * 4 * 4; i++)
            texels[i] = 1.0f;
        bg_image img = {8, 4, BG_PIXEL_RGBA32F, 0, texels};
        uint32_t tex;
        assert_int_equal(bg_scene_add_texture(s, &img, NULL, &tex), BG_OK);
        bg_camera c = bg_camera_init();
        c.position = bg_vec3_make(0, 1, 0);
        c.look_at = bg_vec3_make(0, 0, 0);
        c.up = bg_vec3_make(0, 0, -1);
        c.fov_y_degrees = 60.0;
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        set_environment(s, tex, true, (bg_environment_sampling)sampling);
        for (int plan = -1; plan < 2; plan++) {
            float *px = linear_image(s, 16, 16, plan);
            double worst = 0.0, mean = 0.0;
            for (int i = 0; i < 16 * 16; i++) {
                double e = fabs(px[4 * i] - FLOOR_C);
                worst = e > worst ? e : worst;
                mean += e / (16 * 16);
            }
            print_message("white environment, %s sampling, %-6s largest error %.4f, mean %.4f (exact 0.8)\n",
                          sampling ? "uniform" : "importance", plan < 0 ? "CPU" : plan_names[plan], worst, mean);
            assert_true(worst < (sampling ? WHITE_UNIFORM_MAX_ERROR : WHITE_IMPORTANCE_MAX_ERROR));
            free(px);
        }
        bg_scene_destroy(s);
    }
}

/* ---- bad values ---- */

static void expect_refused(bg_scene *s, bg_status st, const char *field)
{
    assert_int_equal(st, BG_ERR_INVALID_ARGUMENT);
    const char *m = bg_scene_error_message(s);
    print_message("%s\n", m);
    if (!strstr(m, field))
        fail_msg("the message does not name %s: %s", field, m);
    bg_scene_clear_error(s);
}

/* Each bad value of the new fields is refused, naming the field and the reason. */
static void bad_values_are_refused(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_camera c = bg_camera_init();
    c.aperture_radius = -0.1;
    expect_refused(s, bg_scene_set_camera(s, &c), "aperture_radius");
    c.aperture_radius = 0.1;
    c.focus_distance = NAN;
    expect_refused(s, bg_scene_set_camera(s, &c), "focus_distance");
    uint32_t id;
    bg_light l = bg_light_init();
    l.type = BG_LIGHT_SPHERE;
    l.radius = -1.0;
    expect_refused(s, bg_scene_add_light(s, &l, &id), "radius");
    l.radius = INFINITY;
    expect_refused(s, bg_scene_add_light(s, &l, &id), "radius");
    l = bg_light_init();
    l.type = BG_LIGHT_RECTANGLE;
    l.edge_v = bg_vec3_make(2, 0, 0);
    expect_refused(s, bg_scene_add_light(s, &l, &id), "parallel");
    l.edge_v = bg_vec3_make(0, 0, 1);
    l.edge_u = bg_vec3_make(NAN, 0, 0);
    expect_refused(s, bg_scene_add_light(s, &l, &id), "edge_u");
    l.edge_u = bg_vec3_make(1, 0, 0);
    l.spot_cutoff_degrees = 45.0;
    expect_refused(s, bg_scene_add_light(s, &l, &id), "spot_cutoff_degrees");
    bg_environment e = bg_environment_init();
    e.texture = 12345;
    expect_refused(s, bg_scene_set_environment(s, &e), "texture");
    e.texture = 0;
    e.intensity = -1.0;
    expect_refused(s, bg_scene_set_environment(s, &e), "intensity");
    e.intensity = 1.0;
    e.sampling = (bg_environment_sampling)7;
    expect_refused(s, bg_scene_set_environment(s, &e), "sampling");
    assert_int_equal(bg_scene_set_environment(s, NULL), BG_ERR_INVALID_ARGUMENT);
    bg_scene_clear_error(s);
    bg_scene_destroy(s);
}

/* The environment's tables follow its texture through sets, commits and a removal that is refused
 * while the environment uses the texture (the sanitizer run checks that nothing leaks). */
static void environment_follows_its_texture(void **state)
{
    (void)state;
    bg_scene *s = spheres_scene(POINT_LIGHT, 0.0, 0.0);
    uint32_t sky = sky_texture(s, true), plain = sky_texture(s, false);
    set_environment(s, sky, true, BG_ENVIRONMENT_IMPORTANCE);
    unsigned char *a = cpu_image(s, 4, W, H);
    expect_refused(s, bg_scene_remove_texture(s, sky), "environment");
    set_environment(s, plain, true, BG_ENVIRONMENT_IMPORTANCE);
    set_environment(s, 0, false, BG_ENVIRONMENT_IMPORTANCE);
    assert_int_equal(bg_scene_remove_texture(s, sky), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    /* Without an environment the image is the plain scene's again. */
    bg_scene *plain_scene = spheres_scene(POINT_LIGHT, 0.0, 0.0);
    unsigned char *b = cpu_image(s, 4, W, H), *c = cpu_image(plain_scene, 4, W, H);
    expect_same_bytes(b, c, (size_t)W * H * 4, "no environment");
    assert_true(memcmp(a, b, (size_t)W * H * 4) != 0);
    set_environment(s, plain, true, BG_ENVIRONMENT_UNIFORM);
    free(a);
    free(b);
    free(c);
    bg_scene_destroy(plain_scene);
    bg_scene_destroy(s);
}

/* A window of the frame (a crop, a tile) takes the frame pixels' own sample points: with every effect
 * on, the window is the same rectangle of the full frame, byte for byte, on the CPU and the fused
 * plans on any conforming driver (the same program per pixel, on a frame coordinate and pixel hash
 * that come out exactly equal: test_bg_gpu_view's expect_rectangle), and on the multipass where it
 * batches the window as the frame (Mesa); elsewhere the multipass is held to expect_gpu_twins8. */
static void windows_are_the_frame_s_pixels(void **state)
{
    (void)state;
    /* The multipass draws no environment: it gets the scene without one. */
    bg_scene *with_sky = spheres_scene_of(BOTH_AREAS, 0.3, 0.0, GLOSSY), *plain = spheres_scene_of(BOTH_AREAS, 0.3, 0.0, GLOSSY);
    set_environment(with_sky, sky_texture(with_sky, true), true, BG_ENVIRONMENT_IMPORTANCE);
    enum { X0 = 16, Y0 = 8, WW = 32, WH = 24 };
    for (int plan = -1; plan < 3; plan++) {
        bg_scene *s = plan == 2 ? plain : with_sky;
        bg_render_settings set = samples_settings(4);
        unsigned char *full = plan < 0 ? util_cpu_reference(s, &set, W, H)
                                       : util_gpu_plan_image(s, &set, plans[plan], W, H, plan_names[plan]);
        set.frame_width = W;
        set.frame_height = H;
        set.window_x = X0;
        set.window_y = Y0;
        unsigned char *win = plan < 0 ? util_cpu_reference(s, &set, WW, WH)
                                      : util_gpu_plan_image(s, &set, plans[plan], WW, WH, plan_names[plan]);
        size_t differ = 0;
        for (int y = 0; y < WH; y++)
            differ += memcmp(win + (size_t)y * WW * 4, full + ((size_t)(Y0 + y) * W + X0) * 4, WW * 4) != 0;
        print_message("window of the frame, %s: %zu rows differ\n", plan < 0 ? "CPU" : plan_names[plan], differ);
        if (differ && plan >= 0 && plans[plan] == BG_PLAN_MULTIPASS) {
            unsigned char *rect = malloc((size_t)WW * WH * 4);
            assert_non_null(rect);
            for (int y = 0; y < WH; y++)
                memcpy(rect + (size_t)y * WW * 4, full + ((size_t)(Y0 + y) * W + X0) * 4, WW * 4);
            expect_gpu_twins8(rect, win, WW, WH, "multipass window");
            free(rect);
            differ = 0;
        }
        assert_int_equal(differ, 0);
        free(full);
        free(win);
    }
    bg_scene_destroy(with_sky);
    bg_scene_destroy(plain);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sample_points_fill_every_cell_once),
        cmocka_unit_test(sample_orders_use_every_key_bit),
        cmocka_unit_test(zero_is_today),
        cmocka_unit_test(sphere_light_gpu_follows_cpu),
        cmocka_unit_test(rectangle_lights_gpu_follow_cpu),
        cmocka_unit_test(depth_of_field_gpu_follows_cpu),
        cmocka_unit_test(glossy_reflection_gpu_follows_cpu),
        cmocka_unit_test(visible_lights_gpu_follow_cpu),
        cmocka_unit_test(sphere_penumbra_converges),
        cmocka_unit_test(circle_of_confusion_follows_thin_lens),
        cmocka_unit_test(environment_gpu_follows_cpu),
        cmocka_unit_test(white_environment_lights_floor_exactly),
        cmocka_unit_test(bad_values_are_refused),
        cmocka_unit_test(environment_follows_its_texture),
        cmocka_unit_test(windows_are_the_frame_s_pixels),
    };
    return cmocka_run_group_tests_name("bg_distribution", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
