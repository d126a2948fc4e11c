/* The path integrator in the CPU reference (docs/shading.md 13), against what follows from the
 * scene alone: the white furnace (a sphere in a uniform environment), an emitting white box whose
 * every path is exact, a box lit by a black emitter, the direct light of a rectangle light equal to
 * Whitted's sample by sample, and the refusals. Bounds come from the estimator's range: with n
 * samples of a value in [0, M], Hoeffding's inequality puts the mean within
 * M sqrt(ln(2 / delta) / (2 n)) of its expectation with probability 1 - delta. */
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

#define PI 3.14159265358979323846

static uint32_t lambertian(bg_scene *s, double c, const double emission[3])
{
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){c, c, c, 0};
    m.base.roughness.value = 1.0;
    if (emission)
        m.emission = (bg_color_param){emission[0], emission[1], emission[2], 0};
    uint32_t id;
    if (bg_scene_add_material(s, &m, &id) != BG_OK)
        fail_msg("bg_scene_add_material: %s", bg_scene_error_message(s));
    return id;
}

static bg_render_settings path_settings(int samples, int max_depth)
{
    bg_render_settings set = bg_render_settings_init();
    set.integrator = BG_INTEGRATOR_PATH;
    set.samples = samples;
    set.max_depth = max_depth;
    return set;
}

/* The CPU's linear RGBA32F image; the caller frees it. */
static float *render(bg_scene *s, const bg_render_settings *set, int w, int h)
{
    float *px = malloc((size_t)w * h * 4 * sizeof *px);
    assert_non_null(px);
    bg_image img = {w, h, BG_PIXEL_RGBA32F, 0, px};
    bg_status st = bg_render_cpu(s, set, &img);
    if (st != BG_OK)
        fail_msg("bg_render_cpu: %s", bg_scene_error_message(s));
    return px;
}

static void look(bg_scene *s, bg_vec3 from, bg_vec3 at, double fov)
{
    bg_camera c = bg_camera_init();
    c.position = from;
    c.look_at = at;
    c.up = bg_vec3_make(0, 1, 0);
    c.fov_y_degrees = fov;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
}

/* A uniform environment of radiance radiance that lights the scene by the given sampling. */
static void uniform_sky(bg_scene *s, double radiance, bg_environment_sampling sampling)
{
    float texels[8 * 4 * 4];
    for (int i = 0; i < 8 * 4 * 4; i++)
        texels[i] = (float)radiance;
    bg_image img = {8, 4, BG_PIXEL_RGBA32F, 0, texels};
    uint32_t tex;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &tex), BG_OK);
    bg_environment e = bg_environment_init();
    e.texture = tex;
    e.lights = true;
    e.sampling = sampling;
    assert_int_equal(bg_scene_set_environment(s, &e), BG_OK);
}

/* Hoeffding's half-width for the mean of n values in [0, range] at failure probability delta. */
static double hoeffding(double range, int n, double delta)
{
    return range * sqrt(log(2.0 / delta) / (2.0 * n));
}

/* ---- the white furnace ---- */

enum { FW = 12, FH = 12, FURNACE_SAMPLES = 256 };

/* Schlick's isotropic glossy factor D (docs/shading.md 6.2, p = 1 so A = 1), written out here from
 * the formula rather than taken from the renderer. */
static double schlick_d(double r, double t, double v, double vl)
{
    double g = v / (r - r * v + v) * (vl / (r - r * vl + vl));
    double zd = 1.0 + r * t * t - t * t, z = r / (zd * zd);
    return g * z / (4.0 * PI * v * vl) + (1.0 - g) / PI;
}

/* The share of a uniform environment a single layer of reflectance c and roughness r returns
 * towards a viewer at cos v: integral S(V.H) (a / pi + b D) (n.L) dL over the hemisphere plus the
 * mirror share c_s S(v) (6.3), by the midpoint rule in (cos theta, phi); a 400 x 400 grid is
 * exact to about 1e-4 for r >= 0.3. For r = 1 it is 13.4's rho(v). */
