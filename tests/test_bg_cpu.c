/* The CPU reference renderer against values computed by hand from docs/shading.md, thread-count
 * independence, NaN/Inf freedom on the shared scenes, and its error paths. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/common/encoding.h"
#include "betelgeuse/cpu/cpu_internal.h"
#include "betelgeuse/common/srgb.h"
#include "scenes/scenes.h"

static const double PI = 3.14159265358979323846;

static void rel_near(double got, double want, double rel)
{
    double tol = rel * (fabs(want) > 1e-300 ? fabs(want) : 1.0);
    if (!(fabs(got - want) <= tol))
        fail_msg("got %.17g, want %.17g (rel %g)", got, want, rel);
}

static bg_scene *new_scene(void)
{
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    return scene;
}

static uint32_t add_material(bg_scene *scene, const bg_material *m)
{
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_material(scene, m, &id), BG_OK);
    return id;
}

static void set_ambient(bg_scene *scene, double r, double g, double b)
{
    const double a[3] = {r, g, b};
    assert_int_equal(bg_scene_set_ambient(scene, a), BG_OK);
}

static bg_material black_emitter(double r, double g, double b)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 0.0;
    m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    m.emission.r = r;
    m.emission.g = g;
    m.emission.b = b;
    return m;
}

/* The centre pixel of a 3x3 RGBA32F render (its ray is exactly the camera's forward axis). */
static void centre_pixel(bg_scene *scene, const bg_render_settings *settings, float out[4])
{
    float px[9 * 4];
    bg_image img = {3, 3, BG_PIXEL_RGBA32F, 0, px};
    assert_int_equal(bg_render_cpu(scene, settings, &img), BG_OK);
    memcpy(out, px + 4 * 4, 4 * sizeof(float));
}

static void centre_ray(bg_scene *scene, const bg_render_settings *settings, double rgb[3])
{
    const bg_scene_state *st = bgi_scene_committed(scene);
    assert_non_null(st);
    double o[3], d[3];
    bgi_cpu_primary_ray(&st->camera, 3, 3, 1, 1, o, d);
    bgi_cpu_shade_ray(st, settings, NULL, o, d, rgb);
}

/* Camera at (0, 0, 5) facing a unit sphere at the origin; one point light at the camera. */
static bg_scene *lit_sphere(double roughness)
{
    bg_scene *scene = new_scene();
    bg_material m = bg_material_init();
    m.base.reflectance.r = 0.5;
    m.base.reflectance.g = 0.6;
    m.base.reflectance.b = 0.7;
    m.base.roughness.value = roughness;
    m.ambient.r = 0.1;
    m.ambient.g = 0.2;
    m.ambient.b = 0.3;
    uint32_t mat = add_material(scene, &m), obj = 0, light = 0;
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(0, 0, 0), 1.0, mat, &obj), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0, 0, 5);
    l.color[0] = 1.0;
    l.color[1] = 0.5;
    l.color[2] = 0.25;
    l.intensity = 2.0;
    l.attenuation[0] = 1.0;
    l.attenuation[1] = 0.1;
    l.attenuation[2] = 0.01;
    assert_int_equal(bg_scene_add_light(scene, &l, &light), BG_OK);
    set_ambient(scene, 0.5, 0.5, 0.5);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    return scene;
}

static void test_centre_hit(void **state)
{
    (void)state;
    bg_scene *scene = lit_sphere(1.0);
    const bg_scene_state *st = bgi_scene_committed(scene);
    double o[3], d[3];
    bgi_cpu_primary_ray(&st->camera, 3, 3, 1, 1, o, d);
    bg_cpu_hit hit;
    assert_true(bgi_cpu_nearest_hit(st, o, d, BG_CPU_NONE, BG_CPU_NONE, &hit));
    rel_near(hit.t, 4.0, 1e-12); /* d - 1 */
    assert_true(hit.normal[2] > 1.0 - 1e-12);
    assert_true(bg_v3_dot(hit.normal, d) < 0.0);
    assert_true(hit.entering);
    bg_scene_destroy(scene);
}

/* Lambertian (r = 1): a = 1, b = c = 0; at the centre v = v' = t = u = 1 so S = C and f = C / pi.
 * Light: distance 4, attenuation 1 + 0.1 * 4 + 0.01 * 16 = 1.56, radiance (1, 0.5, 0.25) * 2 / 1.56.
 * Pixel = pi * f * radiance * v' + ambient 0.5 * (0.1, 0.2, 0.3) = C * radiance + ambient. */
