/* A caller's own GL textures in MACS (macs_texture_wrap, macs_texture_gl_name): the description
 * checked against what GL holds, each refusal naming its field; a wrapped texture as pass input and
 * output, exact; destroying it (or its context) leaves the caller's texture alive with what MACS
 * wrote in it, while MACS's own textures are deleted; region uploads touching only their region. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"
#include "util_raw_gl.h"

static util_raw_gl raw;

static int setup(void **state)
{
    util_group_setup(state);
    util_raw_gl_load(*state, &raw);
    return 0;
}

/* Fails the test unless status is want and the context's message holds every fragment given. */
static void expect_error(macs_context *ctx, macs_status status, macs_status want, const char *a, const char *b)
{
    const char *m = macs_context_error_message(ctx);
    if (status != want || !strstr(m, a) || (b && !strstr(m, b)))
        fail_msg("status %d (want %d), message \"%s\" should name \"%s\"%s%s", (int)status, (int)want, m, a,
                 b ? " and " : "", b ? b : "");
    macs_context_clear_error(ctx);
}

static macs_status wrap(macs_context *ctx, unsigned name, int w, int h, macs_format f, macs_texture **out)
{
    macs_texture_wrap_desc d = {name, w, h, f, MACS_FILTER_DEFAULT, MACS_WRAP_DEFAULT};
    return macs_texture_wrap(ctx, &d, out);
}

