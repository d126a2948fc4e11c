/* Errors: compile and link failures with their info logs, bad arguments, sticky first error,
 * nothing half-applied, the logger. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

typedef struct log_record {
    int count;
    int last_level;
    char last[4096];
} log_record;

static void record_log(macs_log_level level, const char *message, void *user)
{
    log_record *r = user;
    r->count++;
    r->last_level = level;
    snprintf(r->last, sizeof r->last, "%s", message);
}

static macs_context *logged_context(void **state, log_record *rec)
{
    macs_context_desc d = {0};
    d.get_proc_address = macs_headless_get_proc_address(*state);
    d.get_proc_address_user = macs_headless_proc_user(*state);
    d.logger.func = record_log;
    d.logger.user = rec;
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&d, &ctx, NULL, 0), MACS_OK);
    return ctx;
}

/* Whether an info log names line `line` as compilers do: "string:line(" (Mesa: "0:2(12): error"),
 * "string(line)" (NVIDIA: "0(2) : error C1008") or "string:line:" (AMD and glslang: "ERROR: 0:2:").
 * Each form puts the number between ':' or '(' and ':', '(' or ')'; the assertion holds on any of them
 * and fails on a log that names another line. */
static bool names_line(const char *log, int line)
{
    char number[16];
    snprintf(number, sizeof number, "%d", line);
    size_t n = strlen(number);
    for (const char *p = strstr(log, number); p; p = strstr(p + 1, number)) {
        bool before = p > log && (p[-1] == ':' || p[-1] == '(');
        bool after = p[n] == ':' || p[n] == '(' || p[n] == ')';
        if (before && after)
            return true;
    }
    return false;
}

static void compile_error_keeps_info_log(void **state)
{
    log_record rec = {0};
    macs_context *ctx = logged_context(state, &rec);
    macs_texture *t = util_texture(ctx, 4, 4, 0);
    macs_output_desc o = {"o", "vec4(1.0)"};
    macs_pass_desc d = {0};
    d.functions = "float f(float x)\n{\n    return x * 2.0;\n}\n";
    d.main = "float a = f(1.0);\nfloat b = no_such_variable;\n";
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &t;
    macs_pass *p = (macs_pass *)&d; /* must be reset to NULL on failure */
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_SHADER_COMPILE);
    assert_null(p);
    assert_int_equal(macs_context_error(ctx), MACS_ERR_SHADER_COMPILE);
    const char *msg = macs_context_error_message(ctx);
    assert_non_null(strstr(msg, "no_such_variable"));
    /* The line is the caller's: line 2 of main, in whichever form the compiler writes it. */
    assert_true(names_line(msg, 2));
    assert_true(rec.count > 0);
    assert_int_equal(rec.last_level, MACS_LOG_ERROR);
    assert_non_null(strstr(rec.last, "no_such_variable"));
    /* A float where a vec4 is expected is a type error, not a silent splat. */
    macs_context_clear_error(ctx);
    macs_output_desc wrong = {"o", "1.0"};
    d.main = NULL;
    d.outputs = &wrong;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_SHADER_COMPILE);
    /* GLSL beyond 1.10 is refused (a 1.20 array constructor). */
    macs_context_clear_error(ctx);
    macs_output_desc modern = {"o", "vec4(float[2](1.0, 2.0)[0])"};
    d.outputs = &modern;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_SHADER_COMPILE);
    macs_context_destroy(ctx);
}

static void link_error_keeps_info_log(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, 4, 4, 0);
    macs_output_desc o = {"o", "vec4(declared_only(1.0))"};
    macs_pass_desc d = {0};
    d.functions = "float declared_only(float x);\n"; /* prototype without a body: a link error */
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = &t;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_SHADER_LINK);
    assert_null(p);
    assert_non_null(strstr(macs_context_error_message(ctx), "declared_only"));
    macs_context_destroy(ctx);
}

