/* The renderer object: creation, sticky first error (Embree style), statistics, teardown. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "gpu_internal.h"

bg_status gpu_fail(bg_renderer *r, bg_status status, const char *format, ...)
{
    char buffer[GPU_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    vsnprintf(buffer, sizeof buffer, format, args);
    va_end(args);
    if (r->error == BG_OK && status != BG_OK) {
        r->error = status;
        memcpy(r->message, buffer, sizeof buffer);
    }
    if (r->log)
        r->log(BG_LOG_ERROR, buffer, r->log_user);
    return status;
}

bg_status gpu_fail_macs(bg_renderer *r, macs_status ms, const char *what)
{
    bg_status st;
    switch (ms) {
    case MACS_ERR_GPU_OUT_OF_MEMORY: st = BG_ERR_GPU_OUT_OF_MEMORY; break;
    case MACS_ERR_OUT_OF_MEMORY: st = BG_ERR_OUT_OF_MEMORY; break;
    case MACS_ERR_LIMIT: st = BG_ERR_LIMIT; break;
    case MACS_ERR_INVALID_ARGUMENT: st = BG_ERR_INVALID_ARGUMENT; break;
    default: st = BG_ERR_GL; break;
    }
    const char *detail = macs_context_error_message(r->ctx);
    st = gpu_fail(r, st, "bg_render_gpu: %s: %s (%s)", what, detail && *detail ? detail : macs_status_string(ms),
                  macs_status_string(ms));
    /* MACS keeps only its first error; ours now holds it, so the next MACS failure is reported too. */
    macs_context_clear_error(r->ctx);
    return st;
}

bg_status bg_renderer_create(const bg_renderer_desc *desc, bg_renderer **out_renderer)
{
    if (out_renderer)
        *out_renderer = NULL;
    if (!desc || !out_renderer || !desc->context)
        return BG_ERR_INVALID_ARGUMENT;
    if (!bg_allocator_valid(&desc->allocator))
        return BG_ERR_INVALID_ARGUMENT;
    bg_renderer *r = bg_alloc(&desc->allocator, sizeof *r);
    if (!r)
        return BG_ERR_OUT_OF_MEMORY;
    memset(r, 0, sizeof *r);
    r->allocator = desc->allocator;
    r->log = desc->log;
    r->log_user = desc->log_user;
    r->ctx = desc->context;
    macs_context_limits(r->ctx, NULL, &r->limits);
    macs_features feats;
    macs_context_features(r->ctx, &feats);
    r->float_depth = desc->float_depth && feats.depth_buffer_float;
    if (desc->half_gbuffer) {
        /* Once per renderer: the formats are then fixed, so targets made once stay right. A GL
         * without renderable RGBA16F still renders, at full precision: a warning, not an error. */
        char why[512];
        r->half_gbuffer = gpu_half_probe(r, why, sizeof why);
        if (!r->half_gbuffer && r->log) {
            char message[GPU_MESSAGE_SIZE];
            snprintf(message, sizeof message, "bg_renderer_create: RGBA16F G-buffer unsupported (%s); using RGBA32F",
                     why);
            r->log(BG_LOG_WARNING, message, r->log_user);
        }
    }
    *out_renderer = r;
    return BG_OK;
}

void gpu_release_all(bg_renderer *r)
{
    gpu_passes_release(r);
    gpu_targets_release(r);
    gpu_scene_textures_release(r);
    memset(&r->key, 0, sizeof r->key);
}

void bg_renderer_destroy(bg_renderer *renderer)
{
    if (!renderer)
        return;
    gpu_release_all(renderer);
    bg_allocator a = renderer->allocator;
    bg_free(&a, renderer);
}

bg_status bg_renderer_error(const bg_renderer *renderer)
{
    return renderer ? renderer->error : BG_ERR_INVALID_ARGUMENT;
}

const char *bg_renderer_error_message(const bg_renderer *renderer)
{
    return renderer ? renderer->message : "renderer is NULL";
}

void bg_renderer_clear_error(bg_renderer *renderer)
{
    if (!renderer)
        return;
    renderer->error = BG_OK;
    renderer->message[0] = '\0';
}

void bg_renderer_stats(const bg_renderer *renderer, bg_render_stats *stats)
{
    if (!stats)
        return;
    if (!renderer) {
        memset(stats, 0, sizeof *stats);
        return;
    }
    *stats = renderer->stats;
}
