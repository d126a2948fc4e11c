/* Passes: uniforms of every type, inputs and uniforms swapped between runs, occlusion queries,
 * scissor, blending, colour masks, texture-unit limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_driver.h"
#include "util_gl.h"

/* Runs a one-output pass with no inputs over a 1x1... WxH texture and returns it. */
static macs_pass *simple_pass(macs_context *ctx, macs_texture *out, const char *main_code, const char *value,
                              const macs_uniform_desc *u, int un)
{
    macs_output_desc o = {"o", value};
    macs_pass_desc d = {0};
    d.main = main_code;
    d.uniforms = u;
    d.uniform_count = un;
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &out;
    macs_pass *p = NULL;
    macs_status st = macs_pass_create(ctx, &d, &p);
    if (st != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
    return p;
}

static void every_uniform_type_arrives(void **state)
{
    /* Capped to 4 buffers so the 14 outputs also exercise uniforms across chunks. */
    macs_limits caps = {0};
    caps.max_draw_buffers = 4;
    macs_context *ctx = util_context(*state, &caps);
    macs_uniform_desc u[] = {
        {"uf", MACS_UNIFORM_FLOAT, 0}, {"u2", MACS_UNIFORM_VEC2, 0}, {"u3", MACS_UNIFORM_VEC3, 0},
        {"u4", MACS_UNIFORM_VEC4, 0},  {"ui", MACS_UNIFORM_INT, 0},  {"ub", MACS_UNIFORM_BOOL, 0},
        {"m3", MACS_UNIFORM_MAT3, 0},  {"m4", MACS_UNIFORM_MAT4, 0}, {"arr", MACS_UNIFORM_VEC4, 3},
        {"fa", MACS_UNIFORM_FLOAT, 2},
    };
    static const char *values[] = {
        "vec4(uf, u2, float(ui))",
        "vec4(u3, ub ? 1.0 : -1.0)",
        "u4",
        "vec4(m3[0], m3[1].x)",
        "vec4(m3[1].yz, m3[2].xy)",
        "vec4(m3[2].z, fa[0], fa[1], 0.0)",
        "m4[0]", "m4[1]", "m4[2]", "m4[3]",
        "arr[0]", "arr[1]", "arr[2]",
        "vec4(float(ub), float(-ui), uf * 2.0, 0.5)",
    };
    enum { N = sizeof values / sizeof *values };
    macs_texture *out[N];
    macs_output_desc od[N];
    for (int i = 0; i < N; i++) {
        out[i] = util_texture(ctx, 3, 2, MACS_FORMAT_RGBA32F);
        od[i].name = "o";
        od[i].value = values[i];
    }
    macs_pass_desc d = {0};
    d.uniforms = u;
    d.uniform_count = (int)(sizeof u / sizeof *u);
    d.outputs = od;
    d.output_count = N;
    d.output_textures = out;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(p), 4);
    const float f = -1.5e-3f, v2[2] = {2.5f, -3.25f}, v3[3] = {1e6f, -7.0f, 0.1f}, v4[4] = {9.0f, 8.0f, -7.0f, 6.5f};
    const int i1 = -42, b1 = 1;
    float m3[9], m4[16], arr[12], fa[2] = {0.25f, -0.75f};
    for (int i = 0; i < 9; i++)
        m3[i] = (float)i * 1.5f - 4.0f;
    for (int i = 0; i < 16; i++)
        m4[i] = (float)(i * i) * 0.5f - 20.0f;
    for (int i = 0; i < 12; i++)
        arr[i] = (float)i / 3.0f;
    assert_int_equal(macs_pass_set_uniform(p, "uf", &f), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "u2", v2), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "u3", v3), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "u4", v4), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "ui", &i1), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "ub", &b1), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "m3", m3), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "m4", m4), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "arr", arr), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "fa", fa), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "nope", fa), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    const float expect[N][4] = {
        {f, v2[0], v2[1], (float)i1},
        {v3[0], v3[1], v3[2], 1.0f},
        {v4[0], v4[1], v4[2], v4[3]},
        {m3[0], m3[1], m3[2], m3[3]},
        {m3[4], m3[5], m3[6], m3[7]},
        {m3[8], fa[0], fa[1], 0.0f},
        {m4[0], m4[1], m4[2], m4[3]},
        {m4[4], m4[5], m4[6], m4[7]},
        {m4[8], m4[9], m4[10], m4[11]},
        {m4[12], m4[13], m4[14], m4[15]},
        {arr[0], arr[1], arr[2], arr[3]},
        {arr[4], arr[5], arr[6], arr[7]},
        {arr[8], arr[9], arr[10], arr[11]},
        {1.0f, 42.0f, f * 2.0f, 0.5f},
    };
    float px[3 * 2 * 4];
    for (int i = 0; i < N; i++) {
        assert_int_equal(macs_texture_read(out[i], px, 0), MACS_OK);
        for (int k = 0; k < 6; k++)
            if (memcmp(&px[k * 4], expect[i], sizeof expect[i]) != 0)
                fail_msg("output %d (%s) texel %d: %g %g %g %g", i, values[i], k, px[k * 4], px[k * 4 + 1],
                         px[k * 4 + 2], px[k * 4 + 3]);
    }
    /* bool false arrives as false. */
    const int b0 = 0;
    assert_int_equal(macs_pass_set_uniform(p, "ub", &b0), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(out[1], px, 0), MACS_OK);
    assert_true(px[3] == -1.0f);
    macs_context_destroy(ctx);
}