static void bad_arguments_are_refused(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, 4, 4, 0), *t2 = util_texture(ctx, 5, 4, 0);
    macs_texture *in_t = util_texture(ctx, 4, 4, 0);
    macs_pass *p = NULL;
    /* NULLs */
    assert_int_equal(macs_pass_create(NULL, NULL, &p), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_create(ctx, NULL, &p), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_texture_create(NULL, NULL, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_texture_upload(NULL, NULL, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_texture_upload(t, NULL, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_texture_read(t, NULL, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_run(NULL, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_uniform(NULL, "x", &p), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_occlusion_result(NULL, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_depth_stencil_clear(NULL, 1.0f, 0, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_context_create(NULL, NULL, NULL, 0), MACS_ERR_INVALID_ARGUMENT);
    macs_texture_destroy(NULL);
    macs_pass_destroy(NULL);
    macs_depth_stencil_destroy(NULL);
    macs_context_destroy(NULL);
    macs_headless_destroy(NULL);
    assert_string_equal(macs_status_string(MACS_OK), "ok");
    assert_string_equal(macs_status_string((macs_status)999), "unknown status");
    assert_non_null(strstr(macs_status_string(MACS_ERR_LIMIT), "limit"));

    macs_output_desc o[2] = {{"a", "vec4(1.0)"}, {"b", "vec4(2.0)"}};
    macs_texture *outs[2] = {t, t2};
    macs_input_desc in[2] = {{"src"}, {"src"}};
    macs_uniform_desc u = {"k", MACS_UNIFORM_FLOAT, 0};
    macs_pass_desc d = {0};
    d.outputs = o;
    d.output_count = 2;
    d.output_textures = outs;
    macs_context_clear_error(ctx);
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT); /* sizes differ */
    assert_non_null(strstr(macs_context_error_message(ctx), "5x4"));
    macs_context_clear_error(ctx);
    d.output_count = 0;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    d.output_count = 1;
    d.inputs = in;
    d.input_count = 2; /* duplicate names */
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    d.input_count = 1;
    in[0].name = "gl_bad";
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    in[0].name = "macs_uv";
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    in[0].name = "two words";
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    in[0].name = "src";
    d.input_textures = outs; /* input 0 would be output 0 */
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    d.input_textures = NULL;
    d.uniforms = &u;
    d.uniform_count = 1;
    u.type = (macs_uniform_type)99;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    u.type = MACS_UNIFORM_FLOAT;
    u.count = -1;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    u.count = 0;
    d.depth.test = true; /* without a depth/stencil object */
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    d.depth.test = false;
    d.blend = (macs_blend)7;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    d.blend = MACS_BLEND_NONE;
    macs_depth_stencil_desc dsd = {8, 8, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &dsd, &ds), MACS_OK);
    d.depth_stencil = ds; /* wrong size */
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_ERR_INVALID_ARGUMENT);
    d.depth_stencil = NULL;
    assert_null(p);

    /* A valid pass; out-of-range setters change nothing. */
    d.input_textures = &in_t;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_set_input(p, 1, in_t), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_input(p, -1, in_t), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_output(p, 1, t), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_output(p, 0, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_output(p, 0, t2), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_depth_stencil(p, ds), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_uniform(p, NULL, &u), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_uniform(p, "k", NULL), MACS_ERR_INVALID_ARGUMENT);
    const float k = 4.0f;
    assert_int_equal(macs_pass_set_uniform(p, "k", &k), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    float px[64];
    assert_int_equal(macs_texture_read(t, px, 0), MACS_OK);
    assert_true(px[0] == 1.0f); /* still writing to t: the refused set_output was not applied */

    /* Objects of another context are refused. */
    macs_context *other = util_context(*state, NULL);
    macs_texture *foreign = util_texture(other, 4, 4, 0);
    assert_int_equal(macs_pass_set_input(p, 0, foreign), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_pass_set_output(p, 0, foreign), MACS_ERR_INVALID_ARGUMENT);
    macs_context_destroy(other);
    macs_context_destroy(ctx);
}

static void first_error_is_sticky(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    assert_string_equal(macs_context_error_message(ctx), "");
    macs_texture *t = NULL;
    macs_texture_desc bad = {0};
    assert_int_equal(macs_texture_create(ctx, &bad, &t), MACS_ERR_INVALID_ARGUMENT);
    char first[256];
    snprintf(first, sizeof first, "%s", macs_context_error_message(ctx));
    assert_non_null(strstr(first, "0x0"));
    bad.width = bad.height = 1 << 30;
    assert_int_equal(macs_texture_create(ctx, &bad, &t), MACS_ERR_LIMIT);
    assert_int_equal(macs_context_error(ctx), MACS_ERR_INVALID_ARGUMENT); /* still the first */
    assert_string_equal(macs_context_error_message(ctx), first);
    macs_context_clear_error(ctx);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &bad, &t), MACS_ERR_LIMIT);
    assert_int_equal(macs_context_error(ctx), MACS_ERR_LIMIT);
    macs_context_destroy(ctx);
}

static void *only_alloc(size_t size, void *user)
{
    (void)user;
    return malloc(size);
}

static void creation_failure_fills_message(void **state)
{
    (void)state;
    macs_context_desc d = {0};
    char message[256] = "unchanged";
    macs_context *ctx = (macs_context *)message;
    log_record rec = {0};
    d.logger.func = record_log;
    d.logger.user = &rec;
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_null(ctx);
    assert_non_null(strstr(message, "get_proc_address"));
    assert_int_equal(rec.count, 1);
    d.get_proc_address = macs_headless_get_proc_address(*state);
    d.get_proc_address_user = macs_headless_proc_user(*state);
    d.caps.max_draw_buffers = -1;
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "caps"));
    d.caps.max_draw_buffers = 0;
    d.allocator.alloc = only_alloc; /* alloc without free */
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    /* A tiny buffer is truncated, never overrun. */
    char tiny[4] = {'x', 'x', 'x', 'x'};
    assert_int_equal(macs_context_create(&d, &ctx, tiny, 3), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(tiny[2], '\0');
    assert_int_equal(tiny[3], 'x');
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(compile_error_keeps_info_log),
        cmocka_unit_test(link_error_keeps_info_log),
        cmocka_unit_test(bad_arguments_are_refused),
        cmocka_unit_test(first_error_is_sticky),
        cmocka_unit_test(creation_failure_fills_message),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