static void test_lambertian_centre(void **state)
{
    (void)state;
    bg_scene *scene = lit_sphere(1.0);
    bg_render_settings s = bg_render_settings_init();
    const double c[3] = {0.5, 0.6, 0.7}, col[3] = {1.0, 0.5, 0.25}, amb[3] = {0.1, 0.2, 0.3};
    double want[3];
    for (int i = 0; i < 3; i++)
        want[i] = c[i] * col[i] * 2.0 / 1.56 + 0.5 * amb[i];
    double rgb[3];
    centre_ray(scene, &s, rgb);
    for (int i = 0; i < 3; i++)
        rel_near(rgb[i], want[i], 1e-9);
    float px[4];
    centre_pixel(scene, &s, px);
    for (int i = 0; i < 3; i++)
        rel_near(px[i], (float)want[i], 1e-7);
    assert_true(px[3] == 1.0f);
    bg_scene_destroy(scene);
}

/* Glossy r = 0.75, p = 1: b = 4 r (1 - r) = 0.75, a = 0.25, c = 0. At the centre t = v = v' = w = 1:
 * G(1) = 1, Z(1) = r / r^2 = 4/3, A(1) = sqrt(p) = 1, D = Z A / (4 pi) + (1 - 1) / pi = 1 / (3 pi).
 * f = C (0.25 / pi + 0.75 / (3 pi)) = C / (2 pi), so the light term is C * radiance / 2. */
static void test_glossy_centre(void **state)
{
    (void)state;
    bg_scene *scene = lit_sphere(0.75);
    bg_render_settings s = bg_render_settings_init();
    const double c[3] = {0.5, 0.6, 0.7}, col[3] = {1.0, 0.5, 0.25}, amb[3] = {0.1, 0.2, 0.3};
    double rgb[3];
    centre_ray(scene, &s, rgb);
    for (int i = 0; i < 3; i++)
        rel_near(rgb[i], 0.5 * c[i] * col[i] * 2.0 / 1.56 + 0.5 * amb[i], 1e-9);
    bg_scene_destroy(scene);
}

/* The BRDF pieces at an off-axis configuration against the paper's formulas written out here. */
static void test_brdf_formulas(void **state)
{
    (void)state;
    double r = 0.3, p = 0.4, t = 0.9, v = 0.7, vl = 0.5, w = 0.6;
    double g = (v / (r - r * v + v)) * (vl / (r - r * vl + vl));
    double z = r / pow(1.0 + r * t * t - t * t, 2.0);
    double a = sqrt(p / (p * p - p * p * w * w + w * w));
    double want = g * z * a / (4.0 * PI * v * vl) + (1.0 - g) / PI;
    rel_near(bgi_cpu_schlick_d(r, p, t, v, vl, w), want, 1e-12);
    double sa, sb, sc;
    bgi_cpu_schlick_split(0.3, &sa, &sb, &sc);
    rel_near(sb, 0.84, 1e-12);
    assert_true(sa == 0.0);
    rel_near(sc, 0.16, 1e-12);
    bgi_cpu_schlick_split(0.8, &sa, &sb, &sc);
    rel_near(sa, 1.0 - 0.64, 1e-12);
    assert_true(sc == 0.0);
    const double cc[3] = {0.2, 0.5, 1.0};
    double s3[3];
    bgi_cpu_schlick_s(cc, 0.5, s3);
    rel_near(s3[0], 0.2 + 0.8 / 32.0, 1e-12);
    rel_near(s3[2], 1.0, 1e-12);
    /* guards: no NaN at r = 0, t = 1 and p = 0, w = 0, v = 0 */
    assert_true(bgi_cpu_schlick_d(0.0, 0.0, 1.0, 1.0, 1.0, 0.0) == 0.0);
    assert_true(bgi_cpu_schlick_d(0.5, 1.0, 1.0, 0.0, 1.0, 1.0) == 0.0);
    double ct;
    rel_near(bgi_cpu_fresnel(1.0, 1.0, 1.5, &ct), 0.04, 1e-12);
    assert_true(bgi_cpu_fresnel(0.1, 1.5, 1.0, &ct) == 1.0); /* total internal reflection */
}

