/* MACS smoke subset, run on every backend and driver: context, exact texture round trip, split pass. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

static void context_reports_limits(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_limits real, eff;
    macs_context_get_limits(ctx, &real, &eff);
    macs_gl_info info;
    macs_context_get_gl_info(ctx, &info);
    print_message("%s / %s: draw buffers %d, colour attachments %d, texture units %d, texture size %d\n",
                  info.renderer ? info.renderer : "?", info.version ? info.version : "?", real.max_draw_buffers,
                  real.max_color_attachments, real.max_texture_units, real.max_texture_size);
    assert_non_null(info.version);
    assert_true(real.max_draw_buffers >= 1);
    assert_true(real.max_texture_units >= 2);
    assert_memory_equal(&real, &eff, sizeof real); /* no caps: effective is real */
    macs_context_destroy(ctx);
    macs_limits caps = {0};
    caps.max_draw_buffers = 1;
    caps.max_texture_units = 1000; /* a cap never raises */
    ctx = util_context(*state, &caps);
    macs_context_get_limits(ctx, &real, &eff);
    assert_int_equal(eff.max_draw_buffers, 1);
    assert_int_equal(eff.max_texture_units, real.max_texture_units);
    macs_context_destroy(ctx);
}

static void texture_round_trip(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    float in[9 * 7 * 4], out[9 * 7 * 4];
    util_fill_pattern(in, sizeof in / sizeof *in, 77);
    macs_texture_desc d = {9, 7, 0, 0, 0, in, 0};
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    assert_memory_equal(in, out, sizeof in);
    macs_context_destroy(ctx);
}

static void run_split(void **state, int cap, float *result)
{
    macs_limits caps = {0};
    caps.max_draw_buffers = cap;
    macs_context *ctx = util_context(*state, &caps);
    float in[16 * 8 * 4];
    util_fill_pattern(in, sizeof in / sizeof *in, 3);
    macs_texture_desc d = {16, 8, 0, 0, 0, in, 0};
    macs_texture *src = NULL, *out[5];
    assert_int_equal(macs_texture_create(ctx, &d, &src), MACS_OK);
    macs_output_desc od[5];
    char text[5][96];
    for (int i = 0; i < 5; i++) {
        out[i] = util_texture(ctx, 16, 8, 0);
        assert_int_equal(macs_texture_clear(out[i], (const float[4]){-1, -1, -1, -1}), MACS_OK);
        snprintf(text[i], sizeof text[i], "vec4(v.x * %d.0, v.y + r, sin(r * %d.0), v.w)", i + 1, i + 2);
        od[i].name = "o";
        od[i].value = text[i];
    }
    macs_input_desc inp = {"src"};
    macs_pass_desc pd = {0};
    pd.main = "vec4 v = texture2D(src, macs_uv);\nfloat r = length(macs_uv - 0.5);\nif (r > 0.4) discard;\n";
    pd.inputs = &inp;
    pd.input_count = 1;
    pd.input_textures = &src;
    pd.outputs = od;
    pd.output_count = 5;
    pd.output_textures = out;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &pd, &p), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    for (int i = 0; i < 5; i++)
        assert_int_equal(macs_texture_read(out[i], result + i * 16 * 8 * 4, 0), MACS_OK);
    macs_context_destroy(ctx);
}

static void split_pass_matches_unsplit(void **state)
{
    static float reference[5 * 16 * 8 * 4], result[5 * 16 * 8 * 4];
    run_split(state, 0, reference);
    int written = 0;
    for (int i = 0; i < 16 * 8; i++)
        written += reference[4 * 16 * 8 * 4 + i * 4 + 3] != -1.0f || reference[4 * 16 * 8 * 4 + i * 4] != -1.0f;
    assert_true(written > 20 && written < 16 * 8); /* the discard really cut some pixels */
    for (int cap = 1; cap <= 4; cap *= 2) {
        run_split(state, cap, result);
        if (memcmp(reference, result, sizeof result) != 0)
            fail_msg("cap %d differs from the unsplit pass", cap);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(context_reports_limits),
        cmocka_unit_test(texture_round_trip),
        cmocka_unit_test(split_pass_matches_unsplit),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
