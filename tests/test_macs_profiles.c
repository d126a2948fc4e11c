/* Limit profiles and the levers they are made of: caps that combine with a profile's, limits claimed
 * above the driver's, extensions treated as absent, a GL version MACS goes by, and the float features
 * GL 2.1 cannot report, which MACS then refuses to depend on. These tests make their own contexts and
 * hold whatever MACS_TEST_PROFILE says. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

/* Creates a context on the headless one with desc's options; message gets the reason on failure. */
static macs_status create(void **state, macs_context_desc *d, macs_context **ctx, char *message, size_t size)
{
    d->get_proc_address = macs_headless_get_proc_address(*state);
    d->get_proc_address_user = macs_headless_proc_user(*state);
    return macs_context_create(d, ctx, message, size);
}

static macs_context *create_ok(void **state, macs_context_desc *d)
{
    macs_context *ctx = NULL;
    char message[1024];
    if (create(state, d, &ctx, message, sizeof message) != MACS_OK)
        fail_msg("macs_context_create: %s", message);
    return ctx;
}

static int smaller(int a, int b)
{
    return a < b ? a : b;
}

/* The limits a profile promises, compared with what the context obeys: never more than the driver. */
static void expect_limits(const macs_context *ctx, int draw, int units, int size, int uniforms, int varyings)
{
    macs_limits real, eff;
    macs_context_get_limits(ctx, &real, &eff);
    assert_int_equal(eff.max_draw_buffers, smaller(real.max_draw_buffers, draw));
    assert_int_equal(eff.max_color_attachments, smaller(real.max_color_attachments, draw));
    assert_int_equal(eff.max_texture_units, smaller(real.max_texture_units, units));
    assert_int_equal(eff.max_texture_size, smaller(real.max_texture_size, size));
    assert_int_equal(eff.max_uniform_components, smaller(real.max_uniform_components, uniforms));
    assert_int_equal(eff.max_varying_components, smaller(real.max_varying_components, varyings));
    assert_int_equal(macs_context_max_uniform_components(ctx), eff.max_uniform_components);
}

static void expect_float_features(const macs_context *ctx, bool f32_filter, bool f16_filter, bool f32_blend,
                                  bool f16_blend)
{
    macs_features f;
    macs_context_get_features(ctx, &f);
    assert_int_equal(f.float32_filter, f32_filter);
    assert_int_equal(f.float16_filter, f16_filter);
    assert_int_equal(f.float32_blend, f32_blend);
    assert_int_equal(f.float16_blend, f16_blend);
    assert_false(f.depth_buffer_float); /* every profile predates ARB_depth_buffer_float */
}

static void each_profile_gives_its_limits_and_features(void **state)
{
    macs_context_desc d = {0};
    d.profile = "geforce7";
    macs_context *ctx = create_ok(state, &d);
    expect_limits(ctx, 4, 16, 4096, 896, 32);
    expect_float_features(ctx, false, true, false, true);
    macs_context_destroy(ctx);

    d.profile = "radeon_x1600";
    ctx = create_ok(state, &d);
    expect_limits(ctx, 4, 16, 4096, 1024, 40);
    expect_float_features(ctx, false, false, false, true);
    macs_features f;
    macs_context_get_features(ctx, &f);
    assert_false(f.arb_framebuffer_object); /* the EXT_framebuffer_object path, as ATI's driver had */
    macs_context_destroy(ctx);

    d.profile = "gma_x3100";
    ctx = create_ok(state, &d);
    expect_limits(ctx, 8, 16, 8192, 1024, 64);
    expect_float_features(ctx, false, true, true, true);
    macs_context_destroy(ctx);

    d.profile = "gl21";
    ctx = create_ok(state, &d);
    expect_limits(ctx, 1, 2, 64, 64, 32);
    expect_float_features(ctx, false, false, false, false);
    macs_context_get_features(ctx, &f);
    assert_false(f.color_buffer_float);
    assert_false(f.half_float_pixel);
    macs_context_destroy(ctx);
}

/* The header's list of names is the one the library knows, name for name. */
static void every_documented_name_is_a_profile(void **state)
{
    char names[] = MACS_PROFILE_NAMES;
    int count = 0;
    for (char *save = NULL, *n = strtok_r(names, ", ", &save); n; n = strtok_r(NULL, ", ", &save)) {
        macs_context_desc d = {0};
        d.profile = n;
        macs_context_destroy(create_ok(state, &d));
        count++;
    }
    assert_int_equal(count, 4);
}

