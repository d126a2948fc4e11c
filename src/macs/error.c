/* Status strings, the context's sticky first error, and GL error checks. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

const char *macs_status_string(macs_status status)
{
#define MACS_STATUS_CASE_(name, message) case name: return message;
    switch (status) {
        MACS_STATUS_LIST(MACS_STATUS_CASE_)
    default:
        break;
    }
#undef MACS_STATUS_CASE_
    return "unknown status";
}

void macs_log(const macs_context *ctx, int level, const char *message)
{
    if (ctx->logger)
        ctx->logger(level, message, ctx->logger_user);
}

/* "<status message>: <details>", truncated to MACS_MESSAGE_SIZE. */
static void format_message(char buffer[MACS_MESSAGE_SIZE], macs_status status, const char *format,
                           va_list args)
{
    int n = snprintf(buffer, MACS_MESSAGE_SIZE, "%s: ", macs_status_string(status));
    if (n > 0 && n < MACS_MESSAGE_SIZE)
        vsnprintf(buffer + n, MACS_MESSAGE_SIZE - (size_t)n, format, args);
}

macs_status macs_fail(macs_context *ctx, macs_status status, const char *format, ...)
{
    char buffer[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    format_message(buffer, status, format, args);
    va_end(args);
    /* Only the first error is kept: later ones are usually consequences of it. */
    if (ctx->error == MACS_OK) {
        ctx->error = status;
        memcpy(ctx->error_message, buffer, sizeof buffer);
    }
    macs_log(ctx, MACS_LOG_ERROR, buffer);
    return status;
}

void macs_report(macs_log_fn logger, void *user, char *message, size_t size, macs_status status,
                 const char *format, ...)
{
    char buffer[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    format_message(buffer, status, format, args);
    va_end(args);
    if (message && size > 0)
        snprintf(message, size, "%s", buffer);
    if (logger)
        logger(MACS_LOG_ERROR, buffer, user);
}

macs_status macs_context_error(const macs_context *ctx)
{
    return ctx ? ctx->error : MACS_ERR_INVALID_ARGUMENT;
}

const char *macs_context_error_message(const macs_context *ctx)
{
    return ctx ? ctx->error_message : "";
}

void macs_context_clear_error(macs_context *ctx)
{
    if (!ctx)
        return;
    ctx->error = MACS_OK;
    ctx->error_message[0] = '\0';
}

void macs_gl_drain(macs_context *ctx)
{
    /* Errors left by the caller's own GL code must not be blamed on MACS. The bound stops a broken
     * implementation that never returns GL_NO_ERROR from hanging us. */
    for (int i = 0; i < 32 && ctx->gl.GetError() != GL_NO_ERROR; i++)
        ;
}

static const char *gl_error_name(GLenum e)
{
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return "unknown GL error";
    }
}

macs_status macs_gl_check(macs_context *ctx, const char *what)
{
    GLenum e = ctx->gl.GetError();
    if (e == GL_NO_ERROR)
        return MACS_OK;
    macs_gl_drain(ctx);
    if (e == GL_OUT_OF_MEMORY)
        return macs_fail(ctx, MACS_ERR_GPU_OUT_OF_MEMORY, "%s: GL_OUT_OF_MEMORY", what);
    return macs_fail(ctx, MACS_ERR_GL, "%s: %s (0x%04x)", what, gl_error_name(e), (unsigned)e);
}
