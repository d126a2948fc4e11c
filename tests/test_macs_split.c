/* Splitting: a pass with more outputs than draw buffers gives the unsplit pass's values (equal bits, or
 * within the rounding of another program: expect_split_matches), with discard, depth testing and the
 * caller's stencil bits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

enum { W = 24, H = 16, NOUT = 13 };

static char value_text[NOUT][160];
static macs_output_desc outputs[NOUT];

static void build_outputs(int count)
{
    for (int i = 0; i < count; i++) {
        snprintf(value_text[i], sizeof value_text[i],
                 "vec4(wave(macs_uv, %d.0) * s, a.x * %d.0 - b.y, a.z + b.w / %d.0, float(%d) + a.w)", i + 1, i + 2,
                 i + 3, i);
        outputs[i].name = "out";
        outputs[i].value = value_text[i];
    }
}

/* Caps of the matrix: {draw buffers, colour attachments}; {0, 0} is uncapped. */
static const int cap_matrix[][2] = {{0, 0}, {1, 1}, {2, 2}, {4, 4}, {8, 8}, {4, 2}, {1, 8}};
#define CAP_COUNT (int)(sizeof cap_matrix / sizeof cap_matrix[0])

/* Under valgrind (MACS_TEST_QUICK) every cap costs seconds of shader compilation: keep the uncapped
 * reference, the deepest split and the mixed caps. */
static bool cap_selected(int c)
{
    return !util_quick() || c == 0 || c == 1 || c == 5;
}

static macs_context *capped_context(void **state, int c)
{
    macs_limits caps = {0};
    caps.max_draw_buffers = cap_matrix[c][0];
    caps.max_color_attachments = cap_matrix[c][1];
    return util_context(*state, &caps);
}

/* The chunks of a split pass are other programs than the unsplit pass: each holds a subset of the
 * outputs, so a compiler may contract or order the shared code's float operations otherwise (GL 2.1
 * appendix A promises equal bits only to the same program). Every value here is a handful of float
 * operations on operands below 16 in magnitude, plus sin and cos of such; contraction or reordering
 * moves each by a few units in the last place, and sin or cos by as much again through their
 * argument. So a value may differ from the unsplit pass's by 2^-16 of max(1, |value|) (about 500
 * ULPs, far above rounding and far below any wrong output, input or texel, all of which move a value
 * by 1e-3 or more). Equal bytes pass at once (Mesa gives them in every case so far). */
static void expect_split_matches(const float *reference, const float *result, size_t n, const char *label, int c)
{
    if (memcmp(reference, result, n * sizeof(float)) == 0)
        return;
    size_t differing = 0;
    for (size_t i = 0; i < n; i++) {
        double a = reference[i], b = result[i];
        if (a == b)
            continue;
        differing++;
        double bound = ldexp(fmax(1.0, fmax(fabs(a), fabs(b))), -16);
        if (!(fabs(a - b) <= bound))
            fail_msg("%s: caps %d/%d: value %zu is %.9g, uncapped %.9g (bound %.3g)", label, cap_matrix[c][0],
                     cap_matrix[c][1], i, b, a, bound);
    }
    print_message("%s: caps %d/%d: %zu values differ from uncapped within rounding\n", label, cap_matrix[c][0],
                  cap_matrix[c][1], differing);
}

static int expected_chunks(macs_context *ctx, int outputs_n)
{
    macs_limits e;
    macs_context_get_limits(ctx, NULL, &e);
    int per = e.max_draw_buffers < e.max_color_attachments ? e.max_draw_buffers : e.max_color_attachments;
    return (outputs_n + per - 1) / per;
}

static void read_all(macs_texture **t, int n, float *dst)
{
    for (int i = 0; i < n; i++)
        assert_int_equal(macs_texture_read(t[i], dst + (size_t)i * W * H * 4, 0), MACS_OK);
}

static void clear_all(macs_texture **t, int n, float v)
{
    const float c[4] = {v, v, v, v};
    for (int i = 0; i < n; i++)
        assert_int_equal(macs_texture_clear(t[i], c), MACS_OK);
}