static void unknown_profile_is_refused_with_the_names(void **state)
{
    macs_context_desc d = {0};
    d.profile = "geforce8";
    macs_context *ctx = (macs_context *)&d;
    char message[1024];
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_null(ctx);
    assert_non_null(strstr(message, "desc.profile \"geforce8\""));
    char names[] = MACS_PROFILE_NAMES;
    for (char *save = NULL, *n = strtok_r(names, ", ", &save); n; n = strtok_r(NULL, ", ", &save))
        assert_non_null(strstr(message, n));
}

/* A test's caps and a profile's combine limit by limit, the smaller winning either way. */
static void caps_combine_with_the_profile(void **state)
{
    macs_context_desc d = {0};
    d.profile = "geforce7";
    d.caps.max_texture_size = 32;    /* below the profile's 4096 */
    d.caps.max_draw_buffers = 6;     /* above the profile's 4 */
    d.caps.max_texture_units = 3;
    macs_context *ctx = create_ok(state, &d);
    macs_limits eff;
    macs_context_get_limits(ctx, NULL, &eff);
    assert_int_equal(eff.max_texture_size, 32);
    assert_int_equal(eff.max_texture_units, 3);
    macs_limits real;
    macs_context_get_limits(ctx, &real, NULL);
    assert_int_equal(eff.max_draw_buffers, smaller(real.max_draw_buffers, 4));
    macs_context_destroy(ctx);
}

/* A limit claimed above the driver's is reported and obeyed; what GL then refuses comes back as a
 * MACS error naming the claim, and the context goes on working. */
static void claimed_limits_fail_clearly_in_gl(void **state)
{
    macs_context_desc d = {0};
    macs_context *plain = create_ok(state, &d);
    macs_limits real;
    macs_context_get_limits(plain, &real, NULL);
    macs_context_destroy(plain);

    d.claims.max_texture_size = real.max_texture_size * 2;
    macs_context *ctx = create_ok(state, &d);
    macs_limits r2, eff;
    macs_context_get_limits(ctx, &r2, &eff);
    assert_int_equal(r2.max_texture_size, real.max_texture_size);
    assert_int_equal(eff.max_texture_size, real.max_texture_size * 2);
    /* One row past the driver's limit: tiny, so GL refuses it by size, not by memory. */
    macs_texture_desc td = {0};
    td.width = real.max_texture_size + 1;
    td.height = 1;
    macs_texture *t = (macs_texture *)&td;
    macs_status st = macs_texture_create(ctx, &td, &t);
    assert_true(st == MACS_ERR_LIMIT || st == MACS_ERR_GPU_OUT_OF_MEMORY);
    assert_null(t);
    const char *msg = macs_context_error_message(ctx);
    assert_non_null(strstr(msg, "desc.claims.max_texture_size"));
    char driver[64];
    snprintf(driver, sizeof driver, "max_texture_size %d", real.max_texture_size);
    assert_non_null(strstr(msg, driver));
    macs_context_clear_error(ctx);
    /* A depth/stencil buffer of that size the same way. */
    macs_depth_stencil_desc dd = {real.max_texture_size + 1, 1, MACS_DEPTH24_STENCIL8};
    macs_depth_stencil *ds = (macs_depth_stencil *)&dd;
    assert_int_not_equal(macs_depth_stencil_create(ctx, &dd, &ds), MACS_OK);
    assert_null(ds);
    assert_non_null(strstr(macs_context_error_message(ctx), "desc.claims"));
    macs_context_clear_error(ctx);
    /* The context goes on working. */
    t = util_texture(ctx, 4, 4, MACS_FORMAT_RGBA32F);
    assert_int_equal(macs_texture_clear(t, (const float[4]){1.0f, 2.0f, 3.0f, 4.0f}), MACS_OK);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

static void hidden_extensions_count_as_absent(void **state)
{
    macs_context_desc d = {0};
    d.hidden_extensions = "GL_ARB_color_buffer_float  GL_ARB_half_float_pixel GL_ARB_depth_buffer_float";
    macs_context *ctx = create_ok(state, &d);
    macs_features f;
    macs_context_get_features(ctx, &f);
    assert_false(f.color_buffer_float);
    assert_false(f.half_float_pixel);
    assert_false(f.depth_buffer_float);
    macs_context_destroy(ctx);

    /* A required one: refused exactly as a driver without it is. */
    d.hidden_extensions = "GL_ARB_texture_float";
    char message[1024];
    ctx = (macs_context *)&d;
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_GL_UNSUPPORTED);
    assert_null(ctx);
    assert_non_null(strstr(message, "GL_ARB_texture_float"));

    /* Names that cannot be extensions hide nothing, so they are refused. */
    d.hidden_extensions = "GL_ARB_texture_float,GL_ARB_half_float_pixel";
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc.hidden_extensions"));
    d.hidden_extensions = "ARB_texture_float";
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "\"ARB_texture_float\""));
}