static void inputs_outputs_and_uniforms_swap_between_runs(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 8, H = 4 };
    float a[W * H * 4], b[W * H * 4], px[W * H * 4];
    util_fill_pattern(a, W * H * 4, 5);
    util_fill_pattern(b, W * H * 4, 6);
    macs_texture_desc da = {W, H, 0, 0, 0, a, 0}, db = {W, H, 0, 0, 0, b, 0};
    macs_texture *ta, *tb;
    assert_int_equal(macs_texture_create(ctx, &da, &ta), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &db, &tb), MACS_OK);
    macs_texture *o1 = util_texture(ctx, W, H, 0), *o2 = util_texture(ctx, W, H, 0);
    macs_input_desc in = {"src"};
    macs_uniform_desc u = {"k", MACS_UNIFORM_FLOAT, 0};
    macs_output_desc o = {"o", "texture2D(src, macs_uv) * k"};
    macs_pass_desc d = {0};
    d.inputs = &in;
    d.input_count = 1;
    d.input_textures = &ta;
    d.uniforms = &u;
    d.uniform_count = 1;
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &o1;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    float k = 2.0f;
    assert_int_equal(macs_pass_set_uniform(p, "k", &k), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(o1, px, 0), MACS_OK);
    for (int i = 0; i < W * H * 4; i++)
        assert_true(px[i] == a[i] * 2.0f);
    k = -0.5f;
    assert_int_equal(macs_pass_set_uniform(p, "k", &k), MACS_OK);
    assert_int_equal(macs_pass_set_input(p, 0, tb), MACS_OK);
    assert_int_equal(macs_pass_set_output(p, 0, o2), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(o2, px, 0), MACS_OK);
    for (int i = 0; i < W * H * 4; i++)
        assert_true(px[i] == b[i] * -0.5f);
    /* o1 kept the first result. */
    assert_int_equal(macs_texture_read(o1, px, 0), MACS_OK);
    assert_true(px[5] == a[5] * 2.0f);
    /* Feeding the output back as input, or an output of another size, is refused. */
    assert_int_equal(macs_pass_set_input(p, 0, o2), MACS_ERR_INVALID_ARGUMENT);
    macs_texture *small = util_texture(ctx, W / 2, H, 0);
    assert_int_equal(macs_pass_set_output(p, 0, small), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_input(p, 1, ta), MACS_ERR_INVALID_ARGUMENT);
    /* A destroyed input leaves the pass refusing to run rather than sampling a dead texture. */
    macs_texture_destroy(tb);
    assert_int_equal(macs_pass_run(p, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_input(p, 0, ta), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    macs_context_destroy(ctx);
}

static int disc_pixels(int w, int h, double cx, double cy, double r, int sx, int sy, int sw, int sh)
{
    int n = 0;
    for (int y = sy; y < sy + sh; y++)
        for (int x = sx; x < sx + sw; x++) {
            double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
            n += dx * dx + dy * dy <= r * r;
        }
    (void)w;
    (void)h;
    return n;
}

static void occlusion_query_counts_samples(void **state)
{
    macs_limits caps = {0};
    caps.max_draw_buffers = 1; /* a split pass: the count is the first chunk's */
    macs_context *ctx = util_context(*state, &caps);
    enum { W = 64, H = 48 };
    macs_texture *out[2] = {util_texture(ctx, W, H, 0), util_texture(ctx, W, H, 0)};
    macs_output_desc od[2] = {{"a", "vec4(1.0)"}, {"b", "vec4(2.0)"}};
    macs_pass_desc d = {0};
    /* Disc of radius 20.3 pixels at (30.2, 21.7), in pixel units so the count is exact. */
    d.main = "vec2 p = gl_FragCoord.xy - vec2(30.2, 21.7);\nif (dot(p, p) > 20.3 * 20.3) discard;\n";
    d.outputs = od;
    d.output_count = 2;
    d.output_textures = out;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(p), 2);
    uint64_t samples = 0;
    assert_int_equal(macs_pass_occlusion_result(p, &samples), MACS_ERR_NO_RESULT);
    macs_context_clear_error(ctx);
    macs_run_desc run = {0};
    run.occlusion_query = true;
    assert_int_equal(macs_pass_run(p, &run), MACS_OK);
    assert_int_equal(macs_pass_occlusion_result(p, &samples), MACS_OK);
    int expect = disc_pixels(W, H, 30.2, 21.7, 20.3, 0, 0, W, H);
    assert_true(expect > 1200);
    assert_int_equal(samples, expect);
    run.scissor = true;
    run.scissor_x = 10;
    run.scissor_y = 5;
    run.scissor_width = 17;
    run.scissor_height = 30;
    assert_int_equal(macs_pass_run(p, &run), MACS_OK);
    assert_int_equal(macs_pass_occlusion_result(p, &samples), MACS_OK);
    assert_int_equal(samples, disc_pixels(W, H, 30.2, 21.7, 20.3, 10, 5, 17, 30));
    /* The scissor also limits what is written. */
    float px[W * H * 4];
    assert_int_equal(macs_texture_clear(out[1], (const float[4]){0, 0, 0, 0}), MACS_OK);
    assert_int_equal(macs_pass_run(p, &run), MACS_OK);
    assert_int_equal(macs_texture_read(out[1], px, 0), MACS_OK);
    int written = 0;
    for (int i = 0; i < W * H; i++)
        written += px[i * 4] == 2.0f;
    assert_int_equal(written, (int)samples);
    run.scissor_width = -1;
    assert_int_equal(macs_pass_run(p, &run), MACS_ERR_INVALID_ARGUMENT);
    macs_context_destroy(ctx);
}