/* A point on the plane straight below a sphere, with the light straight above: ambient only. */
static void test_shadow_ambient_only(void **state)
{
    (void)state;
    bg_scene *scene = new_scene();
    bg_material m = bg_material_init();
    m.ambient.r = 0.2;
    m.ambient.g = 0.3;
    m.ambient.b = 0.4;
    uint32_t mat = add_material(scene, &m), id = 0;
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(0, 0, 0), 1.0, mat, &id), BG_OK);
    assert_int_equal(bg_scene_add_plane(scene, bg_vec3_make(0, -2, 0), bg_vec3_make(0, 1, 0), mat, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0, 10, 0);
    assert_int_equal(bg_scene_add_light(scene, &l, &id), BG_OK);
    set_ambient(scene, 0.5, 0.5, 0.5);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(scene);
    bg_render_settings s = bg_render_settings_init();
    double o[3] = {0, -1.5, 5}, d[3] = {0, -0.5, -5}, rgb[3];
    bg_v3_normalize(d);
    bgi_cpu_shade_ray(st, &s, NULL, o, d, rgb);
    rel_near(rgb[0], 0.1, 1e-12);
    rel_near(rgb[1], 0.15, 1e-12);
    rel_near(rgb[2], 0.2, 1e-12);
    /* control: a point on the plane away from the shadow is lit */
    double o2[3] = {6, -1.5, 5}, rgb2[3];
    bgi_cpu_shade_ray(st, &s, NULL, o2, d, rgb2);
    assert_true(rgb2[0] > 0.1 + 1e-3);
    bg_scene_destroy(scene);
}

/* A mirror (r = 0, C = 1, so c = 1 and S(v) = 1) reflects an emitter behind the camera exactly. */
static void test_mirror_reflects_emitter(void **state)
{
    (void)state;
    bg_scene *scene = new_scene();
    bg_material mirror = bg_material_init();
    mirror.base.reflectance.r = mirror.base.reflectance.g = mirror.base.reflectance.b = 1.0;
    mirror.base.roughness.value = 0.0;
    mirror.ambient.r = mirror.ambient.g = mirror.ambient.b = 0.0;
    bg_material emit = black_emitter(0.25, 0.5, 0.75);
    uint32_t mm = add_material(scene, &mirror), me = add_material(scene, &emit), id = 0;
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(0, 0, 0), 1.0, mm, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(0, 0, 10), 1.0, me, &id), BG_OK);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    bg_render_settings s = bg_render_settings_init();
    s.background[0] = 0.125; /* must not show: the reflected ray hits the emitter */
    float px[4];
    centre_pixel(scene, &s, px);
    assert_true(px[0] == 0.25f && px[1] == 0.5f && px[2] == 0.75f);
    /* no bounce allowed: the mirror alone is black */
    s.max_depth = 0;
    centre_pixel(scene, &s, px);
    assert_true(px[0] == 0.0f && px[1] == 0.0f && px[2] == 0.0f);
    bg_scene_destroy(scene);
}

/* A glass slab (box, transparency 1, ior 1.5, thickness 0.5) in front of an emissive rectangle,
 * seen at normal incidence. Every interface reflects F = ((n - 1) / (n + 1))^2 = 0.04.
 * The emitter is hit at bounce level 2 + 2k after 2k internal reflections with weight
 * (1 - F)^2 F^(2k); the level-3 ray of k = 1 has weight (1 - F) F^2 = 0.001536. */
static bg_scene *glass_slab(void)
{
    bg_scene *scene = new_scene();
    bg_material glass = bg_material_init();
    glass.base.reflectance.r = glass.base.reflectance.g = glass.base.reflectance.b = 0.04;
    glass.base.roughness.value = 0.0;
    glass.transparency.value = 1.0;
    glass.ior = 1.5;
    bg_material emit = black_emitter(1.0, 2.0, 4.0);
    uint32_t mg = add_material(scene, &glass), me = add_material(scene, &emit), id = 0;
    bg_object_desc slab = bg_object_desc_init(BG_SHAPE_BOX, mg);
    slab.transform = bg_mat4_scale(2, 2, 0.25);
    assert_int_equal(bg_scene_add_object(scene, &slab, &id), BG_OK);
    bg_object_desc rect = bg_object_desc_init(BG_SHAPE_RECTANGLE, me);
    rect.transform = bg_mat4_mul(bg_mat4_translate(0, 0, -3),
                                 bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 0, 0), 90.0), bg_mat4_scale(5, 1, 5)));
    assert_int_equal(bg_scene_add_object(scene, &rect, &id), BG_OK);
    set_ambient(scene, 0.0, 0.0, 0.0);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    return scene;
}