/* Runs the 13-output pass on one context and returns all outputs. */
static void run_plain(macs_context *ctx, float *result)
{
    float a[W * H * 4], b[7 * 5 * 4];
    util_fill_pattern(a, W * H * 4, 11);
    for (int i = 0; i < 7 * 5 * 4; i++)
        b[i] = (float)i * 0.125f - 3.0f;
    macs_texture_desc da = {W, H, 0, 0, 0, a, 0};
    macs_texture_desc db = {7, 5, 0, MACS_FILTER_LINEAR, MACS_WRAP_REPEAT, b, 0};
    macs_texture *ta, *tb, *out[NOUT];
    assert_int_equal(macs_texture_create(ctx, &da, &ta), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &db, &tb), MACS_OK);
    for (int i = 0; i < NOUT; i++)
        out[i] = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    clear_all(out, NOUT, -7.0f);
    build_outputs(NOUT);
    macs_input_desc in[2] = {{"src_a"}, {"src_b"}};
    macs_texture *in_t[2] = {ta, tb};
    macs_uniform_desc u = {"scale", MACS_UNIFORM_FLOAT, 0};
    macs_pass_desc d = {0};
    d.functions = "float wave(vec2 p, float k)\n{\n    return sin(p.x * k) * cos(p.y * (k + 1.0));\n}\n";
    d.main = "vec4 a = texture2D(src_a, macs_uv);\nvec4 b = texture2D(src_b, macs_uv * 2.0);\nfloat s = scale;\n";
    d.inputs = in;
    d.input_count = 2;
    d.input_textures = in_t;
    d.uniforms = &u;
    d.uniform_count = 1;
    d.outputs = outputs;
    d.output_count = NOUT;
    d.output_textures = out;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(p), expected_chunks(ctx, NOUT));
    const float scale = 1.75f;
    assert_int_equal(macs_pass_set_uniform(p, "scale", &scale), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    read_all(out, NOUT, result);
    /* Sanity against the CPU: the w channel is float(i) + a.w, exact in float. */
    for (int i = 0; i < NOUT; i++)
        for (int px = 0; px < W * H; px++)
            assert_true(result[((size_t)i * W * H + px) * 4 + 3] == (float)i + a[px * 4 + 3]);
}

static void thirteen_outputs_identical_across_caps(void **state)
{
    const size_t n = (size_t)NOUT * W * H * 4;
    float *reference = malloc(n * sizeof(float));
    float *result = malloc(n * sizeof(float));
    assert_non_null(reference);
    assert_non_null(result);
    for (int c = 0; c < CAP_COUNT; c++) {
        if (!cap_selected(c))
            continue;
        macs_context *ctx = capped_context(state, c);
        run_plain(ctx, c == 0 ? reference : result);
        if (c > 0)
            expect_split_matches(reference, result, n, "13 outputs", c);
        macs_context_destroy(ctx);
    }
    free(reference);
    free(result);
}

/* Overlapping "objects": discs with a sloped depth, drawn one run each with the depth test. */
enum { OBJECTS = 5, DOUT = 10 };
static const float objects[OBJECTS][7] = {
    /* cx, cy, r, z0, gx, gy, id */
    {0.40f, 0.50f, 0.35f, 0.50f, 0.60f, 0.10f, 1.0f},
    {0.60f, 0.45f, 0.30f, 0.45f, -0.50f, 0.20f, 2.0f},
    {0.50f, 0.60f, 0.25f, 0.55f, 0.10f, -0.70f, 3.0f},
    {0.30f, 0.30f, 0.20f, 0.30f, 0.90f, 0.90f, 4.0f},
    {0.75f, 0.70f, 0.28f, 0.40f, 0.20f, 0.30f, 5.0f},
};
static char depth_text[DOUT][160];
static macs_output_desc depth_outputs[DOUT];