static void blending_and_colour_masks(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, 2, 2, 0);
    float px[16];
    struct {
        macs_blend blend;
        unsigned mask;
        float dst[4], src[4], expect[4];
    } cases[] = {
        {MACS_BLEND_ADD, 0, {1, 2, 3, 4}, {0.5f, 0.25f, -1, 2}, {1.5f, 2.25f, 2, 6}},
        {MACS_BLEND_MULTIPLY, 0, {2, 3, 4, 5}, {0.5f, 2, -1, 0.25f}, {1, 6, -4, 1.25f}},
        {MACS_BLEND_MAX, 0, {2, -3, 4, -1e30f}, {0.5f, 2, -1, 7}, {2, 2, 4, 7}},
        /* after MAX, an ADD pass adds again: the blend equation is set back */
        {MACS_BLEND_ADD, 0, {1, 2, 3, 4}, {1, 1, 1, 1}, {2, 3, 4, 5}},
        {MACS_BLEND_NONE, MACS_COLOR_MASK_R | MACS_COLOR_MASK_B, {1, 2, 3, 4}, {9, 9, 9, 9}, {9, 2, 9, 4}},
        {MACS_BLEND_NONE, MACS_COLOR_MASK_NONE, {1, 2, 3, 4}, {9, 9, 9, 9}, {1, 2, 3, 4}},
        {MACS_BLEND_ADD, MACS_COLOR_MASK_A, {1, 2, 3, 4}, {10, 10, 10, 10}, {1, 2, 3, 14}},
    };
    macs_uniform_desc u = {"v", MACS_UNIFORM_VEC4, 0};
    macs_output_desc o = {"o", "v"};
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        macs_pass_desc d = {0};
        d.uniforms = &u;
        d.uniform_count = 1;
        d.outputs = &o;
        d.output_count = 1;
        d.output_textures = &t;
        d.blend = cases[c].blend;
        d.color_mask = cases[c].mask;
        macs_pass *p = NULL;
        assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
        assert_int_equal(macs_texture_clear(t, cases[c].dst), MACS_OK);
        assert_int_equal(macs_pass_set_uniform(p, "v", cases[c].src), MACS_OK);
        assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
        assert_int_equal(macs_texture_read(t, px, 0), MACS_OK);
        for (int k = 0; k < 4; k++)
            if (memcmp(&px[k * 4], cases[c].expect, sizeof cases[c].expect) != 0)
                fail_msg("case %zu: %g %g %g %g", c, px[k * 4], px[k * 4 + 1], px[k * 4 + 2], px[k * 4 + 3]);
        macs_pass_destroy(p);
    }
    macs_context_destroy(ctx);
}

