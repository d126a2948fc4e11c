/* Texture filtering that does not depend on the hardware (docs/shading.md 5.1): GL_LINEAR scene
 * textures are filtered in the shader (glsl110/bg_texture_filter.glsl) from GL_NEAREST fetches with
 * float weights, because texture units keep their weights in fixed point (8 fractional bits on
 * NVIDIA's), and some cannot filter float textures at all.
 *   - every scene texture, the environment's included, is sampled by GL with GL_NEAREST in every
 *     plan, so the texture unit's weights never reach an image;
 *   - the shader filter equals the CPU reference's bilinear (cpu/texture_sample.c) on the same float
 *     coordinates within the bound its float arithmetic allows, on textures of sharp 0/1 texels, and
 *     8-bit weights (the CPU reference's rounded to 1/256) break that bound, so the test tells the two
 *     apart. */
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
#include "betelgeuse/cpu/cpu_internal.h"
#include "betelgeuse/gpu/shared/shared.h"
#include "betelgeuse/scene/scene_internal.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_raw_gl.h"

enum { W = 48, H = 36 };

static util_raw_gl raw;

static int setup(void **state)
{
    util_gpu_group_setup(state);
    util_raw_gl_load(util_fx.headless, &raw);
    return 0;
}

/* ---- GL samples every scene texture with GL_NEAREST ---- */

/* Fails unless GL samples texture t with GL_NEAREST both ways and the wrap its scene texture asks
 * for; the binding of the active unit is put back. */
static void expect_nearest(const macs_texture *t, const bg_texture_data *data, const char *label)
{
    GLint before = 0, min = 0, mag = 0, wrap_s = 0, wrap_t = 0;
    raw.GetIntegerv(GL_TEXTURE_BINDING_2D, &before);
    raw.BindTexture(GL_TEXTURE_2D, macs_texture_gl_name(t));
    raw.GetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, &min);
    raw.GetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, &mag);
    raw.GetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, &wrap_s);
    raw.GetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, &wrap_t);
    raw.BindTexture(GL_TEXTURE_2D, (GLuint)before);
    assert_int_equal(raw.GetError(), GL_NO_ERROR);
    if (min != GL_NEAREST || mag != GL_NEAREST)
        fail_msg("%s: GL filters a scene texture (min 0x%x, mag 0x%x, not GL_NEAREST 0x%x)", label, (unsigned)min,
                 (unsigned)mag, (unsigned)GL_NEAREST);
    GLint want = data->wrap == BG_WRAP_REPEAT ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    if (wrap_s != want || wrap_t != want)
        fail_msg("%s: wrap 0x%x/0x%x, not 0x%x", label, (unsigned)wrap_s, (unsigned)wrap_t, (unsigned)want);
}

/* A texture of the scene from RGBA8 noise (seeded), with its wrap, filter and encoding. */
static uint32_t noise_texture(bg_scene *s, int w, int h, uint32_t seed, bg_texture_wrap wrap, bg_texture_filter filter,
                              bg_texture_encoding encoding)
{
    unsigned char *px = malloc((size_t)w * h * 4);
    assert_non_null(px);
    for (int i = 0; i < w * h * 4; i++) {
        seed = seed * 1664525u + 1013904223u;
        px[i] = (i % 4 == 3) ? 255 : (unsigned char)(seed >> 24);
    }
    bg_image img = {w, h, BG_PIXEL_RGBA8, 0, px};
    bg_texture_desc desc = {wrap, encoding, filter};
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_texture(s, &img, &desc, &id), BG_OK);
    free(px);
    return id;
}

/* A lit sphere and a plane whose materials sample a GL_LINEAR repeating colour texture, a GL_LINEAR
 * clamped roughness texture and a GL_NEAREST one; with env, an environment of a GL_LINEAR float
 * texture that also lights the scene. Committed. */