static void run_depth_scene(macs_context *ctx, float *result, bool caller_stencil_keep)
{
    macs_texture *out[DOUT];
    for (int i = 0; i < DOUT; i++) {
        out[i] = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
        snprintf(depth_text[i], sizeof depth_text[i], "vec4(obj.w * %d.0, depth * %d.0, sin(depth * %d.0) + q.x, q.y)",
                 i + 1, i + 1, i + 7);
        depth_outputs[i].name = "g";
        depth_outputs[i].value = depth_text[i];
    }
    clear_all(out, DOUT, -1.0f);
    macs_depth_stencil_desc dsd = {W, H, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &dsd, &ds), MACS_OK);
    macs_uniform_desc u[2] = {{"obj", MACS_UNIFORM_VEC4, 0}, {"plane", MACS_UNIFORM_VEC3, 0}};
    macs_pass_desc d = {0};
    d.main = "vec2 q = macs_uv - obj.xy;\n"
             "float d2 = dot(q, q);\n"
             "if (d2 > obj.z * obj.z)\n"
             "    discard;\n"
             "float depth = plane.x + plane.y * q.x + plane.z * q.y + 0.2 * d2;\n"
             "gl_FragDepth = depth;\n";
    d.uniforms = u;
    d.uniform_count = 2;
    d.outputs = depth_outputs;
    d.output_count = DOUT;
    d.output_textures = out;
    d.depth_stencil = ds;
    d.depth.test = true;
    d.depth.write = true;
    d.depth.func = MACS_COMPARE_LESS;
    if (caller_stencil_keep) {
        /* A caller stencil test that passes everywhere must not change anything. */
        d.stencil.test = true;
        d.stencil.func = MACS_COMPARE_EQUAL;
        d.stencil.ref = 0;
    }
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(p), expected_chunks(ctx, DOUT));
    for (int o = 0; o < OBJECTS; o++) {
        float obj[4] = {objects[o][0], objects[o][1], objects[o][2], objects[o][6]};
        float plane[3] = {objects[o][3], objects[o][4], objects[o][5]};
        assert_int_equal(macs_pass_set_uniform(p, "obj", obj), MACS_OK);
        assert_int_equal(macs_pass_set_uniform(p, "plane", plane), MACS_OK);
        assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    }
    read_all(out, DOUT, result);
}

static void check_nearest_wins(const float *result)
{
    int checked = 0, covered = 0, depth_decided = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double u = (x + 0.5) / W, v = (y + 0.5) / H;
            double best = 2.0, second = 2.0, best_id = -1.0, last_id = -1.0;
            bool ambiguous = false;
            for (int o = 0; o < OBJECTS; o++) {
                double qx = u - objects[o][0], qy = v - objects[o][1], r = objects[o][2];
                double d2 = qx * qx + qy * qy;
                if (fabs(d2 - r * r) < 1e-5)
                    ambiguous = true; /* on the silhouette: float and double may disagree */
                if (d2 > r * r)
                    continue;
                last_id = objects[o][6];
                double depth = objects[o][3] + objects[o][4] * qx + objects[o][5] * qy + 0.2 * d2;
                if (depth < best) {
                    second = best;
                    best = depth;
                    best_id = objects[o][6];
                } else if (depth < second) {
                    second = depth;
                }
            }
            if (ambiguous || (best_id > 0 && second - best < 1e-4))
                continue;
            checked++;
            covered += best_id > 0;
            depth_decided += best_id != last_id; /* draw order alone would get these wrong */
            assert_true(result[(y * W + x) * 4] == (float)best_id); /* output 0: obj.w * 1 */
        }
    assert_true(checked > W * H * 3 / 4);
    assert_true(covered > W * H / 3);
    assert_true(depth_decided > 10);
}

static void depth_tested_objects_identical_across_caps(void **state)
{
    const size_t n = (size_t)DOUT * W * H * 4;
    float *reference = malloc(n * sizeof(float));
    float *result = malloc(n * sizeof(float));
    assert_non_null(reference);
    assert_non_null(result);
    for (int keep = 0; keep < (util_quick() ? 1 : 2); keep++)
        for (int c = 0; c < CAP_COUNT; c++) {
            if (!cap_selected(c))
                continue;
            macs_context *ctx = capped_context(state, c);
            run_depth_scene(ctx, c == 0 ? reference : result, keep != 0);
            check_nearest_wins(c == 0 ? reference : result);
            if (c > 0)
                expect_split_matches(reference, result, n, "depth scene", c);
            macs_context_destroy(ctx);
        }
    free(reference);
    free(result);
}

