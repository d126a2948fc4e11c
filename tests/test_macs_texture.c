/* Textures and depth/stencil objects: exact round trips, strides, precision, clear, limits. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"
#include "util_oom.h"

static void rgba32f_round_trip_is_bit_exact(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 37, H = 23 };
    float *in = calloc(W * H * 4, sizeof *in);
    float *out = calloc(W * H * 4, sizeof *out);
    assert_non_null(in);
    assert_non_null(out);
    util_fill_pattern(in, W * H * 4, 1);
    /* Values float handling likes to disturb: negative zero, the smallest normal, the smallest
     * subnormal's neighbourhood, the largest finite value. */
    in[0] = -0.0f;
    in[1] = FLT_MIN;
    in[2] = -FLT_MIN * 1.5f;
    in[3] = FLT_MAX;
    in[4] = -FLT_MAX;
    in[5] = 1e-37f;
    in[6] = -123456.789f;
    in[7] = 3.0e38f;
    macs_texture_desc d = {W, H, MACS_FORMAT_RGBA32F, 0, 0, in, 0};
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_format(t), MACS_FORMAT_RGBA32F);
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    assert_memory_equal(in, out, W * H * 4 * sizeof(float));
    /* Second upload through the update path. */
    util_fill_pattern(in, W * H * 4, 2);
    assert_int_equal(macs_texture_upload(t, in, 0), MACS_OK);
    memset(out, 0, W * H * 4 * sizeof *out);
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    assert_memory_equal(in, out, W * H * 4 * sizeof(float));
    free(in);
    free(out);
    macs_context_destroy(ctx);
}

static void strides_are_honoured(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 5, H = 4, PAD = 3 };            /* rows of W + PAD texels */
    const size_t stride = (W + PAD) * 16;
    float in[(W + PAD) * H * 4], out[(W + PAD) * H * 4];
    util_fill_pattern(in, sizeof in / sizeof *in, 3);
    macs_texture *t = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    assert_int_equal(macs_texture_upload(t, in, stride), MACS_OK);
    for (size_t i = 0; i < sizeof out / sizeof *out; i++)
        out[i] = 777.0f;
    assert_int_equal(macs_texture_read(t, out, stride), MACS_OK);
    for (int y = 0; y < H; y++) {
        assert_memory_equal(&in[y * (W + PAD) * 4], &out[y * (W + PAD) * 4], W * 16);
        for (int x = W; x < W + PAD; x++) /* padding untouched by the read */
            assert_true(out[(y * (W + PAD) + x) * 4] == 777.0f);
    }
    /* Tight read of a padded upload: rows must have been taken from the stride. */
    float tight[W * H * 4];
    assert_int_equal(macs_texture_read(t, tight, 0), MACS_OK);
    for (int y = 0; y < H; y++)
        assert_memory_equal(&in[y * (W + PAD) * 4], &tight[y * W * 4], W * 16);
    /* Strides that are not whole texels or shorter than a row are refused. */
    assert_int_equal(macs_texture_read(t, out, W * 16 - 16), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_texture_upload(t, in, W * 16 + 4), MACS_ERR_INVALID_ARGUMENT);
    macs_context_destroy(ctx);
}

static float half_round(float v)
{
    /* Relative precision of a half float is 2^-11; values here stay in its normal range. */
    return fabsf(v) * (1.0f / 1024.0f) + 1e-4f;
}

static void rgba16f_round_trip_within_precision(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 16, H = 9 };
    float in[W * H * 4], out[W * H * 4];
    for (int i = 0; i < W * H * 4; i++)
        in[i] = (float)((i * 37) % 2001 - 1000) * 0.37f; /* -370 .. 370 */
    macs_texture_desc d = {W, H, MACS_FORMAT_RGBA16F, 0, 0, in, 0};
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    int inexact = 0;
    for (int i = 0; i < W * H * 4; i++) {
        assert_true(fabsf(out[i] - in[i]) <= half_round(in[i]));
        inexact += out[i] != in[i];
    }
    assert_true(inexact > 0); /* really stored as 16-bit, not silently as 32-bit */
    macs_context_destroy(ctx);
}

static void rgba8_round_trip_is_exact_with_stride(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 7, H = 3, ROW = 9 * 4 };
    uint8_t in[ROW * H], out[ROW * H];
    for (size_t i = 0; i < sizeof in; i++)
        in[i] = (uint8_t)(i * 31 + 7);
    memset(out, 0xAA, sizeof out);
    macs_texture_desc d = {W, H, MACS_FORMAT_RGBA8, MACS_FILTER_LINEAR, MACS_WRAP_REPEAT, in, ROW};
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_read(t, out, ROW), MACS_OK);
    for (int y = 0; y < H; y++) {
        assert_memory_equal(&in[y * ROW], &out[y * ROW], W * 4);
        assert_int_equal(out[y * ROW + W * 4], 0xAA);
    }
    macs_context_destroy(ctx);
}