/* Under max_gl_version 21 framebuffer objects are no longer core, so hiding both FBO extensions is
 * refused on any driver, whatever version its default context has. */
static void gl_version_cap_makes_fbo_extensions_count(void **state)
{
    macs_context_desc d = {0};
    d.max_gl_version = 21;
    d.hidden_extensions = "GL_ARB_framebuffer_object GL_EXT_framebuffer_object";
    macs_context *ctx = (macs_context *)&d;
    char message[1024];
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_GL_UNSUPPORTED);
    assert_null(ctx);
    assert_non_null(strstr(message, "GL_ARB_framebuffer_object"));
    assert_null(strstr(message, "GL_ARB_texture_float"));
    d.hidden_extensions = "GL_ARB_framebuffer_object";
    ctx = create_ok(state, &d);
    macs_features f;
    macs_context_get_features(ctx, &f);
    assert_false(f.arb_framebuffer_object);
    macs_context_destroy(ctx);
    d.max_gl_version = 20;
    d.hidden_extensions = NULL;
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc.max_gl_version 20"));
}

static void bad_options_are_named(void **state)
{
    macs_context *ctx = NULL;
    char message[1024];
    macs_context_desc d = {0};
    d.claims.max_draw_buffers = -1;
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc.claims.max_draw_buffers -1"));
    memset(&d, 0, sizeof d);
    d.caps.max_varying_components = -3;
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc.caps.max_varying_components -3"));
    memset(&d, 0, sizeof d);
    d.lacking_float_features = 0x10;
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc.lacking_float_features 0x10"));
    /* MACS's vertex shader needs one 4-float varying slot. */
    memset(&d, 0, sizeof d);
    d.caps.max_varying_components = 2;
    assert_int_equal(create(state, &d, &ctx, message, sizeof message), MACS_ERR_LIMIT);
    assert_non_null(strstr(message, "max_varying_components 2"));
    assert_null(ctx);
}

/* A one-input pass copying its input, texel for texel. */
static macs_status copy_pass(macs_context *ctx, macs_texture *in, macs_texture *out, macs_blend blend,
                             macs_pass **pass)
{
    macs_input_desc i = {"src"};
    macs_output_desc o = {"dst", "texture2D(src, macs_uv)"};
    macs_pass_desc d = {0};
    d.inputs = &i;
    d.input_count = 1;
    d.input_textures = &in;
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &out;
    d.blend = blend;
    return macs_pass_create(ctx, &d, pass);
}

