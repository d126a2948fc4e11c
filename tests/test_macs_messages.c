/* Messages of refused arguments: each names the argument (desc.backend, out, desc.format, uniform 0
 * "macs_mine", ...), its bad value where it has one, and the rule it breaks, and says nothing of the
 * arguments that were fine, so that a caller can fix the call from the message alone. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

/* Fails with the whole message when a wanted phrase is missing from it. */
static void assert_says(const char *message, const char *phrase)
{
    if (!strstr(message, phrase))
        fail_msg("message \"%s\" does not say \"%s\"", message, phrase);
}

static void assert_does_not_say(const char *message, const char *phrase)
{
    if (strstr(message, phrase))
        fail_msg("message \"%s\" should not mention \"%s\"", message, phrase);
}

static void *only_alloc(size_t size, void *user)
{
    (void)user;
    return malloc(size);
}

static void headless_create_names_the_bad_argument(void **state)
{
    (void)state;
    char message[512];
    macs_headless *h = NULL;
    macs_headless_desc d = {0};
    d.backend = (macs_headless_backend)7;
    assert_int_equal(macs_headless_create(&d, &h, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "desc.backend 7");
    assert_does_not_say(message, "allocator");
    assert_does_not_say(message, "out ");

    d.backend = MACS_HEADLESS_DEFAULT;
    assert_int_equal(macs_headless_create(&d, NULL, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "out is NULL");
    assert_does_not_say(message, "backend");
    assert_does_not_say(message, "allocator");

    d.allocator.alloc = only_alloc;
    assert_int_equal(macs_headless_create(&d, &h, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "desc.allocator");
    assert_says(message, "together");
    assert_does_not_say(message, "backend");
    assert_null(h);
}

static void context_create_names_the_bad_argument(void **state)
{
    char message[512];
    macs_context *ctx = NULL;
    macs_context_desc d = {0};
    assert_int_equal(macs_context_create(NULL, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "desc is NULL");
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "desc.get_proc_address is NULL");
    assert_does_not_say(message, "out");

    d.get_proc_address = macs_headless_get_proc_address(*state);
    d.get_proc_address_user = macs_headless_proc_user(*state);
    assert_int_equal(macs_context_create(&d, NULL, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "out is NULL");
    assert_does_not_say(message, "get_proc_address");

    d.allocator.alloc = only_alloc;
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "desc.allocator");
    d.allocator.alloc = NULL;

    d.caps.max_texture_units = -3;
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_says(message, "desc.caps.max_texture_units -3");
    assert_null(ctx);
}

/* Creates a 4x4 texture with one field of its descriptor set to a bad value and returns the message. */
static const char *texture_message(macs_context *ctx, macs_texture_desc d)
{
    macs_texture *t = NULL;
    macs_context_clear_error(ctx);
    assert_int_equal(macs_texture_create(ctx, &d, &t), MACS_ERR_INVALID_ARGUMENT);
    assert_null(t);
    return macs_context_error_message(ctx);
}

static void texture_create_names_format_filter_and_wrap(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture_desc d = {4, 4, 0, 0, 0, NULL, 0};
    d.format = (macs_format)7;
    const char *m = texture_message(ctx, d);
    assert_says(m, "desc.format 7");
    assert_does_not_say(m, "filter");
    assert_does_not_say(m, "wrap");
    d.format = MACS_FORMAT_DEFAULT;
    d.filter = (macs_filter)5;
    m = texture_message(ctx, d);
    assert_says(m, "desc.filter 5");
    assert_does_not_say(m, "format");
    d.filter = MACS_FILTER_DEFAULT;
    d.wrap = (macs_wrap)9;
    m = texture_message(ctx, d);
    assert_says(m, "desc.wrap 9");
    assert_does_not_say(m, "filter");
    macs_context_destroy(ctx);
}

/* A pass over one 4x4 output "o" with one input "src" and one float uniform "k" that a test breaks. */
typedef struct pass_fixture {
    macs_context *ctx;
    macs_texture *out;
    macs_input_desc input;
    macs_uniform_desc uniform;
    macs_output_desc output;
    macs_pass_desc desc;
} pass_fixture;

static void pass_fixture_init(pass_fixture *f, macs_headless *headless)
{
    memset(f, 0, sizeof *f);
    f->ctx = util_context(headless, NULL);
    f->out = util_texture(f->ctx, 4, 4, 0);
    f->input.name = "src";
    f->uniform.name = "k";
    f->uniform.type = MACS_UNIFORM_FLOAT;
    f->output.name = "o";
    f->output.value = "texture2D(src, macs_uv) * k";
    f->desc.inputs = &f->input;
    f->desc.input_count = 1;
    f->desc.uniforms = &f->uniform;
    f->desc.uniform_count = 1;
    f->desc.outputs = &f->output;
    f->desc.output_count = 1;
    f->desc.output_textures = &f->out;
}

/* Creates the fixture's pass, expects a refusal and returns its message. */
static const char *pass_message(pass_fixture *f)
{
    macs_pass *p = NULL;
    macs_context_clear_error(f->ctx);
    assert_int_equal(macs_pass_create(f->ctx, &f->desc, &p), MACS_ERR_INVALID_ARGUMENT);
    assert_null(p);
    return macs_context_error_message(f->ctx);
}

static void pass_names_the_bad_name_and_its_rule(void **state)
{
    pass_fixture f;
    pass_fixture_init(&f, *state);
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(f.ctx, &f.desc, &p), MACS_OK); /* the fixture itself is valid */
    macs_pass_destroy(p);

    f.uniform.name = "macs_mine";
    const char *m = pass_message(&f);
    assert_says(m, "uniform 0 \"macs_mine\"");
    assert_says(m, "reserved prefix \"macs_\"");
    f.uniform.name = "k";

    f.input.name = "gl_tex";
    m = pass_message(&f);
    assert_says(m, "input 0 \"gl_tex\"");
    assert_says(m, "reserved prefix \"gl_\"");
    f.input.name = "src";

    f.output.name = "o__x";
    m = pass_message(&f);
    assert_says(m, "output 0 \"o__x\"");
    assert_says(m, "\"__\"");
    assert_does_not_say(m, "value");
    f.output.name = "o";

    f.input.name = "two words";
    m = pass_message(&f);
    assert_says(m, "input 0 \"two words\"");
    assert_says(m, "letter, digit or underscore");
    f.input.name = NULL;
    m = pass_message(&f);
    assert_says(m, "input 0 name is NULL");
    f.input.name = "src";

    f.uniform.name = "src";
    m = pass_message(&f);
    assert_says(m, "uniform 0 \"src\"");
    assert_says(m, "input 0");
    f.uniform.name = "k";

    f.output.value = NULL;
    m = pass_message(&f);
    assert_says(m, "output 0 \"o\"");
    assert_says(m, "value is NULL");
    macs_context_destroy(f.ctx);
}

static void pass_names_the_bad_field_and_value(void **state)
{
    pass_fixture f;
    pass_fixture_init(&f, *state);
    f.uniform.type = (macs_uniform_type)99;
    const char *m = pass_message(&f);
    assert_says(m, "uniform 0 \"k\"");
    assert_says(m, "type 99");
    assert_does_not_say(m, "count");
    f.uniform.type = MACS_UNIFORM_FLOAT;
    f.uniform.count = -1;
    m = pass_message(&f);
    assert_says(m, "count -1");
    assert_does_not_say(m, "type");
    f.uniform.count = 0;

    f.desc.blend = (macs_blend)7;
    m = pass_message(&f);
    assert_says(m, "desc.blend 7");
    assert_does_not_say(m, "stencil");
    f.desc.blend = MACS_BLEND_NONE;
    f.desc.depth.func = (macs_compare)42;
    m = pass_message(&f);
    assert_says(m, "desc.depth.func 42");
    f.desc.depth.func = MACS_COMPARE_DEFAULT;
    f.desc.stencil.depth_fail = (macs_stencil_op)13;
    m = pass_message(&f);
    assert_says(m, "desc.stencil.depth_fail 13");
    f.desc.stencil.depth_fail = MACS_STENCIL_OP_DEFAULT;
    f.desc.color_mask = 64;
    m = pass_message(&f);
    assert_says(m, "desc.color_mask 64");
    f.desc.color_mask = 0;

    f.desc.input_count = 2;
    f.desc.inputs = NULL;
    m = pass_message(&f);
    assert_says(m, "desc.input_count 2");
    assert_says(m, "desc.inputs is NULL");
    macs_context_destroy(f.ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(headless_create_names_the_bad_argument),
        cmocka_unit_test(context_create_names_the_bad_argument),
        cmocka_unit_test(texture_create_names_format_filter_and_wrap),
        cmocka_unit_test(pass_names_the_bad_name_and_its_rule),
        cmocka_unit_test(pass_names_the_bad_field_and_value),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