static bg_scene *textured_scene(bool env)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t color = noise_texture(s, 13, 7, 1u, BG_WRAP_REPEAT, BG_FILTER_LINEAR, BG_TEXTURE_SRGB);
    uint32_t rough = noise_texture(s, 5, 9, 2u, BG_WRAP_CLAMP, BG_FILTER_LINEAR, BG_TEXTURE_LINEAR);
    uint32_t near = noise_texture(s, 6, 6, 3u, BG_WRAP_REPEAT, BG_FILTER_NEAREST, BG_TEXTURE_SRGB);
    bg_material m = bg_material_init();
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 1.0;
    m.base.reflectance.texture = color;
    m.base.roughness.value = 0.8;
    m.base.roughness.texture = rough;
    uint32_t mat = 0, floor_mat = 0, id = 0;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    bg_material f = bg_material_init();
    f.base.reflectance.r = f.base.reflectance.g = f.base.reflectance.b = 0.9;
    f.base.reflectance.texture = near;
    assert_int_equal(bg_scene_add_material(s, &f, &floor_mat), BG_OK);
    bg_object_desc ball = bg_object_desc_init(BG_SHAPE_SPHERE, mat);
    assert_int_equal(bg_scene_add_object(s, &ball, &id), BG_OK);
    bg_object_desc plane = bg_object_desc_init(BG_SHAPE_PLANE, floor_mat);
    plane.transform = bg_mat4_translate(0.0, -1.0, 0.0);
    assert_int_equal(bg_scene_add_object(s, &plane, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(2.0, 4.0, 3.0);
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    if (env) {
        enum { EW = 16, EH = 8 };
        float sky[EW * EH * 4];
        for (int i = 0; i < EW * EH * 4; i++)
            sky[i] = i % 4 == 3 ? 1.0f : (float)((i * 37) % 11) * 0.1f;
        bg_image img = {EW, EH, BG_PIXEL_RGBA32F, 0, sky};
        bg_texture_desc desc = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR, BG_FILTER_LINEAR};
        bg_environment e = bg_environment_init();
        assert_int_equal(bg_scene_add_texture(s, &img, &desc, &e.texture), BG_OK);
        e.lights = true;
        e.intensity = 0.5;
        assert_int_equal(bg_scene_set_environment(s, &e), BG_OK);
    }
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0.4, 1.1, 3.6);
    cam.look_at = bg_vec3_make(0.0, -0.2, 0.0);
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

/* Renders s with plan on a renderer of its own, then checks each of its scene textures. */
static void check_plan(bg_scene *s, bg_gpu_plan plan, const char *label)
{
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = bg_render_settings_init();
    set.gpu_plan = plan;
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    util_render_gpu(r, util_fx.ctx, s, &set, &img, label);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.plan, plan);
    const bg_scene_state *state = bgi_scene_committed(s);
    assert_int_equal(r->scene_textures.count, state->texture_count);
    for (uint32_t i = 0; i < state->texture_count; i++) {
        char what[96];
        snprintf(what, sizeof what, "%s, scene texture %u", label, (unsigned)(i + 1));
        assert_non_null(r->scene_textures.texture[i]);
        expect_nearest(r->scene_textures.texture[i], &state->textures[i], what);
    }
    bg_renderer_destroy(r);
}

static void scene_textures_are_nearest(void **state)
{
    (void)state;
    bg_scene *s = textured_scene(false);
    check_plan(s, BG_PLAN_FUSED, "fused");
    check_plan(s, BG_PLAN_FUSED_TREE, "fused tree");
    check_plan(s, BG_PLAN_MULTIPASS, "multipass");
    bg_scene_destroy(s);
}

static void environment_is_nearest(void **state)
{
    (void)state;
    bg_scene *s = textured_scene(true);
    /* The multipass does not draw environments (bg_scene_set_environment). */
    check_plan(s, BG_PLAN_FUSED, "fused with environment");
    check_plan(s, BG_PLAN_FUSED_TREE, "fused tree with environment");
    bg_scene_destroy(s);
}