static double layer_albedo(double c, double r, double v)
{
    enum { NT = 400, NP = 400 };
    double b = 4.0 * r * (1.0 - r), a = r < 0.5 ? 0.0 : 1.0 - b, cs = r < 0.5 ? 1.0 - b : 0.0;
    double view[3] = {sqrt(1.0 - v * v), 0.0, v}, sum = 0.0;
    for (int i = 0; i < NT; i++) {
        double ct = (i + 0.5) / NT, st = sqrt(1.0 - ct * ct);
        for (int j = 0; j < NP; j++) {
            double phi = 2.0 * PI * (j + 0.5) / NP;
            double l[3] = {st * cos(phi), st * sin(phi), ct};
            double h[3] = {view[0] + l[0], view[1] + l[1], view[2] + l[2]};
            double len = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
            double u = (view[0] * h[0] + view[1] * h[1] + view[2] * h[2]) / len, t = h[2] / len;
            double k = 1.0 - u;
            double f = a / PI + (b > 0.0 ? b * schlick_d(r, t > 1.0 ? 1.0 : t, v, ct) : 0.0);
            sum += (c + (1.0 - c) * k * k * k * k * k) * f * ct;
        }
    }
    double k = 1.0 - v;
    return sum * (2.0 * PI / NP) * (1.0 / NT) + cs * (c + (1.0 - c) * k * k * k * k * k);
}

/* A sphere of reflectance c and roughness r (or glass, transparency 1) in a uniform environment
 * of radiance L: every pixel that sees only the sphere is L times the albedo towards it on average
 * (layer_albedo), L itself for c = 1, r = 1 (S = 1) and for glass (F + (1 - F) = 1 at each
 * interface, and every path leaves the sphere), since a convex object sees nothing of itself
 * from outside. One sample of a pixel is at most M L: the environment's sample gives
 * f L v' / p_env w <= f_max 4 pi L, the BRDF's path L w / P <= L; M = 5 bounds the Lambertian
 * layers (f <= 1 / pi) and glass, and is computed from f's largest value for a glossy layer. The
 * pixels whose whole square sees the sphere are checked against Hoeffding's bound at
 * delta = 1e-4 per pixel, and the mean of all of them at delta = 1e-4. */
