/* Phase timing (settings.gpu_timing, bg_render_stats.timing): GPU timer queries where GL has them,
 * which add no wait inside the call (their results are read after its last command), and the wall
 * clock with glFinish around each phase where it has none. Times are never asserted (they are the
 * benchmarks' business, bench_phases); what is asserted is the GL work timing adds, that it changes
 * no pixel, that phases add up over sample passes and tiles, and that no impossible time is given. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_warnings.h"

enum { W = 64, H = 48 };

static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
static const char *const plan_name[] = {"fused", "tree", "multipass"};
#define PLANS ((int)(sizeof plans / sizeof plans[0]))

/* Skips the calling test, naming why, unless ctx has GPU timers. */
static void require_timers(macs_context *ctx)
{
    macs_features f;
    macs_context_get_features(ctx, &f);
    if (f.timer_query)
        return;
    print_message("[  SKIPPED ] the driver (or MACS_TEST_PROFILE) has neither GL_ARB_timer_query nor "
                  "GL_EXT_timer_query\n");
    skip();
}

/* The second of two renders (the cached frame) of s into pixels; its stats. */
static bg_render_stats cached(bg_renderer *r, bg_scene *s, const bg_render_settings *set, unsigned char *pixels)
{
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, pixels};
    util_expect_render_ok(r, bg_render_gpu(r, s, set, &img), "first frame");
    util_expect_render_ok(r, bg_render_gpu(r, s, set, &img), "cached frame");
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    return st;
}

/* The phases' sum, printed beside the call's time. With one span a phase (one sample pass, one
 * tile), no phase may be longer than the call: its commands ran inside it. Their sum may be, where
 * the GPU overlaps one phase's end with the next one's start (llvmpipe's tiles do). */
static double expect_phases_within_call(const bg_render_stats *st, bool one_span_each, const char *label)
{
    double sum = 0.0;
    for (int p = 0; p < BG_PHASE_COUNT_; p++) {
        assert_true(st->phase_ms[p] >= 0.0);
        if (one_span_each && st->phase_ms[p] > st->total_ms * 1.01 + 0.1)
            fail_msg("%s: phase %d took %.3f ms of a call of %.3f ms", label, p, st->phase_ms[p], st->total_ms);
        sum += st->phase_ms[p];
    }
    print_message("%s: phases %.3f ms of a %.3f ms call\n", label, sum, st->total_ms);
    return sum;
}

/* With GPU timers a timed frame waits for nothing more than the untimed one: its syncs are the
 * untimed frame's plus the timers' reads after the frame's end (plus, in the multipass, the reads of
 * its shaded-fragment counts), and its pixels are the same bytes. */