/* ---- the shader filter against the CPU reference ---- */

/* The error model of bg_texture_linear against bgi_cpu_texture_sample on the same float (u, v),
 * per channel, with eps = 2^-23 (one float step at 1; twice the unit roundoff, so that a GPU whose
 * float add and multiply round less exactly than IEEE's nearest still fits):
 *   - the coordinate: fract(u) is exact for u >= 0 and one rounding (<= eps) for u < 0; c * size one
 *     rounding (<= eps * size); the -0.5, floor and x - floor(x) are exact. So |dx| <= 2 eps w,
 *     |dy| <= 2 eps h, and since bilinear filtering is continuous and piecewise linear, with slope at
 *     most jx (the largest step between neighbouring texels along x, wrap neighbours included), the
 *     value moves by at most 2 eps (jx w + jy h), whichever texels the floor picks;
 *   - the weights and the blend: 1 - a, two products and the texel product per term, three sums:
 *     at most 16 eps T, T the largest texel magnitude;
 *   - the NEAREST fetches at texel centres return the stored floats exactly.
 * 8-bit weights are off by up to 1/512 of a texel step per axis: 1.95e-3 for a 0/1 step, above
 * the bound of any texture up to 2048 texels a side (2.4e-4 + 4.9e-4 at 2048 x 2048). */
static double filter_bound(int w, int h, double jx, double jy, double t)
{
    const double eps = 0x1p-23;
    return 2.0 * eps * (jx * w + jy * h) + 16.0 * eps * t;
}

/* bgi_cpu_texture_sample's GL_LINEAR with each weight rounded to a multiple of 1/256, as a texture
 * unit with 8 fractional bits of weight filters. */
static void sample_8bit_weights(const bg_texture_data *t, double u, double v, double rgba[4])
{
    bool clamp = t->wrap == BG_WRAP_CLAMP;
    double s[2] = {u, v}, a[2];
    int i0[2], i1[2], size[2] = {t->width, t->height};
    for (int k = 0; k < 2; k++) {
        double c = clamp ? (s[k] < 0.0 ? 0.0 : s[k] > 1.0 ? 1.0 : s[k]) : s[k] - floor(s[k]);
        double x = c * size[k] - 0.5, f = floor(x);
        a[k] = floor((x - f) * 256.0 + 0.5) / 256.0;
        int lo = (int)f, hi = lo + 1;
        if (clamp) {
            lo = lo < 0 ? 0 : lo;
            hi = hi > size[k] - 1 ? size[k] - 1 : hi;
        } else {
            lo = lo < 0 ? lo + size[k] : lo;
            hi = hi >= size[k] ? hi - size[k] : hi;
        }
        i0[k] = lo;
        i1[k] = hi;
    }
    const float *t00 = t->texels + ((size_t)i0[1] * t->width + i0[0]) * 4;
    const float *t10 = t->texels + ((size_t)i0[1] * t->width + i1[0]) * 4;
    const float *t01 = t->texels + ((size_t)i1[1] * t->width + i0[0]) * 4;
    const float *t11 = t->texels + ((size_t)i1[1] * t->width + i1[0]) * 4;
    for (int c = 0; c < 4; c++)
        rgba[c] = (1.0 - a[0]) * (1.0 - a[1]) * t00[c] + a[0] * (1.0 - a[1]) * t10[c] + (1.0 - a[0]) * a[1] * t01[c] +
                  a[0] * a[1] * t11[c];
}

/* The largest step between neighbouring texels of t along x (dx 1) or y, wrap neighbours included
 * for REPEAT, and the largest magnitude. */