static macs_texture *filtered_texture(macs_context *ctx, macs_format format, macs_filter filter)
{
    macs_texture_desc d = {0};
    d.width = 4;
    d.height = 4;
    d.format = format;
    d.filter = filter;
    macs_texture *t = NULL;
    if (macs_texture_create(ctx, &d, &t) != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
    return t;
}

/* Linear sampling of a float format the context cannot filter is refused, at creation and when bound
 * later, naming the input and the feature; the formats and filters it can do run. */
static void unfilterable_inputs_are_refused(void **state)
{
    macs_context_desc d = {0};
    d.lacking_float_features = MACS_FLOAT32_FILTER;
    macs_context *ctx = create_ok(state, &d);
    macs_texture *out = util_texture(ctx, 4, 4, MACS_FORMAT_RGBA32F);
    macs_texture *lin32 = filtered_texture(ctx, MACS_FORMAT_RGBA32F, MACS_FILTER_LINEAR);
    macs_texture *near32 = filtered_texture(ctx, MACS_FORMAT_RGBA32F, MACS_FILTER_NEAREST);
    macs_texture *lin16 = filtered_texture(ctx, MACS_FORMAT_RGBA16F, MACS_FILTER_LINEAR);
    macs_texture *lin8 = filtered_texture(ctx, MACS_FORMAT_RGBA8, MACS_FILTER_LINEAR);
    macs_pass *p = (macs_pass *)&d;
    assert_int_equal(copy_pass(ctx, lin32, out, MACS_BLEND_NONE, &p), MACS_ERR_LIMIT);
    assert_null(p);
    const char *msg = macs_context_error_message(ctx);
    assert_non_null(strstr(msg, "input 0 \"src\""));
    assert_non_null(strstr(msg, "RGBA32F"));
    assert_non_null(strstr(msg, "float32_filter"));
    macs_context_clear_error(ctx);
    /* RGBA16F filters here, RGBA8 always; and the pass runs. */
    assert_int_equal(copy_pass(ctx, lin16, out, MACS_BLEND_NONE, &p), MACS_OK);
    assert_int_equal(macs_texture_clear(lin16, (const float[4]){0.5f, 1.0f, 2.0f, 4.0f}), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    float px[64];
    assert_int_equal(macs_texture_read(out, px, 0), MACS_OK);
    assert_true(px[0] == 0.5f && px[1] == 1.0f && px[2] == 2.0f && px[3] == 4.0f);
    assert_int_equal(macs_pass_set_input(p, 0, lin8), MACS_OK);
    assert_int_equal(macs_pass_set_input(p, 0, near32), MACS_OK);
    /* Bound later: refused the same way, and the input keeps its texture. */
    assert_int_equal(macs_pass_set_input(p, 0, lin32), MACS_ERR_LIMIT);
    assert_non_null(strstr(macs_context_error_message(ctx), "macs_pass_set_input: input 0 \"src\""));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_texture_clear(near32, (const float[4]){7.0f, 8.0f, 9.0f, 10.0f}), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(out, px, 0), MACS_OK);
    assert_true(px[60] == 7.0f && px[63] == 10.0f);
    macs_context_destroy(ctx);

    /* Without a lack, the same linear RGBA32F input is taken. */
    memset(&d, 0, sizeof d);
    ctx = create_ok(state, &d);
    out = util_texture(ctx, 4, 4, MACS_FORMAT_RGBA32F);
    lin32 = filtered_texture(ctx, MACS_FORMAT_RGBA32F, MACS_FILTER_LINEAR);
    assert_int_equal(copy_pass(ctx, lin32, out, MACS_BLEND_NONE, &p), MACS_OK);
    macs_context_destroy(ctx);
}

/* Blending into a float format the context cannot blend is refused, naming the output; RGBA16F,
 * which it can, blends right. */
static void unblendable_outputs_are_refused(void **state)
{
    macs_context_desc d = {0};
    d.profile = "geforce7"; /* blends RGBA16F only */
    macs_context *ctx = create_ok(state, &d);
    macs_texture *in = util_texture(ctx, 4, 4, MACS_FORMAT_RGBA32F);
    macs_texture *out32 = util_texture(ctx, 4, 4, MACS_FORMAT_RGBA32F);
    macs_texture *out16 = util_texture(ctx, 4, 4, MACS_FORMAT_RGBA16F);
    macs_pass *p = NULL;
    assert_int_equal(copy_pass(ctx, in, out32, MACS_BLEND_ADD, &p), MACS_ERR_LIMIT);
    assert_null(p);
    const char *msg = macs_context_error_message(ctx);
    assert_non_null(strstr(msg, "output 0 \"dst\""));
    assert_non_null(strstr(msg, "float32_blend"));
    assert_non_null(strstr(msg, "RGBA16F")); /* the way out this context offers */
    macs_context_clear_error(ctx);
    /* Replacing (no blend) is always fine. */
    assert_int_equal(copy_pass(ctx, in, out32, MACS_BLEND_NONE, &p), MACS_OK);
    macs_pass_destroy(p);
    assert_int_equal(copy_pass(ctx, in, out16, MACS_BLEND_ADD, &p), MACS_OK);
    assert_int_equal(macs_texture_clear(in, (const float[4]){0.25f, 0.5f, 1.0f, 2.0f}), MACS_OK);
    assert_int_equal(macs_texture_clear(out16, (const float[4]){1.0f, 1.0f, 1.0f, 1.0f}), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    float px[64];
    assert_int_equal(macs_texture_read(out16, px, 0), MACS_OK);
    assert_true(px[0] == 1.25f && px[1] == 1.5f && px[2] == 2.0f && px[3] == 3.0f);
    /* Bound later: refused, naming the output. */
    assert_int_equal(macs_pass_set_output(p, 0, out32), MACS_ERR_LIMIT);
    assert_non_null(strstr(macs_context_error_message(ctx), "macs_pass_set_output: output 0 \"dst\""));
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(each_profile_gives_its_limits_and_features),
        cmocka_unit_test(every_documented_name_is_a_profile),
        cmocka_unit_test(unknown_profile_is_refused_with_the_names),
        cmocka_unit_test(caps_combine_with_the_profile),
        cmocka_unit_test(claimed_limits_fail_clearly_in_gl),
        cmocka_unit_test(hidden_extensions_count_as_absent),
        cmocka_unit_test(gl_version_cap_makes_fbo_extensions_count),
        cmocka_unit_test(bad_options_are_named),
        cmocka_unit_test(unfilterable_inputs_are_refused),
        cmocka_unit_test(unblendable_outputs_are_refused),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
