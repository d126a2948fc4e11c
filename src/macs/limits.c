/* Real limits as GL reports them, and the effective ones passes obey after the caller's caps. */
#include <stdio.h>

#include "internal.h"

static int capped(int real, int cap)
{
    /* A cap lowers a limit to test or emulate smaller hardware; it never promises more than GL has. */
    return cap > 0 && cap < real ? cap : real;
}

void macs_limits_query(macs_context *ctx)
{
    GLint v;
    macs_limits *r = &ctx->real;
    v = 0; ctx->gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &v); r->max_draw_buffers = v;
    v = 0; ctx->gl.GetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &v); r->max_color_attachments = v;
    v = 0; ctx->gl.GetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &v); r->max_texture_units = v;
    v = 0; ctx->gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &v); r->max_texture_size = v;
    /* GL 2.0 promises 64; a driver reporting less is taken at that word rather than at zero. */
    v = 0; ctx->gl.GetIntegerv(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS, &v);
    r->max_uniform_components = v < 64 ? 64 : v;
    /* Depth/stencil objects are renderbuffers of the output size, so the smaller limit rules both. */
    GLint rb = 0;
    ctx->gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    if (rb > 0 && rb < r->max_texture_size)
        r->max_texture_size = rb;
    /* GL 2.1 guarantees at least one of each; a driver reporting less would make every pass fail. */
    if (r->max_draw_buffers < 1) r->max_draw_buffers = 1;
    if (r->max_color_attachments < 1) r->max_color_attachments = 1;
}

macs_status macs_limits_check_caps(const macs_limits *caps, char *message, size_t size)
{
    if (caps->max_draw_buffers < 0 || caps->max_color_attachments < 0 || caps->max_texture_units < 0 ||
        caps->max_texture_size < 0 || caps->max_uniform_components < 0) {
        snprintf(message, size, "caps must be 0 (no override) or positive");
        return MACS_ERR_INVALID_ARGUMENT;
    }
    return MACS_OK;
}

void macs_apply_caps(macs_context *ctx, const macs_limits *caps)
{
    ctx->effective.max_draw_buffers = capped(ctx->real.max_draw_buffers, caps->max_draw_buffers);
    ctx->effective.max_color_attachments = capped(ctx->real.max_color_attachments, caps->max_color_attachments);
    ctx->effective.max_texture_units = capped(ctx->real.max_texture_units, caps->max_texture_units);
    ctx->effective.max_texture_size = capped(ctx->real.max_texture_size, caps->max_texture_size);
    ctx->effective.max_uniform_components = capped(ctx->real.max_uniform_components, caps->max_uniform_components);
}

int macs_outputs_per_chunk(const macs_context *ctx)
{
    int n = ctx->effective.max_draw_buffers;
    if (ctx->effective.max_color_attachments < n)
        n = ctx->effective.max_color_attachments;
    /* Run-time buffer lists live on the stack; no GL implementation offers more than this. */
    return n > 64 ? 64 : n;
}

void macs_context_limits(const macs_context *ctx, macs_limits *real, macs_limits *effective)
{
    if (!ctx)
        return;
    if (real)
        *real = ctx->real;
    if (effective)
        *effective = ctx->effective;
}

int macs_context_max_uniform_components(const macs_context *ctx)
{
    return ctx ? ctx->effective.max_uniform_components : 0;
}