static void furnace(double c, double r, bool glass, bg_environment_sampling sampling)
{
    const double L = 0.75;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    const double none[3] = {0, 0, 0};
    assert_int_equal(bg_scene_set_ambient(s, none), BG_OK);
    bg_material mat = bg_material_init();
    mat.base.reflectance = (bg_color_param){c, c, c, 0};
    mat.base.roughness.value = r;
    mat.transparency.value = glass ? 1.0 : 0.0;
    uint32_t m, id;
    assert_int_equal(bg_scene_add_material(s, &mat, &m), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1.0, m, &id), BG_OK);
    look(s, bg_vec3_make(0, 0, 4), bg_vec3_make(0, 0, 0), 20.0);
    uniform_sky(s, L, sampling);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    bg_render_settings set = path_settings(FURNACE_SAMPLES, glass ? 64 : 5);
    float *px = render(s, &set, FW, FH);
    /* f's largest value over the grid of layer_albedo, for the glossy layer's range. */
    double range = 5.0;
    if (!glass && r < 1.0) {
        double b = 4.0 * r * (1.0 - r), fmax = 0.0;
        for (int i = 1; i <= 100; i++)
            for (int j = 1; j <= 100; j++)
                for (int k = 0; k <= 100; k++) {
                    double f = b * schlick_d(r, k / 100.0, i / 100.0, j / 100.0);
                    fmax = f > fmax ? f : fmax;
                }
        range = 4.0 * PI * fmax + 1.0;
    }
    double pixel_bound = hoeffding(range * L, FURNACE_SAMPLES, 1e-4), worst = 0.0, sum = 0.0, expected_sum = 0.0;
    int inner = 0;
    double errors[FW * FH];
    double half = tan(10.0 * PI / 180.0);
    for (int y = 0; y < FH; y++)
        for (int x = 0; x < FW; x++) {
            /* The pixel's centre ray and whether its four corners meet the sphere. */
            bool all = true;
            double v_centre = 0.0;
            for (int k = 0; k < 5; k++) {
                double fx = k < 4 ? x + (k & 1) : x + 0.5, fy = k < 4 ? y + (k >> 1) : y + 0.5;
                double d[3] = {(2.0 * fx / FW - 1.0) * half, (1.0 - 2.0 * fy / FH) * half, -1.0};
                double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (int i = 0; i < 3; i++)
                    d[i] /= len;
                /* |o + t d| = 1 with o = (0, 0, 4): t^2 + 2 t (o.d) + 15 = 0. */
                double b = 4.0 * d[2], disc = b * b - 15.0;
                if (disc <= 0.0) {
                    all = false;
                    continue;
                }
                double t = -b - sqrt(disc), p[3] = {t * d[0], t * d[1], 4.0 + t * d[2]};
                if (k == 4)
                    v_centre = -(p[0] * d[0] + p[1] * d[1] + p[2] * d[2]);
            }
            if (!all)
                continue;
            double expected = L * (glass || (c == 1.0 && r == 1.0) ? 1.0 : layer_albedo(c, r, v_centre));
            double got = px[4 * (y * FW + x)];
            errors[inner] = got - expected;
            double e = fabs(got - expected);
            worst = e > worst ? e : worst;
            sum += got;
            expected_sum += expected;
            inner++;
        }
    double mean_bound = hoeffding(range * L, FURNACE_SAMPLES * inner, 1e-4);
    /* Hoeffding's bound holds for any estimator in that range; stratification makes the actual
     * error far smaller, so the mean error is also held to 4 standard errors of the pixels' own
     * spread (plus the quadrature's 1e-4), which a bias of a few thousandths would break. */
    double mean_error = 0.0, spread = 0.0;
    for (int i = 0; i < inner; i++)
        mean_error += errors[i] / inner;
    for (int i = 0; i < inner; i++)
        spread += (errors[i] - mean_error) * (errors[i] - mean_error) / (inner - 1);
    double standard_error = sqrt(spread / inner);
    print_message("furnace %s c = %.1f r = %.1f, %s sampling: %d pixels, largest error %.4f (bound %.4f), mean %.5f "
                  "against %.5f (bound %.4f; 4 standard errors %.5f)\n", glass ? "glass" : "layer", c, r,
                  sampling == BG_ENVIRONMENT_UNIFORM ? "uniform" : "importance", inner, worst, pixel_bound, sum / inner,
                  expected_sum / inner, mean_bound, 4.0 * standard_error);
    assert_true(inner >= 20);
    assert_true(worst <= pixel_bound);
    assert_true(fabs(sum - expected_sum) / inner <= mean_bound);
    assert_true(fabs(mean_error) <= 4.0 * standard_error + 1e-4);
    free(px);
    bg_scene_destroy(s);
}

static void white_furnace_returns_the_environment(void **state)
{
    (void)state;
    furnace(1.0, 1.0, false, BG_ENVIRONMENT_UNIFORM);
    furnace(1.0, 1.0, false, BG_ENVIRONMENT_IMPORTANCE);
}

static void half_furnace_returns_the_albedo(void **state)
{
    (void)state;
    furnace(0.5, 1.0, false, BG_ENVIRONMENT_UNIFORM);
}

/* The glossy lobe's draw, its mix with the cosine, the mirror share and their choice. */
static void glossy_furnace_returns_the_albedo(void **state)
{
    (void)state;
    furnace(1.0, 0.3, false, BG_ENVIRONMENT_UNIFORM);
    furnace(0.6, 0.7, false, BG_ENVIRONMENT_IMPORTANCE);
}

