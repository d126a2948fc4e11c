/* Time per frame phase, for bg_render_settings.gpu_timing. Both plans mark their phases here, so
 * bg_render_stats.phase_ms means the same for each, and an entry call's phases add up over all its
 * sample passes and tiles.
 *
 * With GPU timers (macs_timer: ARB or EXT timer queries) each phase is a span of GL commands whose
 * GPU time is read once, after the call's last command: nothing waits between phases, so the timed
 * frame does the same work as the untimed one. Without them, the wall clock brackets each phase
 * with glFinish, which serialises the GPU and costs the frame time of its own. */
#include <string.h>
#include <time.h>

#include "../../common/alloc.h"
#include "shared.h"

/* Time between a phase's end and the next phase's start: timed, so that spans follow each other
 * without a gap of unknown work, and not kept. */
#define BETWEEN_PHASES (-1)

double bgi_gpu_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* Keeps the first timer failure for the call's end, which reports it. */
static void note(gpu_phase_timing *t, macs_status ms)
{
    if (ms && !t->failed)
        t->failed = ms;
}

/* Begins the next span, making its timer the first time the pool reaches it. */
static void span_begin(bg_renderer *r)
{
    gpu_phase_timing *t = &r->timing;
    if (t->failed)
        return;
    if (t->used == t->capacity) {
        int capacity = t->capacity ? 2 * t->capacity : 16;
        gpu_phase_span *spans = bgi_alloc(&r->allocator, (size_t)capacity * sizeof *spans);
        if (!spans) {
            t->out_of_memory = true;
            note(t, MACS_ERR_OUT_OF_MEMORY);
            return;
        }
        memset(spans, 0, (size_t)capacity * sizeof *spans);
        if (t->spans)
            memcpy(spans, t->spans, (size_t)t->capacity * sizeof *spans);
        bgi_free(&r->allocator, t->spans);
        t->spans = spans;
        t->capacity = capacity;
    }
    gpu_phase_span *s = &t->spans[t->used];
    if (!s->timer)
        note(t, macs_timer_create(r->ctx, &s->timer));
    if (!t->failed)
        note(t, macs_timer_begin(s->timer));
    t->running = !t->failed;
    s->phase = BETWEEN_PHASES;
}

/* Ends the running span as the given phase's. */
static void span_end(bg_renderer *r, int phase)
{
    gpu_phase_timing *t = &r->timing;
    if (!t->running)
        return;
    t->running = false;
    note(t, macs_timer_end(t->spans[t->used].timer));
    t->spans[t->used].phase = phase;
    t->used++;
}

void bgi_gpu_timing_begin(bg_renderer *r, bool on)
{
    gpu_phase_timing *t = &r->timing;
    t->on = on;
    t->used = 0;
    t->running = false;
    t->failed = MACS_OK;
    t->out_of_memory = false;
    memset(t->wall_ms, 0, sizeof t->wall_ms);
    if (!on)
        return;
    macs_features features;
    macs_context_get_features(r->ctx, &features);
    t->timers = features.timer_query;
    /* The wall clock times from an idle GPU, so that earlier work is not this call's. */
    if (!t->timers)
        macs_context_finish(r->ctx);
    t->start = bgi_gpu_now_ms();
    t->clock = t->start;
}

void bgi_gpu_phase_start(bg_renderer *r)
{
    gpu_phase_timing *t = &r->timing;
    if (!t->on)
        return;
    if (t->timers) {
        span_end(r, BETWEEN_PHASES);
        span_begin(r);
        return;
    }
    macs_context_finish(r->ctx);
    t->clock = bgi_gpu_now_ms();
}

void bgi_gpu_phase_end(bg_renderer *r, bg_phase phase)
{
    gpu_phase_timing *t = &r->timing;
    if (!t->on)
        return;
    if (t->timers) {
        span_end(r, (int)phase);
        span_begin(r);
        return;
    }
    macs_context_finish(r->ctx);
    double now = bgi_gpu_now_ms();
    t->wall_ms[phase] += now - t->clock;
    t->clock = now;
}

bg_status bgi_gpu_timing_end(bg_renderer *r, bg_status st)
{
    gpu_phase_timing *t = &r->timing;
    if (!t->on)
        return st;
    t->on = false;
    span_end(r, BETWEEN_PHASES);
    if (st != BG_OK)
        return st;
    double phase_ms[BG_PHASE_COUNT_] = {0}, longest = 0.0;
    if (t->timers) {
        /* The call's last command has been issued; a read-back has usually waited for it already. */
        for (int i = 0; i < t->used && !t->failed; i++) {
            uint64_t ns = 0;
            if (t->spans[i].phase == BETWEEN_PHASES)
                continue;
            note(t, macs_timer_result(t->spans[i].timer, &ns));
            phase_ms[t->spans[i].phase] += (double)ns * 1e-6;
            if ((double)ns * 1e-6 > longest)
                longest = (double)ns * 1e-6;
        }
        if (t->out_of_memory)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the phase timers (settings.gpu_timing)");
        if (t->failed)
            return bgi_gpu_fail_macs(r, t->failed, "timing the phases with GPU timers (settings.gpu_timing)");
    } else {
        memcpy(phase_ms, t->wall_ms, sizeof phase_ms);
    }
    double total = bgi_gpu_now_ms() - t->start;
    /* Every span's commands ran inside the call, so no span's GPU time can exceed the call's wall
     * time (their sum may: a GPU may overlap one phase's end with the next one's start, as llvmpipe's
     * tiles do). A driver whose timers say otherwise (macs_timer_result) gets no phase times at all. */
    if (longest > total * 1.01 + 0.1) {
        bgi_gpu_log(r, BG_LOG_WARNING, "a GPU timer reported %.3f ms for one phase of a call of %.3f ms, "
                    "which cannot be: the driver's timer queries are unreliable, so this call's phases are "
                    "not timed (stats.timed false)", longest, total);
        return BG_OK;
    }
    memcpy(r->stats.phase_ms, phase_ms, sizeof phase_ms);
    r->stats.timed = true;
    r->stats.timing = t->timers ? BG_TIMING_GPU_TIMERS : BG_TIMING_WALL_CLOCK;
    r->stats.total_ms = total;
    return BG_OK;
}

void bgi_gpu_timing_release(bg_renderer *r)
{
    gpu_phase_timing *t = &r->timing;
    for (int i = 0; i < t->capacity; i++)
        macs_timer_destroy(t->spans[i].timer);
    bgi_free(&r->allocator, t->spans);
    memset(t, 0, sizeof *t);
}
