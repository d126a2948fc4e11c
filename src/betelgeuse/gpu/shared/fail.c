/* The renderer's error sink: every failure of the GPU path is recorded here (the first one sticks,
 * through the record MACS's context and the scene keep too) and sent to the logger, as are the
 * warnings and notes. A leaf of gpu/: every other file reports through it, and it calls none of them. */
#include <stdarg.h>
#include <stdio.h>

#include "shared.h"

bg_status bgi_gpu_fail(bg_renderer *r, bg_status status, const char *format, ...)
{
    char buffer[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    const char *message = macs_first_error_vrecord(&r->error, status, buffer, NULL, format, args);
    va_end(args);
    if (r->logger.func)
        r->logger.func(BG_LOG_ERROR, message, r->logger.user);
    return status;
}

/* The renderer's status for a MACS failure: resource exhaustion and caller mistakes keep their
 * meaning, anything else is the GPU path failing. */
static bg_status status_of_macs(macs_status ms)
{
    switch (ms) {
    case MACS_ERR_GPU_OUT_OF_MEMORY: return BG_ERR_GPU_OUT_OF_MEMORY;
    case MACS_ERR_OUT_OF_MEMORY: return BG_ERR_OUT_OF_MEMORY;
    case MACS_ERR_LIMIT: return BG_ERR_LIMIT;
    case MACS_ERR_INVALID_ARGUMENT: return BG_ERR_INVALID_ARGUMENT;
    default: return BG_ERR_GL;
    }
}

bg_status bgi_gpu_fail_macs(bg_renderer *r, macs_status ms, const char *what)
{
    const char *detail = macs_context_error_message(r->ctx);
    bg_status st = bgi_gpu_fail(r, status_of_macs(ms), "bg_render_gpu: %s: %s (%s)", what,
                            detail && *detail ? detail : macs_status_string(ms), macs_status_string(ms));
    /* MACS keeps only its first error; ours now holds it, so the next MACS failure is reported too. */
    macs_context_clear_error(r->ctx);
    return st;
}

void bgi_gpu_log(const bg_renderer *r, bg_log_level level, const char *format, ...)
{
    if (!r->logger.func)
        return;
    char message[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    macs_message_vformat(message, NULL, format, args);
    va_end(args);
    r->logger.func(level, message, r->logger.user);
}