/* Reflection and refraction chosen by Fresnel's weights, inside and outside. */
static void glass_furnace_returns_the_environment(void **state)
{
    (void)state;
    furnace(0.8, 1.0, true, BG_ENVIRONMENT_UNIFORM);
}

/* ---- closed boxes ---- */

/* The six faces of the cube [-1, 1]^3 as rectangles facing inwards, each a little larger than
 * the face, so that no ray leaves through an edge. */
static void inward_box(bg_scene *s, uint32_t material)
{
    const double k = 1.02;
    const struct {
        bg_vec3 axis;
        double angle;
    } faces[6] = {{{1, 0, 0}, 0}, {{1, 0, 0}, 180}, {{0, 0, 1}, 90}, {{0, 0, 1}, -90}, {{1, 0, 0}, 90}, {{1, 0, 0}, -90}};
    for (int f = 0; f < 6; f++) {
        /* The prototype rectangle lies in y = 0 facing +y: moved to y = -1, it is the floor, and
         * each rotation about the origin turns the floor into another face, still facing in. */
        bg_object_desc d = bg_object_desc_init(BG_SHAPE_RECTANGLE, material);
        d.transform = bg_mat4_mul(bg_mat4_rotate(faces[f].axis, faces[f].angle),
                                  bg_mat4_mul(bg_mat4_translate(0, -1, 0), bg_mat4_scale(k, 1, k)));
        uint32_t id;
        if (bg_scene_add_object(s, &d, &id) != BG_OK)
            fail_msg("bg_scene_add_object: %s", bg_scene_error_message(s));
    }
}

/* Walls of reflectance 1 (S = 1: f = 1 / pi exactly) that emit E: the cosine-drawn bounce has
 * weight exactly 1 and every path adds E at each of its max_depth + 1 hits, so every pixel is
 * E (max_depth + 1) up to rounding, whatever the samples: no noise at all. Roulette never ends a
 * path whose weight is 1. */
static void emitting_white_box_is_exact(void **state)
{
    (void)state;
    const double emit[3] = {0.25, 0.5, 1.0};
    for (int depth = 0; depth <= 6; depth += 3) {
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        inward_box(s, lambertian(s, 1.0, emit));
        look(s, bg_vec3_make(0.2, -0.1, 0.5), bg_vec3_make(-0.3, 0.2, -1), 70.0);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        bg_render_settings set = path_settings(4, depth);
        float *px = render(s, &set, 16, 12);
        double worst = 0.0;
        for (int i = 0; i < 16 * 12; i++)
            for (int c = 0; c < 3; c++) {
                double expected = emit[c] * (depth + 1);
                double e = fabs(px[4 * i + c] - expected) / expected;
                worst = e > worst ? e : worst;
            }
        print_message("emitting white box, max_depth %d: largest relative error %.3g\n", depth, worst);
        assert_true(worst < 1e-6); /* float output of a double sum */
        free(px);
        bg_scene_destroy(s);
    }
}

/* Walls of reflectance 0.6 lit by a visible rectangle light just under the ceiling: no surface
 * reflects more than it receives (albedo <= 0.62 here, 13.4's quadrature), so no pixel exceeds the
 * light's radiance Le, which its own pixels show exactly; and the mean over the image settles as
 * the samples grow (16 and 64 against 256). */
/* The box of walls of reflectance 0.6 under a rectangle light just below its ceiling, seen by a
 * camera whose view may include the light. */
static bg_scene *box_under_light(bool visible, bool light_in_view)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    inward_box(s, lambertian(s, 0.6, NULL));
    bg_light l = bg_light_init();
    l.type = BG_LIGHT_RECTANGLE;
    l.position = bg_vec3_make(-0.4, 0.99, -0.4);
    l.edge_u = bg_vec3_make(0.8, 0, 0);
    l.edge_v = bg_vec3_make(0, 0, 0.8); /* u x v = -y: it faces down */
    l.intensity = 1.0;
    l.visible = visible;
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    if (light_in_view)
        look(s, bg_vec3_make(0, 0, 0.95), bg_vec3_make(0, 0, -1), 90.0);
    else
        look(s, bg_vec3_make(0, 0.5, 0.95), bg_vec3_make(0, -0.6, -1), 60.0);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

