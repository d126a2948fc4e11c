/* Status strings, the context's sticky first error, and GL error checks. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

const char *macs_status_string(macs_status status)
{
#define MACS_STATUS_CASE_(name, value, message) case name: return message;
    switch (status) {
        MACS_STATUS_LIST(MACS_STATUS_CASE_)
    default:
        break;
    }
#undef MACS_STATUS_CASE_
    return "unknown status";
}

void macsi_log(const macs_context *ctx, macs_log_level level, const char *message)
{
    if (ctx->logger.func)
        ctx->logger.func(level, message, ctx->logger.user);
}

/* Every MACS message starts with its status's message: "<status message>: <details>". The status
 * messages are short phrases, far below the prefix's room. */
enum { PREFIX_SIZE = 128 };
static const char *status_prefix(char prefix[PREFIX_SIZE], macs_status status)
{
    snprintf(prefix, PREFIX_SIZE, "%s: ", macs_status_string(status));
    return prefix;
}

macs_status macsi_fail(macs_context *ctx, macs_status status, const char *format, ...)
{
    char prefix[PREFIX_SIZE], buffer[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    const char *message =
        macs_first_error_vrecord(&ctx->error, status, buffer, status_prefix(prefix, status), format, args);
    va_end(args);
    macsi_log(ctx, MACS_LOG_ERROR, message);
    return status;
}

void macsi_report(macs_logger logger, char *message, size_t size, macs_status status,
                 const char *format, ...)
{
    char prefix[PREFIX_SIZE], buffer[MACS_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    macs_message_vformat(buffer, status_prefix(prefix, status), format, args);
    va_end(args);
    macs_message_give(message, size, buffer);
    if (logger.func)
        logger.func(MACS_LOG_ERROR, buffer, logger.user);
}

macs_status macs_context_error(const macs_context *ctx)
{
    return ctx ? (macs_status)ctx->error.status : MACS_ERR_INVALID_ARGUMENT;
}

const char *macs_context_error_message(const macs_context *ctx)
{
    return ctx ? ctx->error.message : "";
}

void macs_context_clear_error(macs_context *ctx)
{
    if (!ctx)
        return;
    macs_first_error_clear(&ctx->error);
}

void macsi_gl_drain(macs_context *ctx)
{
    /* Errors left by the caller's own GL code must not be blamed on MACS. The bound stops a broken
     * implementation that never returns GL_NO_ERROR from hanging us. */
    for (int i = 0; i < 32 && ctx->gl.GetError() != GL_NO_ERROR; i++)
        ;
}

macs_status macsi_gl_current(macs_context *ctx, const char *where)
{
    /* Without a current context every GL call does nothing and names come back 0: a shader then
     * "fails to compile" with an empty log. GL_VERSION is NULL exactly then (GL 2.1 section 6.1.11
     * defines it for every context), so one cheap query tells the caller what is really wrong. */
    if (ctx->gl.GetString(GL_VERSION))
        return MACS_OK;
    return macsi_fail(ctx, MACS_ERR_CONTEXT,
                     "%s: no OpenGL context is current on this thread (glGetString(GL_VERSION) is NULL): make the "
                     "context this MACS context was created on current (macs_headless_make_current, or your "
                     "toolkit's call) before using it",
                     where);
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

macs_status macsi_gl_check(macs_context *ctx, const char *what)
{
    GLenum e = ctx->gl.GetError();
    if (e == GL_NO_ERROR)
        return MACS_OK;
    macsi_gl_drain(ctx);
    if (e == GL_OUT_OF_MEMORY)
        return macsi_fail(ctx, MACS_ERR_GPU_OUT_OF_MEMORY, "%s: GL_OUT_OF_MEMORY", what);
    return macsi_fail(ctx, MACS_ERR_GL, "%s: %s (0x%04x)", what, gl_error_name(e), (unsigned)e);
}