static void test_glass_slab(void **state)
{
    (void)state;
    bg_scene *scene = glass_slab();
    const double e[3] = {1.0, 2.0, 4.0}, f = 0.04;
    double rgb[3];
    bg_render_settings s = bg_render_settings_init();
    /* defaults (max_depth 5, min_weight 1/512): only k = 0 survives */
    centre_ray(scene, &s, rgb);
    for (int i = 0; i < 3; i++)
        rel_near(rgb[i], e[i] * (1 - f) * (1 - f), 1e-9);
    /* min_weight 0: levels 2 and 4 reach the emitter (k = 0, 1); k = 2 would need level 6 */
    s.min_weight = 0.0;
    centre_ray(scene, &s, rgb);
    for (int i = 0; i < 3; i++)
        rel_near(rgb[i], e[i] * (1 - f) * (1 - f) * (1 + f * f), 1e-9);
    /* max_depth 7: k = 0, 1, 2 */
    s.max_depth = 7;
    centre_ray(scene, &s, rgb);
    for (int i = 0; i < 3; i++)
        rel_near(rgb[i], e[i] * (1 - f) * (1 - f) * (1 + f * f + f * f * f * f), 1e-9);
    /* max_depth 1: the emitter (level 2) is out of reach */
    s.max_depth = 1;
    centre_ray(scene, &s, rgb);
    assert_true(rgb[0] == 0.0 && rgb[1] == 0.0 && rgb[2] == 0.0);
    bg_scene_destroy(scene);
}

/* Two facing mirror planes with emission 1 and S(1) = C = 0.5: the centre ray collects
 * sum_k 0.5^k over bounce levels k = 0 .. max_depth, cut where 0.5^k < min_weight. */