static void timers_add_no_wait(void **state)
{
    (void)state;
    require_timers(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    for (int i = 0; i < PLANS; i++) {
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_settings set = util_plan_settings(plans[i], 1);
        unsigned char plain[W * H * 4], timed[W * H * 4];
        bg_render_stats a = cached(r, s, &set, plain);
        set.gpu_timing = true;
        bg_render_stats b = cached(r, s, &set, timed);
        char label[64];
        snprintf(label, sizeof label, "%s, timed", plan_name[i]);
        assert_false(a.timed);
        assert_int_equal(a.timing, BG_TIMING_NONE);
        assert_true(b.timed);
        assert_int_equal(b.timing, BG_TIMING_GPU_TIMERS);
        assert_memory_equal(plain, timed, sizeof plain);
        assert_int_equal(a.gl_work.timer_results, 0);
        /* A timer per phase of the frame, at least setup, intersection and resolve. */
        assert_true(b.gl_work.timer_results >= 3);
        uint64_t added = b.gl_work.syncs - a.gl_work.syncs - b.gl_work.timer_results;
        print_message("%s: %llu syncs untimed, %llu timed of which %llu timer reads\n", plan_name[i],
                      (unsigned long long)a.gl_work.syncs, (unsigned long long)b.gl_work.syncs,
                      (unsigned long long)b.gl_work.timer_results);
        if (plans[i] == BG_PLAN_MULTIPASS)
            assert_true(added <= (uint64_t)(b.passes[BG_PASS_SHADOW] + b.passes[BG_PASS_LIGHT]));
        else
            assert_int_equal(added, 0);
        /* Everything else the frame issues is the same. */
        assert_int_equal(a.gl_work.draws, b.gl_work.draws);
        assert_int_equal(a.gl_work.readback_bytes, b.gl_work.readback_bytes);
        assert_int_equal(a.gl_work.upload_bytes, b.gl_work.upload_bytes);
        double sum = expect_phases_within_call(&b, plans[i] != BG_PLAN_MULTIPASS, label);
        assert_true(sum > 0.0);
        bg_renderer_destroy(r);
    }
    bg_scene_destroy(s);
}

/* Phases add up over an entry call's sample passes and tiles: a timer per phase of every pass. */
static void phases_add_up_over_samples_and_tiles(void **state)
{
    (void)state;
    require_timers(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_renderer *r = util_renderer(util_fx.ctx);
    unsigned char px[W * H * 4];
    bg_render_settings set = util_plan_settings(BG_PLAN_FUSED, 1);
    set.gpu_timing = true;
    bg_render_stats one = cached(r, s, &set, px);
    set.samples = 4;
    bg_render_stats four = cached(r, s, &set, px);
    print_message("fused: %llu timer reads at 1 sample, %llu at 4\n", (unsigned long long)one.gl_work.timer_results,
                  (unsigned long long)four.gl_work.timer_results);
    assert_int_equal(four.gl_work.timer_results, 4 * one.gl_work.timer_results);
    expect_phases_within_call(&four, false, "fused, 4 samples");
    /* Tiles: a 320x240 image in a 1 MiB budget. */
    enum { TW = 320, TH = 240 };
    unsigned char *big = malloc((size_t)TW * TH * 4);
    assert_non_null(big);
    set.samples = 1;
    set.gpu_memory_budget = 1024.0 * 1024.0;
    bg_image img = {TW, TH, BG_PIXEL_RGBA8, 0, big};
    util_expect_render_ok(r, bg_render_gpu(r, s, &set, &img), "tiled frame");
    bg_render_stats tiled;
    bg_renderer_get_stats(r, &tiled);
    print_message("fused: %d tiles, %llu timer reads\n", tiled.tiles, (unsigned long long)tiled.gl_work.timer_results);
    assert_true(tiled.tiles > 1);
    assert_int_equal(tiled.gl_work.timer_results, (uint64_t)tiled.tiles * one.gl_work.timer_results);
    assert_true(tiled.timed);
    expect_phases_within_call(&tiled, false, "fused, tiled");
    free(big);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* Without timer queries the wall clock times the phases, named in the stats, with glFinish around
 * each phase: more syncs, no timer reads, the same pixels. */
static void wall_clock_without_timers(void **state)
{
    (void)state;
    macs_context *ctx = util_context_hiding(util_fx.headless, "GL_ARB_timer_query GL_EXT_timer_query");
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    for (int i = 0; i < PLANS; i++) {
        bg_render_settings set = util_plan_settings(plans[i], 1);
        unsigned char plain[W * H * 4], timed[W * H * 4];
        bg_render_stats a = cached(r, s, &set, plain);
        set.gpu_timing = true;
        bg_render_stats b = cached(r, s, &set, timed);
        assert_true(b.timed);
        assert_int_equal(b.timing, BG_TIMING_WALL_CLOCK);
        assert_int_equal(b.gl_work.timer_results, 0);
        /* At least a glFinish at the start and one at each of three phases' ends. */
        assert_true(b.gl_work.syncs >= a.gl_work.syncs + 4);
        assert_memory_equal(plain, timed, sizeof plain);
        expect_phases_within_call(&b, plans[i] != BG_PLAN_MULTIPASS, plan_name[i]);
    }
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* The first timed call on a new GL context (the fused plan: one span a phase): whatever the driver's
 * timers say, the stats hold either phases no longer than the call, or none (timed false) with a warning saying why. llvmpipe reports
 * its absolute clock for a query begun before a context's first draw (macs_timer_result), which the
 * renderer must catch. */
static void first_call_never_gives_an_impossible_time(void **state)
{
    (void)state;
    macs_headless *h = util_headless();
    macs_context *ctx = util_context(h, NULL);
    require_timers(ctx);
    util_warnings warnings = {0};
    bg_renderer_desc rd = {0};
    rd.context = ctx;
    rd.logger.func = util_warnings_collect;
    rd.logger.user = &warnings;
    bg_renderer *r = NULL;
    char message[512];
    assert_int_equal(bg_renderer_create(&rd, &r, message, sizeof message), BG_OK);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_render_settings set = util_plan_settings(BG_PLAN_FUSED, 1);
    set.gpu_timing = true;
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    util_expect_render_ok(r, bg_render_gpu(r, s, &set, &img), "first timed frame");
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    print_message("first call: timed %d, %d warning(s): %s\n", st.timed, warnings.count, warnings.all);
    if (st.timed) {
        assert_int_equal(st.timing, BG_TIMING_GPU_TIMERS);
        expect_phases_within_call(&st, true, "first call");
    } else {
        assert_int_equal(st.timing, BG_TIMING_NONE);
        assert_non_null(strstr(warnings.all, "timer queries are unreliable"));
        for (int p = 0; p < BG_PHASE_COUNT_; p++)
            assert_true(st.phase_ms[p] == 0.0);
    }
    /* The next call is timed. */
    util_expect_render_ok(r, bg_render_gpu(r, s, &set, &img), "second timed frame");
    bg_renderer_get_stats(r, &st);
    assert_true(st.timed);
    expect_phases_within_call(&st, true, "second call");
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
    macs_headless_destroy(h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(timers_add_no_wait),
        cmocka_unit_test(phases_add_up_over_samples_and_tiles),
        cmocka_unit_test(wall_clock_without_timers),
        cmocka_unit_test(first_call_never_gives_an_impossible_time),
    };
    return cmocka_run_group_tests_name("bg_gpu_timing", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