static void clear_sets_exact_values(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, 6, 5, MACS_FORMAT_RGBA32F);
    const float v[4] = {-2.5f, 1.0e30f, 0.1f, -1.0e-30f};
    assert_int_equal(macs_texture_clear(t, v), MACS_OK);
    float out[6 * 5 * 4];
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    for (int i = 0; i < 6 * 5; i++)
        assert_memory_equal(&out[i * 4], v, sizeof v);
    macs_texture *t8 = util_texture(ctx, 2, 2, MACS_FORMAT_RGBA8);
    const float w[4] = {0.0f, 1.0f, 2.0f, -1.0f}; /* RGBA8 saturates */
    assert_int_equal(macs_texture_clear(t8, w), MACS_OK);
    uint8_t b[16];
    assert_int_equal(macs_texture_read(t8, b, 0), MACS_OK);
    assert_int_equal(b[0], 0);
    assert_int_equal(b[1], 255);
    assert_int_equal(b[2], 255);
    assert_int_equal(b[3], 0);
    assert_int_equal(macs_texture_clear(t, NULL), MACS_ERR_INVALID_ARGUMENT);
    macs_context_destroy(ctx);
}

static void sizes_are_checked(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_limits eff;
    macs_context_get_limits(ctx, NULL, &eff);
    macs_texture *t = NULL;
    macs_texture_desc d = {0};
    d.width = 0;
    d.height = 4;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_ERR_INVALID_ARGUMENT);
    assert_null(t);
    d.width = -3;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_ERR_INVALID_ARGUMENT);
    d.width = eff.max_texture_size + 1;
    macs_context_clear_error(ctx);
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_ERR_LIMIT);
    assert_non_null(strstr(macs_context_error_message(ctx), "maximum"));
    d.width = 1;
    d.height = 1;
    d.format = (macs_format)42;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_ERR_INVALID_ARGUMENT);
    d.format = MACS_FORMAT_DEFAULT;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_format(t), MACS_FORMAT_RGBA32F);
    int w = 0, h = 0;
    macs_texture_size(t, &w, &h);
    assert_int_equal(w, 1);
    assert_int_equal(h, 1);
    /* A capped texture size is enforced too. */
    macs_limits caps = {0};
    caps.max_texture_size = 64;
    macs_context *small = util_context(*state, &caps);
    d.width = 65;
    assert_int_equal(macs_texture_create(small, &d, &t), MACS_ERR_LIMIT);
    d.width = 64;
    assert_int_equal(macs_texture_create(small, &d, &t), MACS_OK);
    macs_context_destroy(small);
    macs_context_destroy(ctx);
}

static void depth_stencil_reports_its_format(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_depth_stencil_desc d = {8, 8, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &d, &ds), MACS_OK);
    assert_int_equal(macs_depth_stencil_format(ds), MACS_DEPTH24_STENCIL8);
    assert_int_equal(macs_depth_stencil_clear(ds, 0.5f, 3, 0x7F), MACS_OK);
    macs_depth_stencil_destroy(ds);
    d.width = 0;
    assert_int_equal(macs_depth_stencil_create(ctx, &d, &ds), MACS_ERR_INVALID_ARGUMENT);
    macs_context_destroy(ctx);

    /* With float depth allowed, the extension decides. */
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(*state);
    cd.get_proc_address_user = macs_headless_proc_user(*state);
    cd.allow_float_depth = true;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    macs_features f;
    macs_context_get_features(ctx, &f);
    d.width = 8;
    assert_int_equal(macs_depth_stencil_create(ctx, &d, &ds), MACS_OK);
    assert_int_equal(macs_depth_stencil_format(ds),
                     f.depth_buffer_float ? MACS_DEPTH32F_STENCIL8 : MACS_DEPTH24_STENCIL8);
    macs_context_destroy(ctx); /* also destroys ds */
}

static void gpu_out_of_memory_is_reported_and_recoverable(void **state)
{
    macs_context *ctx = util_oom_context(*state);
    macs_texture_desc d = {4, 4, 0, 0, 0, NULL, 0};
    macs_texture *t = NULL;
    util_oom_start(1); /* the next allocation fails, like on a full GPU */
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_ERR_GPU_OUT_OF_MEMORY);
    assert_int_equal(util_oom_injected(), 1);
    assert_null(t);
    assert_int_equal(macs_context_error(ctx), MACS_ERR_GPU_OUT_OF_MEMORY);
    /* The message says what was asked, so a caller can tell which allocation the GPU could not hold. */
    assert_non_null(strstr(macs_context_error_message(ctx), "GL_OUT_OF_MEMORY"));
    assert_non_null(strstr(macs_context_error_message(ctx), "4x4 RGBA32F"));
    macs_context_clear_error(ctx);
    /* Still usable afterwards. */
    float in[64], out[64];
    util_fill_pattern(in, 64, 9);
    d.data = in;
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    assert_memory_equal(in, out, sizeof in);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rgba32f_round_trip_is_bit_exact),
        cmocka_unit_test(strides_are_honoured),
        cmocka_unit_test(rgba16f_round_trip_within_precision),
        cmocka_unit_test(rgba8_round_trip_is_exact_with_stride),
        cmocka_unit_test(clear_sets_exact_values),
        cmocka_unit_test(sizes_are_checked),
        cmocka_unit_test(depth_stencil_reports_its_format),
        cmocka_unit_test(gpu_out_of_memory_is_reported_and_recoverable),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