static void test_depth_and_min_weight(void **state)
{
    (void)state;
    bg_scene *scene = new_scene();
    bg_material m = bg_material_init();
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 0.5;
    m.base.roughness.value = 0.0;
    m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    m.emission.r = m.emission.g = m.emission.b = 1.0;
    uint32_t mat = add_material(scene, &m), id = 0;
    assert_int_equal(bg_scene_add_plane(scene, bg_vec3_make(0, 0, -1), bg_vec3_make(0, 0, 1), mat, &id), BG_OK);
    assert_int_equal(bg_scene_add_plane(scene, bg_vec3_make(0, 0, 1), bg_vec3_make(0, 0, -1), mat, &id), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0, 0, 0);
    cam.look_at = bg_vec3_make(0, 0, -1);
    assert_int_equal(bg_scene_set_camera(scene, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    bg_render_settings s = bg_render_settings_init();
    double rgb[3];
    /* defaults: max_depth 5 bounds it first */
    centre_ray(scene, &s, rgb);
    rel_near(rgb[0], 2.0 - pow(0.5, 5), 1e-12);
    /* max_depth 64: min_weight 1/512 keeps levels 0 .. 9 */
    s.max_depth = 64;
    centre_ray(scene, &s, rgb);
    rel_near(rgb[1], 2.0 - pow(0.5, 9), 1e-12);
    /* no pruning: all 65 levels */
    s.min_weight = 0.0;
    centre_ray(scene, &s, rgb);
    rel_near(rgb[2], 2.0 - pow(0.5, 64), 1e-12);
    s.max_depth = 0;
    centre_ray(scene, &s, rgb);
    rel_near(rgb[0], 1.0, 1e-12);
    bg_scene_destroy(scene);
}

/* GL_LINEAR with GL's texel centres, both wrap modes, and the row order (texture row 0 is v = 0,
 * the bottom row of the source image). Texels: top row red, green; bottom row blue, white. */
static void test_texture_sampling(void **state)
{
    (void)state;
    bg_scene *scene = new_scene();
    unsigned char px[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    bg_image img = {2, 2, BG_PIXEL_RGBA8, 0, px};
    bg_texture_desc rep = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR, BG_FILTER_LINEAR}, clamp = {BG_WRAP_CLAMP, BG_TEXTURE_LINEAR, BG_FILTER_LINEAR};
    uint32_t tr = 0, tc = 0;
    assert_int_equal(bg_scene_add_texture(scene, &img, &rep, &tr), BG_OK);
    assert_int_equal(bg_scene_add_texture(scene, &img, &clamp, &tc), BG_OK);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(scene);
    const bg_texture_data *r = &st->textures[tr - 1], *c = &st->textures[tc - 1];
    double v[4];
    bgi_cpu_texture_sample(r, 0.25, 0.25, v); /* texel centre (0, 0): bottom-left = blue */
    assert_true(v[0] == 0.0 && v[1] == 0.0 && v[2] == 1.0 && v[3] == 1.0);
    bgi_cpu_texture_sample(r, 0.25, 0.75, v); /* top-left = red */
    assert_true(v[0] == 1.0 && v[1] == 0.0 && v[2] == 0.0);
    bgi_cpu_texture_sample(r, 0.5, 0.5, v); /* the mean of all four */
    assert_true(v[0] == 0.5 && v[1] == 0.5 && v[2] == 0.5);
    bgi_cpu_texture_sample(r, 0.375, 0.25, v); /* a quarter of the way from blue to white */
    assert_true(v[0] == 0.25 && v[1] == 0.25 && v[2] == 1.0);
    bgi_cpu_texture_sample(r, 0.0, 0.25, v); /* REPEAT: half white (column -1 = 1), half blue */
    assert_true(v[0] == 0.5 && v[1] == 0.5 && v[2] == 1.0);
    bgi_cpu_texture_sample(r, 1.25, -0.75, v); /* REPEAT: same as (0.25, 0.25) */
    assert_true(v[0] == 0.0 && v[1] == 0.0 && v[2] == 1.0);
    bgi_cpu_texture_sample(c, 0.0, 0.25, v); /* CLAMP_TO_EDGE: blue only */
    assert_true(v[0] == 0.0 && v[1] == 0.0 && v[2] == 1.0);
    bgi_cpu_texture_sample(c, -3.0, 7.0, v); /* far outside: the top-left corner texel */
    assert_true(v[0] == 1.0 && v[1] == 0.0 && v[2] == 0.0);

    /* GL_NEAREST: the texel whose square holds the point, whatever the distance to its centre. */
    bg_texture_desc near_rep = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR, BG_FILTER_NEAREST};
    bg_texture_desc near_clamp = {BG_WRAP_CLAMP, BG_TEXTURE_LINEAR, BG_FILTER_NEAREST};
    uint32_t nr = 0, nc = 0;
    bg_scene *ns = new_scene();
    assert_int_equal(bg_scene_add_texture(ns, &img, &near_rep, &nr), BG_OK);
    assert_int_equal(bg_scene_add_texture(ns, &img, &near_clamp, &nc), BG_OK);
    assert_int_equal(bg_scene_commit(ns), BG_OK);
    const bg_texture_data *n = &bgi_scene_committed(ns)->textures[nr - 1];
    const bg_texture_data *ncl = &bgi_scene_committed(ns)->textures[nc - 1];
    bgi_cpu_texture_sample(n, 0.49, 0.01, v); /* bottom-left square: blue, no blend toward white */
    assert_true(v[0] == 0.0 && v[1] == 0.0 && v[2] == 1.0);
    bgi_cpu_texture_sample(n, 0.5, 0.5, v); /* a corner belongs to the square above and right: green */
    assert_true(v[0] == 0.0 && v[1] == 1.0 && v[2] == 0.0);
    bgi_cpu_texture_sample(n, -0.25, 1.75, v); /* REPEAT: (0.75, 0.75), top-right: green */
    assert_true(v[0] == 0.0 && v[1] == 1.0 && v[2] == 0.0);
    bgi_cpu_texture_sample(ncl, 1.0, 1.0, v); /* CLAMP's upper edge: the last texel, top-right */
    assert_true(v[0] == 0.0 && v[1] == 1.0 && v[2] == 0.0);
    bgi_cpu_texture_sample(ncl, -2.0, 0.75, v); /* far left: the left column, top row: red */
    assert_true(v[0] == 1.0 && v[1] == 0.0 && v[2] == 0.0);
    bg_scene_destroy(ns);

    /* material parameters: constant x texel, scalar from one channel, then clamped */
    bg_material m = bg_material_init();
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 0.5;
    m.base.reflectance.texture = tr;
    m.base.roughness.value = 1.0;
    m.base.roughness.texture = tc;
    m.base.roughness.channel = 1;
    bg_cpu_surface surf;
    const double uv[2] = {0.75, 0.75}; /* top-right = green */
    bgi_cpu_surface_eval(st, &m, uv, &surf);
    assert_true(surf.base.c[0] == 0.0 && surf.base.c[1] == 0.5 && surf.base.c[2] == 0.0);
    assert_true(surf.base.r == 1.0);
    const double uv2[2] = {0.25, 0.25}; /* blue: green channel 0 */
    bgi_cpu_surface_eval(st, &m, uv2, &surf);
    assert_true(surf.base.r == 0.0);
    bg_scene_destroy(scene);
}

static void test_empty_and_unlit(void **state)
{
    (void)state;
    bg_scene *scene = new_scene();
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    bg_render_settings s = bg_render_settings_init();
    s.background[0] = 0.25;
    s.background[1] = 0.5;
    s.background[2] = 1.0;
    float px[4];
    centre_pixel(scene, &s, px);
    assert_true(px[0] == 0.25f && px[1] == 0.5f && px[2] == 1.0f && px[3] == 1.0f);
    bg_scene_destroy(scene);

    /* no lights: ambient x material ambient + emission */
    scene = new_scene();
    bg_material m = bg_material_init();
    m.ambient.r = 0.5;
    m.emission.g = 0.25;
    uint32_t mat = add_material(scene, &m), id = 0;
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(0, 0, 0), 1.0, mat, &id), BG_OK);
    set_ambient(scene, 0.5, 1.0, 1.0);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    centre_pixel(scene, &s, px);
    rel_near(px[0], 0.25, 1e-7);
    rel_near(px[1], 0.1 + 0.25, 1e-7);
    rel_near(px[2], 0.1, 1e-7);
    bg_scene_destroy(scene);
}