static double texel_step(const bg_texture_data *t, int dx, int dy)
{
    double most = 0.0;
    for (int y = 0; y < t->height; y++)
        for (int x = 0; x < t->width; x++) {
            int nx = x + dx, ny = y + dy;
            if (nx >= t->width || ny >= t->height) {
                if (t->wrap == BG_WRAP_CLAMP)
                    continue;
                nx %= t->width;
                ny %= t->height;
            }
            for (int c = 0; c < 4; c++) {
                double d = fabs((double)t->texels[((size_t)y * t->width + x) * 4 + c] -
                                (double)t->texels[((size_t)ny * t->width + nx) * 4 + c]);
                most = d > most ? d : most;
            }
        }
    return most;
}

enum { PW = 64, PH = 64 }; /* sample points: one per output pixel */

/* Samples t (sharp 0/1 texels) at PW x PH float points through bg_texture_linear on the GPU and
 * compares with the CPU reference; returns the largest error, and in *emulated that of 8-bit weights. */
static double shader_against_cpu(const bg_texture_data *t, double *emulated, double *bound)
{
    macs_context *ctx = util_fx.ctx;
    /* The points: corners, edges and wrap seams first, then pseudo-random ones in [-1.25, 2.25) for
     * REPEAT (fract of negative coordinates too), [-0.25, 1.25) for CLAMP. */
    float *uv = malloc(sizeof(float) * 4 * PW * PH), *got = malloc(sizeof(float) * 4 * PW * PH);
    assert_non_null(uv);
    assert_non_null(got);
    static const float special[][2] = {{0.0f, 0.0f},    {1.0f, 1.0f},   {-1e-7f, 0.5f}, {0.5f, -1e-7f},
                                       {0.999999f, 0.25f}, {1.5f, -0.75f}, {-2.0f, 3.0f},  {0.5f, 0.5f}};
    enum { SPECIAL = sizeof special / sizeof special[0] };
    bool repeat = t->wrap == BG_WRAP_REPEAT;
    uint32_t seed = (uint32_t)(t->width * 131 + t->height);
    for (int i = 0; i < PW * PH; i++) {
        for (int k = 0; k < 2; k++) {
            seed = seed * 1664525u + 1013904223u;
            double r = (double)(seed >> 8) / 16777216.0;
            uv[i * 4 + k] = i < SPECIAL ? special[i][k] : (float)(repeat ? -1.25 + 3.5 * r : -0.25 + 1.5 * r);
        }
        uv[i * 4 + 2] = uv[i * 4 + 3] = 0.0f;
    }
    macs_texture_desc cd = {PW, PH, MACS_FORMAT_RGBA32F, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, uv, 0};
    macs_texture_desc id = {t->width, t->height, MACS_FORMAT_RGBA32F, MACS_FILTER_NEAREST,
                            repeat ? MACS_WRAP_REPEAT : MACS_WRAP_CLAMP_TO_EDGE, t->texels, 0};
    util_require_texture_size(ctx, t->width, t->height);
    macs_texture *in[2], *out = util_texture(ctx, PW, PH, MACS_FORMAT_RGBA32F);
    assert_int_equal(macs_texture_create(ctx, &cd, &in[0]), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &id, &in[1]), MACS_OK);

    /* The production text: the library file and the lookup the plans emit. */
    bg_allocator none = {0};
    gpu_text functions;
    bgi_gpu_text_init(&functions, &none);
    const char *seen[4];
    int seen_count = 0;
    assert_true(bgi_gpu_text_snippet(&functions, "bg_texture_filter.glsl", seen, &seen_count, 4));
    assert_false(functions.failed);
    char lookup[192], value[256];
    gpu_texture_mode mode = bgi_gpu_texture_mode(t, true);
    assert_true(mode.linear);
    assert_true(bgi_gpu_texture_lookup(lookup, sizeof lookup, "bg_img", "texture2D(bg_uv, macs_uv).xy", mode));
    snprintf(value, sizeof value, "%s", lookup);

    macs_input_desc inputs[2] = {{"bg_uv"}, {"bg_img"}};
    macs_output_desc output = {"filtered", value};
    macs_pass_desc pd = {0};
    pd.functions = functions.s;
    pd.inputs = inputs;
    pd.input_count = 2;
    pd.input_textures = in;
    pd.outputs = &output;
    pd.output_count = 1;
    pd.output_textures = &out;
    macs_pass *pass = NULL;
    if (macs_pass_create(ctx, &pd, &pass) != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(out, got, 0), MACS_OK);

    double worst = 0.0, worst8 = 0.0;
    int at = 0;
    for (int i = 0; i < PW * PH; i++) {
        double want[4], eight[4];
        bgi_cpu_texture_sample(t, uv[i * 4], uv[i * 4 + 1], want);
        sample_8bit_weights(t, uv[i * 4], uv[i * 4 + 1], eight);
        for (int c = 0; c < 4; c++) {
            double e = fabs((double)got[i * 4 + c] - want[c]), e8 = fabs(eight[c] - want[c]);
            if (e > worst) {
                worst = e;
                at = i;
            }
            worst8 = e8 > worst8 ? e8 : worst8;
        }
    }
    *emulated = worst8;
    *bound = filter_bound(t->width, t->height, texel_step(t, 1, 0), texel_step(t, 0, 1), 1.0);
    printf("%dx%d %s: shader filter max error %.3g at (%.9g, %.9g), bound %.3g; 8-bit weights %.3g\n", t->width,
           t->height, repeat ? "REPEAT" : "CLAMP", worst, (double)uv[at * 4], (double)uv[at * 4 + 1], *bound, worst8);
    macs_pass_destroy(pass);
    bgi_gpu_text_free(&functions);
    macs_texture_destroy(in[0]);
    macs_texture_destroy(in[1]);
    macs_texture_destroy(out);
    free(uv);
    free(got);
    return worst;
}