/* A visible light is met both ways, weighted by the power heuristic; an unseen one by its own
 * sampling only: what they light is the same on average. With one bounce (max_depth 1) nothing
 * else differs: a bounce through an unseen light meets the ceiling behind it, which that light,
 * facing down, does not light (deeper, the visible light would hide light the ceiling there
 * passes on, a true difference). Both are rendered at 256 samples, 16 x 16 pixels that see no
 * light; the mean of the pixels' differences must be within 4 standard errors of the differences'
 * own spread (the image's structure cancels in them) plus 0.2 % of the image's level. That margin
 * is there because the two renders share their sample points, so their difference is far less
 * noisy than either: measured, the mean difference is 0.07 % of the level, 5 of those standard
 * errors, a residue this test does not explain (the scramble's jitter takes 4096 values per cell
 * on a fixed pairing of the two coordinates; a bias of the estimator of that size would also
 * pass). Counting the light's hits by the BRDF's rays unweighted moves the mean by 68 %; leaving
 * out the light sampling's weight, which is near 1 here, by 0.15 %. */
static void visible_and_unseen_lights_light_alike(void **state)
{
    (void)state;
    float *px[2];
    for (int v = 0; v < 2; v++) {
        bg_scene *s = box_under_light(v == 1, false);
        bg_render_settings set = path_settings(256, 1);
        px[v] = render(s, &set, 16, 16);
        bg_scene_destroy(s);
    }
    double sum = 0.0, sq = 0.0, level = 0.0;
    for (int i = 0; i < 16 * 16; i++) {
        double d = (double)px[1][4 * i + 1] - px[0][4 * i + 1];
        sum += d;
        sq += d * d;
        level += px[0][4 * i + 1] / 256.0;
    }
    double mean = sum / 256.0, se = sqrt((sq / 256.0 - mean * mean) / 255.0);
    print_message("visible (MIS) against unseen light: mean difference %.5f of %.5f (4 standard errors %.5f)\n",
                  mean, level, 4.0 * se);
    assert_true(fabs(mean) <= 4.0 * se + 0.002 * level);
    free(px[0]);
    free(px[1]);
}

static void box_lit_by_an_emitter_stays_below_it(void **state)
{
    (void)state;
    bg_scene *s = box_under_light(true, true);
    const double le = PI * 1.0 / (0.8 * 0.8); /* 13.1 */
    double means[3];
    const int counts[3] = {16, 64, 256};
    for (int k = 0; k < 3; k++) {
        bg_render_settings set = path_settings(counts[k], 8);
        float *px = render(s, &set, 16, 16);
        double top = 0.0, sum = 0.0;
        int at_light = 0;
        for (int i = 0; i < 16 * 16; i++) {
            for (int c = 0; c < 3; c++)
                top = px[4 * i + c] > top ? px[4 * i + c] : top;
            at_light += fabs(px[4 * i] - le) < 1e-5 * le ? 1 : 0;
            sum += px[4 * i];
        }
        means[k] = sum / (16 * 16);
        print_message("box under an emitter, %3d samples: brightest %.4f (Le %.4f), %d pixels at Le, mean %.5f\n",
                      counts[k], top, le, at_light, means[k]);
        assert_true(top <= le * (1.0 + 1e-6));
        assert_true(at_light > 0);
        free(px);
    }
    double d16 = fabs(means[0] - means[2]) / means[2], d64 = fabs(means[1] - means[2]) / means[2];
    print_message("mean: 16 samples off by %.4f, 64 by %.4f of the 256-sample mean\n", d16, d64);
    assert_true(d16 < 0.05 && d64 < 0.02);
    bg_scene_destroy(s);
}

/* ---- agreement with Whitted ---- */