/* A non-trivial scene: checker-textured floor, earth-textured sphere, mirror, glass, shadows. */
static bg_scene *busy_scene(void)
{
    bg_scene *scene = new_scene();
    uint32_t checker = 0, earth = 0, id = 0;
    const unsigned char a[3] = {230, 230, 230}, b[3] = {40, 40, 160};
    assert_int_equal(scenes_add_checker_texture(scene, a, b, &checker), BG_OK);
    assert_int_equal(scenes_add_earth_texture(scene, &earth), BG_OK);
    bg_material floor = bg_material_init();
    floor.base.reflectance.texture = checker;
    bg_material globe = bg_material_init();
    globe.base.reflectance.r = globe.base.reflectance.g = globe.base.reflectance.b = 1.0;
    globe.base.reflectance.texture = earth;
    globe.base.roughness.value = 0.6;
    globe.base.isotropy.value = 0.5;
    bg_material mirror = bg_material_init();
    mirror.base.reflectance.r = mirror.base.reflectance.g = mirror.base.reflectance.b = 0.9;
    mirror.base.roughness.value = 0.1;
    bg_material glass = bg_material_init();
    glass.base.roughness.value = 0.0;
    glass.base.reflectance.r = glass.base.reflectance.g = glass.base.reflectance.b = 0.04;
    glass.transparency.value = 0.9;
    glass.ior = 1.5;
    bg_material coat = bg_material_init();
    coat.has_coat = true;
    coat.coat.reflectance.r = coat.coat.reflectance.g = coat.coat.reflectance.b = 0.05;
    coat.coat.roughness.value = 0.2;
    uint32_t mf = add_material(scene, &floor), mg = add_material(scene, &globe), mm = add_material(scene, &mirror),
             mt = add_material(scene, &glass), mc = add_material(scene, &coat);
    bg_object_desc pd = bg_object_desc_init(BG_SHAPE_PLANE, mf);
    pd.transform = bg_mat4_translate(0, -1, 0);
    pd.uv_scale[0] = pd.uv_scale[1] = 0.25;
    assert_int_equal(bg_scene_add_object(scene, &pd, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(-1.2, 0, 0), 1.0, mg, &id), BG_OK);
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(1.2, 0, -0.5), 1.0, mm, &id), BG_OK);
    bg_object_desc bd = bg_object_desc_init(BG_SHAPE_BOX, mt);
    bd.transform = bg_mat4_mul(bg_mat4_translate(0, -0.4, 1.6),
                               bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 30.0), bg_mat4_scale(0.5, 0.6, 0.3)));
    assert_int_equal(bg_scene_add_object(scene, &bd, &id), BG_OK);
    bg_object_desc cd = bg_object_desc_init(BG_SHAPE_CYLINDER, mc);
    cd.transform = bg_mat4_mul(bg_mat4_translate(0.3, -0.5, -2.5), bg_mat4_scale(0.5, 0.5, 0.5));
    assert_int_equal(bg_scene_add_object(scene, &cd, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(3, 5, 4);
    l.intensity = 1.2;
    assert_int_equal(bg_scene_add_light(scene, &l, &id), BG_OK);
    bg_light sun = bg_light_init();
    sun.type = BG_LIGHT_DIRECTIONAL;
    sun.direction = bg_vec3_make(-0.3, -1, -0.2);
    sun.intensity = 0.5;
    assert_int_equal(bg_scene_add_light(scene, &sun, &id), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0, 1.5, 6);
    cam.look_at = bg_vec3_make(0, -0.3, 0);
    assert_int_equal(bg_scene_set_camera(scene, &cam), BG_OK);
    set_ambient(scene, 0.3, 0.3, 0.3);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    return scene;
}

static void test_threads_identical(void **state)
{
    (void)state;
    bg_scene *scene = busy_scene();
    enum { W = 67, H = 45 };
    const int counts[3] = {1, 2, 7};
    float *img[3];
    unsigned char *img8[3];
    for (int k = 0; k < 3; k++) {
        img[k] = calloc((size_t)W * H * 4, sizeof(float));
        img8[k] = calloc((size_t)W * H * 4, 1);
        assert_non_null(img[k]);
        assert_non_null(img8[k]);
        bg_render_settings s = bg_render_settings_init();
        s.threads = counts[k];
        bg_image f = {W, H, BG_PIXEL_RGBA32F, 0, img[k]};
        assert_int_equal(bg_render_cpu(scene, &s, &f), BG_OK);
        bg_image b = {W, H, BG_PIXEL_RGBA8, 0, img8[k]};
        assert_int_equal(bg_render_cpu(scene, &s, &b), BG_OK);
    }
    assert_memory_equal(img[0], img[1], (size_t)W * H * 4 * sizeof(float));
    assert_memory_equal(img[0], img[2], (size_t)W * H * 4 * sizeof(float));
    assert_memory_equal(img8[0], img8[1], (size_t)W * H * 4);
    assert_memory_equal(img8[0], img8[2], (size_t)W * H * 4);
    /* the scene is non-trivial: many distinct values */
    int distinct = 0;
    for (int i = 1; i < W * H; i++)
        distinct += img[0][4 * i] != img[0][4 * (i - 1)];
    assert_true(distinct > W * H / 2);
    for (int k = 0; k < 3; k++) {
        free(img[k]);
        free(img8[k]);
    }
    bg_scene_destroy(scene);
}

static void test_stride_and_encoding(void **state)
{
    (void)state;
    bg_scene *scene = busy_scene();
    enum { W = 20, H = 10, PAD = 12 };
    unsigned char tight[W * H * 4], padded[H * (W * 4 + PAD)];
    float lin[W * H * 4];
    memset(padded, 0xAB, sizeof padded);
    bg_render_settings s = bg_render_settings_init();
    bg_image a = {W, H, BG_PIXEL_RGBA8, 0, tight};
    bg_image b = {W, H, BG_PIXEL_RGBA8, W * 4 + PAD, padded};
    bg_image f = {W, H, BG_PIXEL_RGBA32F, 0, lin};
    assert_int_equal(bg_render_cpu(scene, &s, &a), BG_OK);
    assert_int_equal(bg_render_cpu(scene, &s, &b), BG_OK);
    assert_int_equal(bg_render_cpu(scene, &s, &f), BG_OK);
    for (int y = 0; y < H; y++) {
        const unsigned char *row = padded + (size_t)y * (W * 4 + PAD);
        assert_memory_equal(row, tight + (size_t)y * W * 4, W * 4);
        for (int k = 0; k < PAD; k++)
            assert_int_equal(row[W * 4 + k], 0xAB);
    }
    /* RGBA8 is the sRGB encoding of the linear float (float rounding may move the 8-bit value by one) */
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            int want = bgi_encode_channel(lin[4 * i + c], BG_ENCODING_SRGB);
            assert_true(abs(want - tight[4 * i + c]) <= 1);
        }
        assert_int_equal(tight[4 * i + 3], 255);
    }
    /* the encodings themselves */
    assert_int_equal(bgi_encode_channel(0.5, BG_ENCODING_LINEAR), 128);
    assert_int_equal(bgi_encode_channel(2.0, BG_ENCODING_LINEAR), 255);
    assert_int_equal(bgi_encode_channel(-1.0, BG_ENCODING_SRGB), 0);
    assert_int_equal(bgi_encode_channel(0.5, BG_ENCODING_SRGB), 188); /* 0.735357 * 255 = 187.5 */
    rel_near(bgi_linear_to_srgb(0.001), 0.01292, 1e-12);
    bg_scene_destroy(scene);
}