static void wrap_takes_what_gl_reports(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    GLuint bytes = util_raw_texture(&raw, 8, 4, GL_RGBA8, GL_UNSIGNED_BYTE, NULL);
    GLuint floats = util_raw_texture(&raw, 3, 5, GL_RGBA32F_ARB, GL_FLOAT, NULL);
    GLuint halves = util_raw_texture(&raw, 2, 2, GL_RGBA16F_ARB, GL_FLOAT, NULL);
    GLuint unsized = util_raw_texture(&raw, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    macs_texture *t = NULL;
    int w = 0, h = 0;

    /* Zero takes GL's size and format; given values must match. */
    assert_int_equal(wrap(ctx, bytes, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_OK);
    macs_texture_size(t, &w, &h);
    assert_int_equal(w, 8);
    assert_int_equal(h, 4);
    assert_int_equal(macs_texture_format(t), MACS_FORMAT_RGBA8);
    assert_int_equal(macs_texture_gl_name(t), bytes);
    assert_ptr_equal(macs_texture_context(t), ctx);
    macs_texture_destroy(t);
    assert_int_equal(wrap(ctx, floats, 3, 5, MACS_FORMAT_RGBA32F, &t), MACS_OK);
    assert_int_equal(macs_texture_format(t), MACS_FORMAT_RGBA32F);
    macs_texture_destroy(t);
    assert_int_equal(wrap(ctx, halves, 2, 2, MACS_FORMAT_DEFAULT, &t), MACS_OK);
    assert_int_equal(macs_texture_format(t), MACS_FORMAT_RGBA16F);
    macs_texture_destroy(t);
    /* Mesa stores an unsized GL_RGBA in 8 bits a channel. */
    assert_int_equal(wrap(ctx, unsized, 0, 0, MACS_FORMAT_RGBA8, &t), MACS_OK);
    macs_texture_destroy(t);

    GLuint all[4] = {bytes, floats, halves, unsized};
    for (int i = 0; i < 4; i++)
        assert_true(raw.IsTexture(all[i]));
    raw.DeleteTextures(4, all);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

static void wrap_refusals_name_the_field(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    GLuint bytes = util_raw_texture(&raw, 8, 4, GL_RGBA8, GL_UNSIGNED_BYTE, NULL);
    macs_texture *t = NULL;
    expect_error(ctx, wrap(ctx, bytes, 9, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.width 9",
                 "width 8");
    assert_null(t);
    expect_error(ctx, wrap(ctx, bytes, 8, 5, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.height 5",
                 "height 4");
    expect_error(ctx, wrap(ctx, bytes, 8, 4, MACS_FORMAT_RGBA32F, &t), MACS_ERR_INVALID_ARGUMENT,
                 "desc.format RGBA32F", "RGBA8");
    expect_error(ctx, wrap(ctx, bytes, -1, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.width -1",
                 NULL);
    expect_error(ctx, wrap(ctx, bytes, 0, 0, (macs_format)9, &t), MACS_ERR_INVALID_ARGUMENT, "desc.format 9", NULL);
    expect_error(ctx, wrap(ctx, 0, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.gl_name is 0",
                 NULL);

    /* Names that are no 2D texture with an image of a format MACS has. */
    GLuint fresh = 0, empty = 0, line = 0;
    raw.GenTextures(1, &fresh); /* generated, never bound: no texture yet */
    expect_error(ctx, wrap(ctx, fresh, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.gl_name",
                 "glIsTexture");
    expect_error(ctx, wrap(ctx, 4242, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "4242",
                 "glIsTexture");
    raw.GenTextures(1, &empty);
    raw.BindTexture(GL_TEXTURE_2D, empty);
    raw.BindTexture(GL_TEXTURE_2D, 0);
    expect_error(ctx, wrap(ctx, empty, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.gl_name",
                 "no level-0 image");
    raw.GenTextures(1, &line);
    raw.BindTexture(GL_TEXTURE_1D, line);
    raw.TexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    raw.BindTexture(GL_TEXTURE_1D, 0);
    expect_error(ctx, wrap(ctx, line, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "desc.gl_name",
                 "GL_TEXTURE_2D");
    GLuint rgb = util_raw_texture(&raw, 4, 4, GL_RGB8, GL_UNSIGNED_BYTE, NULL);
    expect_error(ctx, wrap(ctx, rgb, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_INVALID_ARGUMENT, "internal format",
                 "0x8051");
    assert_null(t);
    /* A refused wrap leaves GL without an error for the caller to find. */
    assert_int_equal(raw.GetError(), GL_NO_ERROR);

    GLuint all[5] = {bytes, fresh, empty, line, rgb};
    raw.DeleteTextures(5, all);
    macs_context_destroy(ctx);

    /* Beyond the effective size limit, as macs_texture_create refuses it. */
    macs_limits caps = {0};
    caps.max_texture_size = 16;
    ctx = util_context(*state, &caps);
    GLuint big = util_raw_texture(&raw, 32, 8, GL_RGBA8, GL_UNSIGNED_BYTE, NULL);
    expect_error(ctx, wrap(ctx, big, 0, 0, MACS_FORMAT_DEFAULT, &t), MACS_ERR_LIMIT, "32x8", "maximum 16");
    raw.DeleteTextures(1, &big);
    macs_context_destroy(ctx);
}

/* The caller's texture keeps GL's default minification filter, which samples mipmaps it does not
 * have: only the wrap's NEAREST makes passes read its texels rather than an incomplete texture. */
static void wrapped_texture_is_pass_input_and_output(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 7, H = 5 };
    float in[W * H * 4], out[W * H * 4], mid[W * H * 4];
    util_fill_pattern(in, W * H * 4, 7);
    GLuint src_name = util_raw_texture(&raw, W, H, GL_RGBA32F_ARB, GL_FLOAT, in);
    GLuint dst_name = util_raw_texture(&raw, W, H, GL_RGBA32F_ARB, GL_FLOAT, NULL);
    macs_texture *src = NULL, *dst = NULL;
    assert_int_equal(wrap(ctx, src_name, W, H, MACS_FORMAT_RGBA32F, &src), MACS_OK);
    assert_int_equal(wrap(ctx, dst_name, W, H, MACS_FORMAT_RGBA32F, &dst), MACS_OK);
    macs_texture *own = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);

    /* wrapped -> own -> wrapped, each a copy: the caller's texture ends up holding its input. */
    macs_input_desc input = {"src"};
    macs_output_desc output = {"copy", "texture2D(src, macs_uv)"};
    macs_pass_desc d = {0};
    d.inputs = &input;
    d.input_count = 1;
    d.outputs = &output;
    d.output_count = 1;
    d.input_textures = &src;
    d.output_textures = &own;
    macs_pass *pass = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &pass), MACS_OK);
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(own, mid, 0), MACS_OK);
    assert_memory_equal(in, mid, sizeof in);
    assert_int_equal(macs_pass_set_output(pass, 0, dst), MACS_OK);
    assert_int_equal(macs_pass_set_input(pass, 0, own), MACS_OK);
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(dst, out, 0), MACS_OK);
    assert_memory_equal(in, out, sizeof in);

    /* Destroying the wrap forgets it: the pass refuses to run without an output, the GL texture is
     * alive and still holds what the pass wrote, read by the caller's own GL. */
    macs_texture_destroy(dst);
    assert_int_equal(macs_pass_run(pass, NULL), MACS_ERR_INVALID_ARGUMENT);
    macs_context_clear_error(ctx);
    assert_true(raw.IsTexture(dst_name));
    memset(out, 0, sizeof out);
    raw.BindTexture(GL_TEXTURE_2D, dst_name);
    raw.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, out);
    raw.BindTexture(GL_TEXTURE_2D, 0);
    assert_memory_equal(in, out, sizeof in);

    /* MACS deletes the textures it made, and the context forgets wraps still alive. */
    GLuint own_name = macs_texture_gl_name(own);
    assert_true(raw.IsTexture(own_name));
    macs_context_destroy(ctx);
    assert_false(raw.IsTexture(own_name));
    assert_true(raw.IsTexture(src_name));
    GLuint all[2] = {src_name, dst_name};
    raw.DeleteTextures(2, all);
    assert_int_equal(raw.GetError(), GL_NO_ERROR);
}

static void upload_region_touches_only_its_region(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    enum { W = 8, H = 6, RW = 3, RH = 2, RX = 2, RY = 3, PAD = 2 };
    macs_texture *t = util_texture(ctx, W, H, MACS_FORMAT_RGBA8);
    const float grey[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    assert_int_equal(macs_texture_clear(t, grey), MACS_OK);
    unsigned char region[(RW + PAD) * RH * 4], out[W * H * 4];
    for (size_t i = 0; i < sizeof region; i++)
        region[i] = (unsigned char)(17 + 5 * i);
    assert_int_equal(macs_texture_upload_region(t, RX, RY, RW, RH, region, (RW + PAD) * 4), MACS_OK);
    assert_int_equal(macs_texture_read(t, out, 0), MACS_OK);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 4; c++) {
                bool inside = x >= RX && x < RX + RW && y >= RY && y < RY + RH;
                int want = inside ? region[((y - RY) * (RW + PAD) + (x - RX)) * 4 + c] : 0;
                if (out[(y * W + x) * 4 + c] != want)
                    fail_msg("texel (%d, %d) channel %d is %d, want %d", x, y, c, out[(y * W + x) * 4 + c], want);
            }

    /* Regions outside the texture or empty, and bad strides, are refused by name. */
    const int bad[][4] = {{-1, 0, 2, 2}, {0, -1, 2, 2}, {7, 0, 2, 1}, {0, 5, 1, 2}, {0, 0, 0, 1}, {0, 0, 1, 0},
                          {1, 1, W, 1}, {0, 0, 0x7fffffff, 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        expect_error(ctx, macs_texture_upload_region(t, bad[i][0], bad[i][1], bad[i][2], bad[i][3], region, 0),
                     MACS_ERR_INVALID_ARGUMENT, "macs_texture_upload_region: region", "8x6 texture");
    expect_error(ctx, macs_texture_upload_region(t, 0, 0, 2, 2, NULL, 0), MACS_ERR_INVALID_ARGUMENT, "data is NULL",
                 NULL);
    expect_error(ctx, macs_texture_upload_region(t, 0, 0, 3, 1, region, 8), MACS_ERR_INVALID_ARGUMENT, "stride 8",
                 "at least 12");
    assert_int_equal(macs_texture_upload_region(NULL, 0, 0, 1, 1, region, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_texture_gl_name(NULL), 0);
    assert_null(macs_texture_context(NULL));
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(wrap_takes_what_gl_reports),
        cmocka_unit_test(wrap_refusals_name_the_field),
        cmocka_unit_test(wrapped_texture_is_pass_input_and_output),
        cmocka_unit_test(upload_region_touches_only_its_region),
    };
    return cmocka_run_group_tests(tests, setup, util_group_teardown);
}