/* A split pass with discard leaves no stale mark: a second run elsewhere writes only where it should. */
static void marks_are_cleared_between_runs(void **state)
{
    macs_limits caps = {0};
    caps.max_draw_buffers = 2;
    macs_context *ctx = util_context(*state, &caps);
    macs_texture *out[5];
    char text[5][64];
    macs_output_desc od[5];
    for (int i = 0; i < 5; i++) {
        out[i] = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
        snprintf(text[i], sizeof text[i], "vec4(%d.0, macs_uv, 1.0)", i + 1);
        od[i].name = "o";
        od[i].value = text[i];
    }
    macs_depth_stencil_desc dsd = {W, H, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &dsd, &ds), MACS_OK);
    macs_uniform_desc u = {"disc", MACS_UNIFORM_VEC3, 0};
    macs_pass_desc d = {0};
    d.main = "if (distance(macs_uv, disc.xy) > disc.z) discard;\n";
    d.uniforms = &u;
    d.uniform_count = 1;
    d.outputs = od;
    d.output_count = 5;
    d.output_textures = out;
    for (int with_ds = 0; with_ds < 2; with_ds++) {
        d.depth_stencil = with_ds ? ds : NULL; /* without: MACS's internal stencil */
        macs_pass *p = NULL;
        assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
        assert_int_equal(macs_pass_chunk_count(p), 3);
        const float first[3] = {0.25f, 0.5f, 0.2f}, second[3] = {0.75f, 0.5f, 0.2f};
        assert_int_equal(macs_pass_set_uniform(p, "disc", first), MACS_OK);
        assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
        clear_all(out, 5, 0.0f);
        assert_int_equal(macs_pass_set_uniform(p, "disc", second), MACS_OK);
        assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
        float px[W * H * 4];
        for (int i = 0; i < 5; i++) {
            assert_int_equal(macs_texture_read(out[i], px, 0), MACS_OK);
            int inside = 0;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    double dx = (x + 0.5) / W - 0.75, dy = (y + 0.5) / H - 0.5;
                    double dist = sqrt(dx * dx + dy * dy);
                    if (fabs(dist - 0.2) < 1e-4)
                        continue;
                    float v = px[(y * W + x) * 4];
                    if (dist < 0.2) {
                        assert_true(v == (float)(i + 1));
                        inside++;
                    } else {
                        assert_true(v == 0.0f); /* a stale mark from the first disc would show here */
                    }
                }
            assert_true(inside > 10);
        }
        macs_pass_destroy(p);
    }
    macs_context_destroy(ctx);
}

