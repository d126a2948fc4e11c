/* GPU timers (macs_timer): a GL_TIME_ELAPSED query per timer. The ARB and EXT timer extensions share
 * the query target and differ only in the name of the 64-bit result function, picked once here. */
#include "internal.h"

struct macs_timer {
    macs_context *ctx;
    GLuint query;
    bool ended; /* a stretch was timed and not begun again since */
    struct macs_timer *prev, *next;
};

void macsi_timer_probe(macs_context *ctx)
{
    ctx->query_result64 = NULL;
    if (ctx->features.timer_query)
        ctx->query_result64 = ctx->timer_arb ? ctx->gl.GetQueryObjectui64v : ctx->gl.GetQueryObjectui64vEXT;
    /* A driver that lists the extension but exports no result function gets no timers. */
    ctx->features.timer_query = ctx->query_result64 != NULL;
}

macs_status macs_timer_create(macs_context *ctx, macs_timer **timer)
{
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!timer)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_timer_create: timer is NULL");
    *timer = NULL;
    if (!ctx->features.timer_query)
        return macsi_fail(ctx, MACS_ERR_GL_UNSUPPORTED, "macs_timer_create: the context has neither "
                         "GL_ARB_timer_query nor GL_EXT_timer_query (or desc.hidden_extensions or the profile "
                         "hides them)");
    macs_timer *t = macsi_calloc(&ctx->allocator, 1, sizeof *t);
    if (!t)
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "macs_timer_create: out of memory");
    macsi_gl_drain(ctx);
    t->ctx = ctx;
    ctx->gl.GenQueries(1, &t->query);
    macs_status st = macsi_gl_check(ctx, "macs_timer_create: glGenQueries");
    if (st != MACS_OK) {
        macsi_free(&ctx->allocator, t);
        return st;
    }
    MACS_LIST_PUSH(ctx->timers, t);
    *timer = t;
    return MACS_OK;
}

macs_status macs_timer_begin(macs_timer *timer)
{
    if (!timer)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = timer->ctx;
    if (ctx->running_timer)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_timer_begin: %s timer of this context is running "
                         "(GL times one stretch at a time); end it first",
                         ctx->running_timer == timer ? "this" : "another");
    macsi_gl_drain(ctx);
    ctx->gl.BeginQuery(GL_TIME_ELAPSED, timer->query);
    macs_status st = macsi_gl_check(ctx, "macs_timer_begin: glBeginQuery(GL_TIME_ELAPSED)");
    if (st == MACS_OK) {
        ctx->running_timer = timer;
        timer->ended = false;
    }
    return st;
}

macs_status macs_timer_end(macs_timer *timer)
{
    if (!timer)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = timer->ctx;
    if (ctx->running_timer != timer)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_timer_end: the timer is not running");
    ctx->gl.EndQuery(GL_TIME_ELAPSED);
    ctx->running_timer = NULL;
    timer->ended = true;
    return macsi_gl_check(ctx, "macs_timer_end: glEndQuery(GL_TIME_ELAPSED)");
}

macs_status macs_timer_result(macs_timer *timer, uint64_t *nanoseconds)
{
    if (!timer)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = timer->ctx;
    if (!nanoseconds)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_timer_result: nanoseconds is NULL");
    if (!timer->ended)
        return macsi_fail(ctx, MACS_ERR_NO_RESULT, "macs_timer_result: the timer %s",
                         ctx->running_timer == timer ? "is running; end it first" : "was never ended");
    macsi_gl_drain(ctx);
    GLuint64 value = 0;
    macsi_timer_result(ctx, timer->query, &value);
    macs_status st = macsi_gl_check(ctx, "macs_timer_result: glGetQueryObjectui64v");
    if (st == MACS_OK)
        *nanoseconds = value;
    return st;
}

void macs_timer_destroy(macs_timer *timer)
{
    if (!timer)
        return;
    macs_context *ctx = timer->ctx;
    if (ctx->running_timer == timer) {
        ctx->gl.EndQuery(GL_TIME_ELAPSED);
        ctx->running_timer = NULL;
    }
    ctx->gl.DeleteQueries(1, &timer->query);
    MACS_LIST_REMOVE(ctx->timers, timer);
    macsi_free(&ctx->allocator, timer);
}