static void test_shared_scenes_finite(void **state)
{
    (void)state;
    enum { W = 48, H = 40 };
    float *px = malloc((size_t)W * H * 4 * sizeof(float));
    assert_non_null(px);
    for (int id = 0; id < SCENE_COUNT; id++) {
        bg_scene *scene = new_scene();
        bg_status st = scenes_build((scene_id)id, scene);
        if (st != BG_OK)
            fail_msg("scene %s: %s", scenes_name((scene_id)id), bg_scene_error_message(scene));
        bg_render_settings s = bg_render_settings_init();
        bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, px};
        assert_int_equal(bg_render_cpu(scene, &s, &img), BG_OK);
        for (int i = 0; i < W * H * 4; i++)
            if (!isfinite(px[i]) || px[i] < 0.0f)
                fail_msg("scene %s: pixel value %d is %g", scenes_name((scene_id)id), i, (double)px[i]);
        bg_scene_destroy(scene);
    }
    free(px);
}

/* A bad image is refused with the shared check's message, prefixed by the call and naming the field. */
static void assert_image_rejected(bg_scene *scene, const bg_render_settings *s, bg_image *bad, const char *field)
{
    bg_scene_clear_error(scene);
    assert_int_equal(bg_render_cpu(scene, s, bad), BG_ERR_INVALID_ARGUMENT);
    const char *message = bg_scene_error_message(scene);
    assert_non_null(strstr(message, "bg_render_cpu: "));
    assert_non_null(strstr(message, field));
}