/* A pass summing n inputs, each a constant texture of value i + 1. */
static macs_status sum_inputs(macs_context *ctx, int n, float *result)
{
    char names[40][16];
    macs_input_desc in[40];
    macs_texture *tex[40];
    char value[2048] = "vec4(0.0)";
    for (int i = 0; i < n; i++) {
        snprintf(names[i], sizeof names[i], "in%d", i);
        in[i].name = names[i];
        tex[i] = util_texture(ctx, 2, 2, 0);
        float v = (float)(i + 1);
        assert_int_equal(macs_texture_clear(tex[i], (const float[4]){v, v, v, v}), MACS_OK);
        size_t used = strlen(value);
        snprintf(value + used, sizeof value - used, " + texture2D(%s, macs_uv)", names[i]);
    }
    macs_texture *out = util_texture(ctx, 2, 2, 0);
    macs_output_desc o = {"o", value};
    macs_pass_desc d = {0};
    d.inputs = in;
    d.input_count = n;
    d.input_textures = tex;
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &out;
    macs_pass *p = NULL;
    macs_status st = macs_pass_create(ctx, &d, &p);
    if (st != MACS_OK)
        return st;
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    float px[16];
    assert_int_equal(macs_texture_read(out, px, 0), MACS_OK);
    *result = px[0];
    return MACS_OK;
}

static void texture_unit_caps(void **state)
{
    const int caps_list[2] = {8, 16};
    for (int c = 0; c < 2; c++) {
        int cap = caps_list[c];
        macs_limits caps = {0}, real, eff;
        caps.max_texture_units = cap;
        macs_context *ctx = util_context(*state, &caps);
        macs_context_get_limits(ctx, &real, &eff);
        assert_int_equal(eff.max_texture_units, real.max_texture_units < cap ? real.max_texture_units : cap);
        float sum = 0.0f;
        assert_int_equal(sum_inputs(ctx, eff.max_texture_units, &sum), MACS_OK);
        assert_true(sum == (float)(eff.max_texture_units * (eff.max_texture_units + 1) / 2));
        assert_int_equal(sum_inputs(ctx, eff.max_texture_units + 1, &sum), MACS_ERR_LIMIT);
        char numbers[64];
        snprintf(numbers, sizeof numbers, "%d inputs but only %d texture units", eff.max_texture_units + 1,
                 eff.max_texture_units);
        assert_non_null(strstr(macs_context_error_message(ctx), numbers));
        macs_context_destroy(ctx);
    }
}

