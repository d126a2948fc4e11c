/* The renderer's error sink: every failure of the GPU path is recorded here (the first one sticks,
 * through the record MACS's context and the scene keep too) and sent to the logger, as are the
 * warnings and notes. Each message begins with the name of the public call that made it
 * (bg_renderer.entry, which the entry point sets), written here once: a failure deep in a plan reads
 * the same whichever entry point it ran under. A leaf of gpu/: every other file reports through it,
 * and it calls none of them. */
#include <stdarg.h>
#include <stdio.h>

#include "shared.h"

/* "<entry>: ", what every message of the running call begins with. */
typedef struct entry_prefix {
    char s[64];
} entry_prefix;

static entry_prefix prefix_of(const bg_renderer *r)
{
    entry_prefix p;
    snprintf(p.s, sizeof p.s, "%s: ", r->entry ? r->entry : "bg_render_gpu");
    return p;
}

/* Records the first error (prefix, then the formatted text) and sends it to the logger. */
static bg_status vfail(bg_renderer *r, bg_status status, const char *prefix, const char *format, va_list args)
{
    char buffer[MACS_MESSAGE_SIZE];
    const char *message = macs_first_error_vrecord(&r->error, status, buffer, prefix, format, args);
    if (r->logger.func)
        r->logger.func(BG_LOG_ERROR, message, r->logger.user);
    return status;
}

static bg_status fail_unprefixed(bg_renderer *r, bg_status status, const char *format, ...) GPU_PRINTF_(3, 4);
static bg_status fail_unprefixed(bg_renderer *r, bg_status status, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vfail(r, status, NULL, format, args);
    va_end(args);
    return status;
}

bg_status bgi_gpu_fail(bg_renderer *r, bg_status status, const char *format, ...)
{
    entry_prefix prefix = prefix_of(r);
    va_list args;
    va_start(args, format);
    vfail(r, status, prefix.s, format, args);
    va_end(args);
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
    bg_status st = bgi_gpu_fail(r, status_of_macs(ms), "%s: %s (%s)", what,
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
    entry_prefix prefix = prefix_of(r);
    va_list args;
    va_start(args, format);
    macs_message_vformat(message, prefix.s, format, args);
    va_end(args);
    r->logger.func(level, message, r->logger.user);
}

bg_status bgi_gpu_fail_checked(bg_renderer *r, bg_status status, const char *message)
{
    return fail_unprefixed(r, status, "%s", message);
}