/* A w x h texture of 0/1 texels (each channel its own noise): every texel edge a step of 1. */
static bg_texture_data sharp_texture(int w, int h, bg_texture_wrap wrap, uint32_t seed)
{
    bg_texture_data t = {w, h, wrap, BG_FILTER_LINEAR, malloc(sizeof(float) * 4 * (size_t)w * h), NULL, false};
    assert_non_null(t.texels);
    for (int i = 0; i < w * h * 4; i++) {
        seed = seed * 1664525u + 1013904223u;
        t.texels[i] = (float)(seed >> 31);
    }
    return t;
}

static void check_sharp(int w, int h, bg_texture_wrap wrap)
{
    bg_texture_data t = sharp_texture(w, h, wrap, (uint32_t)(w * 7 + h));
    double eight = 0.0, bound = 0.0;
    double worst = shader_against_cpu(&t, &eight, &bound);
    if (!(worst <= bound))
        fail_msg("%dx%d: the shader filter is %.3g from the CPU reference, over the bound %.3g", w, h, worst, bound);
    /* Not blind: weights in 1/256 steps, what a texture unit with 8-bit weights computes, break it. */
    if (!(eight > bound))
        fail_msg("%dx%d: 8-bit weights (%.3g off) pass the bound %.3g", w, h, eight, bound);
    free(t.texels);
}

static void shader_filter_matches_cpu_repeat(void **state)
{
    (void)state;
    check_sharp(16, 8, BG_WRAP_REPEAT);
}

static void shader_filter_matches_cpu_clamp(void **state)
{
    (void)state;
    check_sharp(16, 8, BG_WRAP_CLAMP);
}

/* 2048 texels along u: c * size - 0.5 in float keeps 11 bits of texel index and 12 of weight. */
static void shader_filter_matches_cpu_wide(void **state)
{
    (void)state;
    check_sharp(2048, 2, BG_WRAP_REPEAT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(scene_textures_are_nearest),
        cmocka_unit_test(environment_is_nearest),
        cmocka_unit_test(shader_filter_matches_cpu_repeat),
        cmocka_unit_test(shader_filter_matches_cpu_clamp),
        cmocka_unit_test(shader_filter_matches_cpu_wide),
    };
    return cmocka_run_group_tests(tests, setup, util_gpu_group_teardown);
}