/* The caller's 7 stencil bits work across a split pass, both as a test and as REPLACE. */
static void caller_stencil_bits_across_split(void **state)
{
    macs_limits caps = {0};
    caps.max_draw_buffers = 4;
    macs_context *ctx = util_context(*state, &caps);
    macs_depth_stencil_desc dsd = {W, H, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &dsd, &ds), MACS_OK);
    assert_int_equal(macs_depth_stencil_clear(ds, 1.0f, 0, 0xFF), MACS_OK);
    macs_texture *out[NOUT];
    for (int i = 0; i < NOUT; i++)
        out[i] = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    macs_uniform_desc u = {"rect", MACS_UNIFORM_VEC4, 0};
    const char *rect_main = "if (any(lessThan(macs_uv, rect.xy)) || any(greaterThan(macs_uv, rect.zw))) discard;\n";

    /* 1: an unsplit pass stamps 5 into a rectangle. */
    macs_output_desc one = {"o", "vec4(1.0)"};
    macs_pass_desc d = {0};
    d.main = rect_main;
    d.uniforms = &u;
    d.uniform_count = 1;
    d.outputs = &one;
    d.output_count = 1;
    d.output_textures = out;
    d.depth_stencil = ds;
    d.stencil.test = true;
    d.stencil.func = MACS_COMPARE_ALWAYS;
    d.stencil.ref = 5;
    d.stencil.pass = MACS_STENCIL_OP_REPLACE;
    macs_pass *stamp = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &stamp), MACS_OK);
    const float r1[4] = {0.25f, 0.25f, 0.5f, 0.75f}; /* x 6..11, y 4..11 */
    assert_int_equal(macs_pass_set_uniform(stamp, "rect", r1), MACS_OK);
    assert_int_equal(macs_pass_run(stamp, NULL), MACS_OK);

    /* 2: a split pass tests EQUAL 5 on the caller's bits: only the rectangle is written. */
    build_outputs(NOUT);
    for (int i = 0; i < NOUT; i++)
        outputs[i].value = "vec4(2.0, macs_uv, 3.0)";
    macs_pass_desc s = {0};
    s.main = rect_main;
    s.uniforms = &u;
    s.uniform_count = 1;
    s.outputs = outputs;
    s.output_count = NOUT;
    s.output_textures = out;
    s.depth_stencil = ds;
    s.stencil.test = true;
    s.stencil.func = MACS_COMPARE_EQUAL;
    s.stencil.ref = 5;
    macs_pass *split = NULL;
    assert_int_equal(macs_pass_create(ctx, &s, &split), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(split), 4);
    const float everywhere[4] = {0.0f, 0.0f, 1.0f, 1.0f};
    assert_int_equal(macs_pass_set_uniform(split, "rect", everywhere), MACS_OK);
    clear_all(out, NOUT, 0.0f);
    macs_run_desc run = {0};
    run.occlusion_query = true;
    assert_int_equal(macs_pass_run(split, &run), MACS_OK);
    uint64_t samples = 0;
    assert_int_equal(macs_pass_occlusion_result(split, &samples), MACS_OK);
    assert_int_equal(samples, 6 * 8);
    float px[W * H * 4];
    for (int i = 0; i < NOUT; i++) {
        assert_int_equal(macs_texture_read(out[i], px, 0), MACS_OK);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                bool in = x >= 6 && x < 12 && y >= 4 && y < 12;
                assert_true(px[(y * W + x) * 4] == (in ? 2.0f : 0.0f));
            }
    }
    /* 3: a split pass REPLACEs 9 into a second rectangle overlapping the first. */
    s.stencil.func = MACS_COMPARE_ALWAYS;
    s.stencil.ref = 9;
    s.stencil.pass = MACS_STENCIL_OP_REPLACE;
    macs_pass *writer = NULL;
    assert_int_equal(macs_pass_create(ctx, &s, &writer), MACS_OK);
    const float r2[4] = {0.375f, 0.0f, 1.0f, 0.5f}; /* x 9..23, y 0..7 */
    assert_int_equal(macs_pass_set_uniform(writer, "rect", r2), MACS_OK);
    assert_int_equal(macs_pass_run(writer, NULL), MACS_OK);
    /* Counting with EQUAL 9 and EQUAL 5 shows what the caller's bits now hold. */
    s.stencil.func = MACS_COMPARE_EQUAL;
    s.stencil.pass = MACS_STENCIL_OP_KEEP;
    macs_pass *probe = NULL;
    assert_int_equal(macs_pass_create(ctx, &s, &probe), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(probe, "rect", everywhere), MACS_OK);
    assert_int_equal(macs_pass_run(probe, &run), MACS_OK);
    assert_int_equal(macs_pass_occlusion_result(probe, &samples), MACS_OK);
    assert_int_equal(samples, 15 * 8);
    assert_int_equal(macs_pass_run(split, &run), MACS_OK); /* EQUAL 5: the first rectangle minus the second */
    assert_int_equal(macs_pass_occlusion_result(split, &samples), MACS_OK);
    assert_int_equal(samples, 6 * 8 - 3 * 4);

    /* Ops that would disturb the reserved bit are refused on a split pass, accepted unsplit. */
    s.stencil.pass = MACS_STENCIL_OP_INCR;
    macs_pass *bad = NULL;
    assert_int_equal(macs_pass_create(ctx, &s, &bad), MACS_ERR_LIMIT);
    assert_null(bad);
    assert_non_null(strstr(macs_context_error_message(ctx), "KEEP"));
    s.stencil.pass = MACS_STENCIL_OP_KEEP;
    s.stencil.fail = MACS_STENCIL_OP_ZERO;
    assert_int_equal(macs_pass_create(ctx, &s, &bad), MACS_ERR_LIMIT);
    s.output_count = 4; /* fits in one chunk */
    assert_int_equal(macs_pass_create(ctx, &s, &bad), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(bad), 1);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thirteen_outputs_identical_across_caps),
        cmocka_unit_test(depth_tested_objects_identical_across_caps),
        cmocka_unit_test(marks_are_cleared_between_runs),
        cmocka_unit_test(caller_stencil_bits_across_split),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