static void programs_are_shared(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *a = util_texture(ctx, 4, 4, 0), *b = util_texture(ctx, 4, 4, 0);
    macs_pass *p1 = simple_pass(ctx, a, "float x = 3.0;", "vec4(x)", NULL, 0);
    macs_pass *p2 = simple_pass(ctx, b, "float x = 3.0;", "vec4(x)", NULL, 0);
    /* Both write their own output even though they share one program. */
    assert_int_equal(macs_pass_run(p1, NULL), MACS_OK);
    assert_int_equal(macs_texture_clear(b, (const float[4]){0, 0, 0, 0}), MACS_OK);
    macs_pass_destroy(p1); /* the shared program must survive for p2 */
    assert_int_equal(macs_pass_run(p2, NULL), MACS_OK);
    float px[64];
    assert_int_equal(macs_texture_read(b, px, 0), MACS_OK);
    assert_true(px[0] == 3.0f && px[63] == 3.0f);
    assert_int_equal(macs_texture_read(a, px, 0), MACS_OK);
    assert_true(px[0] == 3.0f);
    macs_context_destroy(ctx);
}

/* Counts the pixels of a 4x4 pass that pass a stencil EQUAL ref test and a depth LESS test at depth z. */
static uint64_t count_passing(macs_context *ctx, macs_depth_stencil *ds, macs_texture *t, unsigned ref, float z)
{
    macs_uniform_desc u = {"z", MACS_UNIFORM_FLOAT, 0};
    macs_output_desc o = {"o", "vec4(1.0)"};
    macs_pass_desc d = {0};
    d.main = "gl_FragDepth = z;\n";
    d.uniforms = &u;
    d.uniform_count = 1;
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &t;
    d.depth_stencil = ds;
    d.depth.test = true;
    d.stencil.test = true;
    d.stencil.func = MACS_COMPARE_EQUAL;
    d.stencil.ref = ref;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(p, "z", &z), MACS_OK);
    macs_run_desc run = {0};
    run.occlusion_query = true;
    assert_int_equal(macs_pass_run(p, &run), MACS_OK);
    uint64_t n = 0;
    assert_int_equal(macs_pass_occlusion_result(p, &n), MACS_OK);
    macs_pass_destroy(p);
    return n;
}

static void depth_stencil_clear_honours_values_and_mask(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, 4, 4, 0);
    macs_depth_stencil_desc dd = {4, 4, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &dd, &ds), MACS_OK);
    assert_int_equal(macs_depth_stencil_clear(ds, 0.5f, 0x0F, 0xFF), MACS_OK);
    assert_int_equal(count_passing(ctx, ds, t, 0x0F, 0.25f), 16);
    assert_int_equal(count_passing(ctx, ds, t, 0x0F, 0.75f), 0);  /* behind the cleared depth */
    assert_int_equal(count_passing(ctx, ds, t, 0x0E, 0.25f), 0);
    /* Only bits 0x30 change: 0x0F becomes 0x3F; the reserved bit stays 0 whatever is asked. */
    util_skip_masked_stencil_clear_on_zink(ctx);
    assert_int_equal(macs_depth_stencil_clear(ds, 0.5f, 0xF0, 0x30), MACS_OK);
    assert_int_equal(count_passing(ctx, ds, t, 0x3F, 0.25f), 16);
    assert_int_equal(macs_depth_stencil_clear(ds, 1.0f, 0xFF, 0xFF), MACS_OK);
    assert_int_equal(count_passing(ctx, ds, t, 0x7F, 0.75f), 16);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_uniform_type_arrives),
        cmocka_unit_test(inputs_outputs_and_uniforms_swap_between_runs),
        cmocka_unit_test(occlusion_query_counts_samples),
        cmocka_unit_test(blending_and_colour_masks),
        cmocka_unit_test(texture_unit_caps),
        cmocka_unit_test(programs_are_shared),
        cmocka_unit_test(depth_stencil_clear_honours_values_and_mask),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
