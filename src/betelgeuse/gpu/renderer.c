/* The renderer object: creation (whose failures say why, like every create call's), the first
 * error's accessors (fail.c records it), statistics, teardown. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "driver.h"

/* Before the renderer exists its failures go to the caller's buffer and the desc's logger, as
 * macs_context_create's do. */
static bg_status create_fail(const bg_renderer_desc *desc, char *message, size_t message_size, bg_status status,
                             const char *format, ...)
{
    char buffer[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    macs_message_vformat(buffer, "bg_renderer_create: ", format, args);
    va_end(args);
    macs_message_give(message, message_size, buffer);
    if (desc && desc->logger.func)
        desc->logger.func(BG_LOG_ERROR, buffer, desc->logger.user);
    return status;
}

/* Once per renderer: the formats are then fixed, so targets made once stay right. A GL without
 * renderable RGBA16F still renders, at full precision: a warning, not an error. */
static void choose_half_gbuffer(bg_renderer *r)
{
    char why[512];
    r->half_gbuffer = bgi_gpu_half_probe(r, why, sizeof why);
    if (!r->half_gbuffer)
        bgi_gpu_log(r, BG_LOG_WARNING, "RGBA16F G-buffer unsupported (%s); using RGBA32F", why);
}

bg_status bg_renderer_create(const bg_renderer_desc *desc, bg_renderer **out_renderer, char *message,
                             size_t message_size)
{
    macs_message_give(message, message_size, "");
    if (out_renderer)
        *out_renderer = NULL;
    if (!desc)
        return create_fail(desc, message, message_size, BG_ERR_INVALID_ARGUMENT, "desc is NULL");
    if (!out_renderer)
        return create_fail(desc, message, message_size, BG_ERR_INVALID_ARGUMENT, "out_renderer is NULL");
    if (!desc->context)
        return create_fail(desc, message, message_size, BG_ERR_INVALID_ARGUMENT,
                           "desc->context is NULL (a MACS context is required)");
    if (!bgi_allocator_valid(&desc->allocator))
        return create_fail(desc, message, message_size, BG_ERR_INVALID_ARGUMENT,
                           "desc->allocator must set alloc and free together (realloc is optional), or nothing");
    bg_renderer *r = bgi_alloc(&desc->allocator, sizeof *r);
    if (!r)
        return create_fail(desc, message, message_size, BG_ERR_OUT_OF_MEMORY,
                           "out of memory: desc->allocator returned NULL for the renderer");
    memset(r, 0, sizeof *r);
    r->allocator = desc->allocator;
    r->logger = desc->logger;
    r->ctx = desc->context;
    r->entry = "bg_renderer_create";
    macs_context_get_limits(r->ctx, NULL, &r->limits);
    macs_features feats;
    macs_context_get_features(r->ctx, &feats);
    r->float_depth = desc->float_depth && feats.depth_buffer_float;
    if (desc->half_gbuffer)
        choose_half_gbuffer(r);
    *out_renderer = r;
    return BG_OK;
}

void bgi_gpu_release_all(bg_renderer *r)
{
    bgi_gpu_plans_release(r);
    bg_accumulation_destroy(r->frame_sum);
    r->frame_sum = NULL;
    bgi_gpu_marks_release(&r->frame_marks);
    bgi_gpu_meshes_release(r);
    bgi_gpu_scene_textures_release(r);
    bgi_gpu_env_tables_release(r);
    bgi_free(&r->allocator, r->readback);
    r->readback = NULL;
    r->readback_size = 0;
    bgi_gpu_timing_release(r);
}

void bg_renderer_destroy(bg_renderer *renderer)
{
    if (!renderer)
        return;
    bgi_gpu_release_all(renderer);
    bg_allocator a = renderer->allocator;
    bgi_free(&a, renderer);
}

bg_status bg_renderer_error(const bg_renderer *renderer)
{
    return renderer ? (bg_status)renderer->error.status : BG_ERR_INVALID_ARGUMENT;
}

const char *bg_renderer_error_message(const bg_renderer *renderer)
{
    return renderer ? renderer->error.message : "renderer is NULL";
}

void bg_renderer_clear_error(bg_renderer *renderer)
{
    if (!renderer)
        return;
    macs_first_error_clear(&renderer->error);
}

void bgi_gpu_entry_begin(bg_renderer *r, const bg_render_settings *settings, gpu_entry *e)
{
    macs_context_get_work(r->ctx, &e->before);
    bgi_gpu_timing_begin(r, settings && settings->gpu_timing);
}

bg_status bgi_gpu_entry_end(bg_renderer *r, const gpu_entry *e, bg_status st)
{
    /* The timers' reads are the call's work too. */
    st = bgi_gpu_timing_end(r, st);
    macs_work after;
    macs_context_get_work(r->ctx, &after);
    r->stats.gl_work = macs_work_since(&after, &e->before);
    return st;
}

void bg_renderer_get_stats(const bg_renderer *renderer, bg_render_stats *stats)
{
    if (!stats)
        return;
    if (!renderer) {
        memset(stats, 0, sizeof *stats);
        return;
    }
    *stats = renderer->stats;
}
