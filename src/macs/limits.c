/* Real limits as GL reports them, and the effective ones passes obey after the caller's caps. */
#include <stdio.h>

#include "internal.h"

static int capped(int real, int cap)
{
    /* A cap lowers a limit to test or emulate smaller hardware; it never promises more than GL has. */
    return cap > 0 && cap < real ? cap : real;
}

/* The struct holds exactly the ints the one list names, so a field missing from the list (and so
 * from every cap, claim and check) stops the build. */
#define MACS_COUNT_FIELD_(field) +1
typedef char macsi_limit_list_matches_struct_[sizeof(macs_limits) == sizeof(int) * (0 MACS_LIMIT_FIELDS(MACS_COUNT_FIELD_)) ? 1 : -1];
#undef MACS_COUNT_FIELD_

void macsi_limits_query(macs_context *ctx)
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
    /* GL 2.0 promises 32; only MACS's vertex shader spends any (macs_uv), see macs_limits. */
    v = 0; ctx->gl.GetIntegerv(GL_MAX_VARYING_FLOATS, &v);
    r->max_varying_components = v < 32 ? 32 : v;
    /* Depth/stencil objects are renderbuffers of the output size, so the smaller limit rules both. */
    GLint rb = 0;
    ctx->gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
    if (rb > 0 && rb < r->max_texture_size)
        r->max_texture_size = rb;
    /* A pass draws its outputs whole, so an output larger than the viewport could be cannot be
     * drawn either: the viewport's limit joins the two (GL 2.1 guarantees at least the window's). */
    GLint vp[2] = {0, 0};
    ctx->gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    int viewport = vp[0] < vp[1] ? vp[0] : vp[1];
    if (viewport > 0 && viewport < r->max_texture_size)
        r->max_texture_size = viewport;
    /* GL 2.1 guarantees at least one of each; a driver reporting less would make every pass fail. */
    if (r->max_draw_buffers < 1) r->max_draw_buffers = 1;
    if (r->max_color_attachments < 1) r->max_color_attachments = 1;
}

macs_status macsi_limits_check_caps(const macs_limits *caps, const char *name, char *message, size_t size)
{
#define MACS_CHECK_CAP_(field) \
    if (caps->field < 0) { \
        snprintf(message, size, "macs_context_create: desc.%s." #field " %d: must be 0 (no override) " \
                 "or positive", name, caps->field); \
        return MACS_ERR_INVALID_ARGUMENT; \
    }
    MACS_LIMIT_FIELDS(MACS_CHECK_CAP_)
#undef MACS_CHECK_CAP_
    return MACS_OK;
}

void macsi_apply_caps(macs_context *ctx, const macs_limits *claims, const macs_limits *profile_caps,
                      const macs_limits *caps)
{
    /* A claim replaces what GL reports, larger or not; then every cap lowers, the smaller winning. */
#define MACS_APPLY_CAP_(field) \
    ctx->effective.field = claims->field > 0 ? claims->field : ctx->real.field; \
    if (profile_caps) \
        ctx->effective.field = capped(ctx->effective.field, profile_caps->field); \
    ctx->effective.field = capped(ctx->effective.field, caps->field);
    MACS_LIMIT_FIELDS(MACS_APPLY_CAP_)
#undef MACS_APPLY_CAP_
    ctx->claims = *claims;
}

int macsi_outputs_per_chunk(const macs_context *ctx)
{
    int n = ctx->effective.max_draw_buffers;
    if (ctx->effective.max_color_attachments < n)
        n = ctx->effective.max_color_attachments;
    /* Run-time buffer lists live on the stack; no GL implementation offers more than this. */
    return n > 64 ? 64 : n;
}

void macs_context_get_limits(const macs_context *ctx, macs_limits *real, macs_limits *effective)
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