/* A floor, a box on it, an invisible rectangle light of attenuation (0, 0, 1) and a point light:
 * at max_depth 0 with the ambient term, each camera sample of the path integrator adds exactly
 * Whitted's terms (the rectangle's point comes from the same dimension, and f Le v' / p_l is
 * pi f E_l v' there: 13.1), so the images agree to rounding. */
static void direct_light_is_whitted_s(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t white = lambertian(s, 0.8, NULL), id;
    bg_material glossy = bg_material_init();
    glossy.base.reflectance = (bg_color_param){0.7, 0.3, 0.2, 0};
    glossy.base.roughness.value = 0.6;
    uint32_t red;
    assert_int_equal(bg_scene_add_material(s, &glossy, &red), BG_OK);
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, 0, 0), bg_vec3_make(0, 1, 0), white, &id), BG_OK);
    bg_object_desc box = bg_object_desc_init(BG_SHAPE_BOX, red);
    box.transform = bg_mat4_mul(bg_mat4_translate(0, 0.5, 0), bg_mat4_scale(0.5, 0.5, 0.5));
    assert_int_equal(bg_scene_add_object(s, &box, &id), BG_OK);
    bg_light rect = bg_light_init();
    rect.type = BG_LIGHT_RECTANGLE;
    rect.position = bg_vec3_make(-1, 3, -1);
    rect.edge_u = bg_vec3_make(2, 0, 0);
    rect.edge_v = bg_vec3_make(0, 0, 2);
    rect.attenuation[0] = 0.0;
    rect.attenuation[2] = 1.0;
    rect.intensity = 3.0;
    assert_int_equal(bg_scene_add_light(s, &rect, &id), BG_OK);
    bg_light point = bg_light_init();
    point.position = bg_vec3_make(2, 2, 2);
    point.color[2] = 0.5;
    assert_int_equal(bg_scene_add_light(s, &point, &id), BG_OK);
    look(s, bg_vec3_make(1.5, 2, 3), bg_vec3_make(0, 0.4, 0), 50.0);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    bg_render_settings whitted = bg_render_settings_init();
    whitted.samples = 4;
    whitted.max_depth = 0;
    bg_render_settings path = path_settings(4, 0);
    path.path_ambient = true;
    float *a = render(s, &whitted, 24, 16), *b = render(s, &path, 24, 16);
    double worst = 0.0;
    for (int i = 0; i < 24 * 16 * 4; i++) {
        double e = fabs(a[i] - b[i]) / (fabs(a[i]) > 1e-3 ? fabs(a[i]) : 1e-3);
        worst = e > worst ? e : worst;
    }
    print_message("direct light: path against Whitted, largest relative difference %.3g\n", worst);
    assert_true(worst < 1e-5);
    free(a);
    free(b);
    bg_scene_destroy(s);
}

/* The integrator is a setting like the others: an unknown value is refused by name, and the
 * default is Whitted. */
static void integrator_is_checked(void **state)
{
    (void)state;
    bg_render_settings set = bg_render_settings_init();
    assert_int_equal(set.integrator, BG_INTEGRATOR_WHITTED);
    assert_false(set.path_ambient);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    set.integrator = (bg_integrator)7;
    unsigned char px[4 * 4 * 4];
    memset(px, 0x5a, sizeof px);
    bg_image img = {4, 4, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_render_cpu(s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "settings.integrator"));
    for (size_t i = 0; i < sizeof px; i++)
        assert_int_equal(px[i], 0x5a);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(white_furnace_returns_the_environment),
        cmocka_unit_test(half_furnace_returns_the_albedo),
        cmocka_unit_test(glossy_furnace_returns_the_albedo),
        cmocka_unit_test(glass_furnace_returns_the_environment),
        cmocka_unit_test(emitting_white_box_is_exact),
        cmocka_unit_test(box_lit_by_an_emitter_stays_below_it),
        cmocka_unit_test(visible_and_unseen_lights_light_alike),
        cmocka_unit_test(direct_light_is_whitted_s),
        cmocka_unit_test(integrator_is_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
