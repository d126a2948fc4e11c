/* GPU timers (macs_timer): a GL_TIME_ELAPSED query around a stretch of commands, from
 * GL_ARB_timer_query or GL_EXT_timer_query. The tests take each extension in turn by hiding the other
 * (desc.hidden_extensions), and a context with neither. A driver without the extension the test needs
 * skips it by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "util_gl.h"

/* Skips the calling test, naming what, unless ctx has timers. */
static void require_timers(macs_context *ctx, const char *what)
{
    macs_features f;
    macs_context_get_features(ctx, &f);
    if (f.timer_query)
        return;
    print_message("[  SKIPPED ] %s: the driver (or MACS_TEST_PROFILE) has no %s\n", what, what);
    macs_context_destroy(ctx);
    skip();
}

static double host_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* A pass that writes a 256x256 texture: GPU work to time. */
static void draw_something(macs_context *ctx, macs_texture **out, macs_pass **pass)
{
    *out = util_texture(ctx, 256, 256, MACS_FORMAT_RGBA32F);
    macs_output_desc o = {"result", "vec4(sin(gl_FragCoord.x) * cos(gl_FragCoord.y))"};
    macs_pass_desc d = {0};
    d.outputs = &o;
    d.output_count = 1;
    d.output_textures = out;
    *pass = NULL;
    if (macs_pass_create(ctx, &d, pass) != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
}

/* Times a pass: the result is the GPU's time, more than nothing, and reading it is one counted sync. */
static void time_a_pass(void **state, const char *hidden, const char *what)
{
    macs_context *ctx = util_context_hiding(*state, hidden);
    require_timers(ctx, what);
    macs_texture *t;
    macs_pass *pass;
    draw_something(ctx, &t, &pass);
    macs_timer *timer = NULL;
    assert_int_equal(macs_timer_create(ctx, &timer), MACS_OK);
    assert_non_null(timer);
    /* llvmpipe reports its absolute clock for a stretch begun before a GL context's first draw
     * (macs_timer_result); a draw first keeps this test to what it is about. */
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    macs_work before, after;
    double host_start = host_ns();
    macs_context_get_work(ctx, &before);
    assert_int_equal(macs_timer_begin(timer), MACS_OK);
    for (int i = 0; i < 4; i++)
        assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_timer_end(timer), MACS_OK);
    macs_context_get_work(ctx, &after);
    macs_work between = macs_work_since(&after, &before);
    /* Begin and end wait for nothing. */
    assert_int_equal(between.syncs, 0);
    uint64_t ns = 0;
    assert_int_equal(macs_timer_result(timer, &ns), MACS_OK);
    double host = host_ns() - host_start;
    print_message("%s: 4 runs of a 256x256 pass took %llu ns of GPU time, %.0f ns of host time\n", what,
                  (unsigned long long)ns, host);
    /* More than nothing, and no more than the host's time from begin to result. */
    assert_true(ns > 0);
    assert_true((double)ns <= host);
    macs_context_get_work(ctx, &before);
    between = macs_work_since(&before, &after);
    assert_int_equal(between.syncs, 1);
    assert_int_equal(between.timer_results, 1);
    /* A timer begins again: the result is then of the new stretch. */
    assert_int_equal(macs_timer_begin(timer), MACS_OK);
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_timer_end(timer), MACS_OK);
    assert_int_equal(macs_timer_result(timer, &ns), MACS_OK);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_timer_destroy(timer);
    macs_pass_destroy(pass);
    macs_texture_destroy(t);
    macs_context_destroy(ctx);
}

static void arb_timer_times_a_pass(void **state)
{
    time_a_pass(state, "GL_EXT_timer_query", "GL_ARB_timer_query");
}

static void ext_timer_times_a_pass(void **state)
{
    time_a_pass(state, "GL_ARB_timer_query", "GL_EXT_timer_query");
}

/* Without either extension no timer is made, and the message names both. */
static void no_extension_no_timer(void **state)
{
    macs_context *ctx = util_context_hiding(*state, "GL_ARB_timer_query GL_EXT_timer_query");
    macs_features f;
    macs_context_get_features(ctx, &f);
    assert_false(f.timer_query);
    macs_timer *timer = (macs_timer *)ctx;
    assert_int_equal(macs_timer_create(ctx, &timer), MACS_ERR_GL_UNSUPPORTED);
    assert_null(timer);
    const char *msg = macs_context_error_message(ctx);
    assert_non_null(strstr(msg, "GL_ARB_timer_query"));
    assert_non_null(strstr(msg, "GL_EXT_timer_query"));
    macs_context_destroy(ctx);
}

/* Misuse is refused, naming the argument or the state, and leaves the timers usable. */
static void misuse_is_named(void **state)
{
    macs_context *ctx = util_context_hiding(*state, NULL);
    require_timers(ctx, "timer query extension");
    assert_int_equal(macs_timer_create(NULL, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_timer_create(ctx, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(macs_context_error_message(ctx), "timer is NULL"));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_begin(NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_timer_end(NULL), MACS_ERR_INVALID_ARGUMENT);
    uint64_t ns = 0;
    assert_int_equal(macs_timer_result(NULL, &ns), MACS_ERR_INVALID_ARGUMENT);
    macs_timer_destroy(NULL);

    macs_timer *a = NULL, *b = NULL;
    assert_int_equal(macs_timer_create(ctx, &a), MACS_OK);
    assert_int_equal(macs_timer_create(ctx, &b), MACS_OK);
    assert_int_equal(macs_timer_result(a, NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(macs_context_error_message(ctx), "nanoseconds is NULL"));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_result(a, &ns), MACS_ERR_NO_RESULT);
    assert_non_null(strstr(macs_context_error_message(ctx), "never ended"));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_end(a), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(macs_context_error_message(ctx), "not running"));
    macs_context_clear_error(ctx);

    assert_int_equal(macs_timer_begin(a), MACS_OK);
    assert_int_equal(macs_timer_begin(a), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(macs_context_error_message(ctx), "this timer"));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_begin(b), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(macs_context_error_message(ctx), "another timer"));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_result(a, &ns), MACS_ERR_NO_RESULT);
    assert_non_null(strstr(macs_context_error_message(ctx), "is running"));
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_end(b), MACS_ERR_INVALID_ARGUMENT);
    macs_context_clear_error(ctx);
    assert_int_equal(macs_timer_end(a), MACS_OK);
    /* Once a has ended, b may run. */
    assert_int_equal(macs_timer_begin(b), MACS_OK);
    assert_int_equal(macs_timer_end(b), MACS_OK);
    assert_int_equal(macs_timer_result(a, &ns), MACS_OK);
    assert_int_equal(macs_timer_result(b, &ns), MACS_OK);
    assert_int_equal(macs_context_error(ctx), MACS_OK);

    /* A running timer destroyed ends first: another may begin after it. */
    assert_int_equal(macs_timer_begin(a), MACS_OK);
    macs_timer_destroy(a);
    assert_int_equal(macs_timer_begin(b), MACS_OK);
    assert_int_equal(macs_timer_end(b), MACS_OK);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    /* b is left for the context to destroy (the sanitizers see a leak otherwise). */
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(arb_timer_times_a_pass),
        cmocka_unit_test(ext_timer_times_a_pass),
        cmocka_unit_test(no_extension_no_timer),
        cmocka_unit_test(misuse_is_named),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