static void test_errors(void **state)
{
    (void)state;
    unsigned char px[16 * 4];
    bg_image img = {4, 4, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings s = bg_render_settings_init();
    assert_int_equal(bg_render_cpu(NULL, &s, &img), BG_ERR_INVALID_ARGUMENT);

    bg_scene *scene = new_scene();
    /* never committed */
    assert_int_equal(bg_render_cpu(scene, &s, &img), BG_ERR_NOT_COMMITTED);
    assert_int_equal(bg_scene_error(scene), BG_ERR_NOT_COMMITTED);
    bg_scene_clear_error(scene);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    assert_int_equal(bg_render_cpu(scene, &s, &img), BG_OK);

    assert_int_equal(bg_render_cpu(scene, NULL, &img), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_render_cpu(scene, &s, NULL), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_scene_error(scene), BG_ERR_INVALID_ARGUMENT);
    assert_true(strlen(bg_scene_error_message(scene)) > 0);

    bg_image bad = img;
    bad.pixels = NULL;
    assert_image_rejected(scene, &s, &bad, "image pixels");
    bad = img;
    bad.width = 0;
    assert_image_rejected(scene, &s, &bad, "image width");
    bad = img;
    bad.height = -3;
    assert_image_rejected(scene, &s, &bad, "image height");
    bad = img;
    bad.width = 16385;
    assert_image_rejected(scene, &s, &bad, "image width");
    bad = img;
    bad.stride = 15; /* below 4 * 4 */
    assert_image_rejected(scene, &s, &bad, "image stride");
    bad = img;
    bad.format = (bg_pixel_format)7;
    assert_image_rejected(scene, &s, &bad, "image format");

    bg_render_settings b = s;
    b.max_depth = 65;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.max_depth = -1;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.threads = 257;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.threads = -1;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.min_weight = NAN;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.min_weight = -1.0;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.background[1] = INFINITY;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.background[2] = -0.5;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = s;
    b.encoding = (bg_output_encoding)9;
    assert_int_equal(bg_render_cpu(scene, &b, &img), BG_ERR_INVALID_ARGUMENT);

    /* the defaults of bg_render_settings_init */
    assert_int_equal(s.max_depth, 5);
    assert_true(s.min_weight == 1.0 / 512.0);
    assert_int_equal(s.threads, 0);
    assert_int_equal(s.encoding, BG_ENCODING_SRGB);
    assert_true(s.background[0] == 0.0 && s.background[1] == 0.0 && s.background[2] == 0.0);
    bg_scene_destroy(scene);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_centre_hit),
        cmocka_unit_test(test_lambertian_centre),
        cmocka_unit_test(test_glossy_centre),
        cmocka_unit_test(test_brdf_formulas),
        cmocka_unit_test(test_shadow_ambient_only),
        cmocka_unit_test(test_mirror_reflects_emitter),
        cmocka_unit_test(test_glass_slab),
        cmocka_unit_test(test_depth_and_min_weight),
        cmocka_unit_test(test_texture_sampling),
        cmocka_unit_test(test_empty_and_unlit),
        cmocka_unit_test(test_threads_identical),
        cmocka_unit_test(test_stride_and_encoding),
        cmocka_unit_test(test_shared_scenes_finite),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
