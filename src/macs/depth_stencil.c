/* Packed depth/stencil renderbuffers: the caller's, and the context's internal ones for split passes. */
#include <stdio.h>

#include "internal.h"

void macsi_fbo_attach_depth_stencil(macs_context *ctx, const macs_depth_stencil *ds)
{
    /* Two attachment points rather than GL_DEPTH_STENCIL_ATTACHMENT, which EXT_framebuffer_object lacks. */
    GLuint rb = ds ? ds->renderbuffer : 0;
    ctx->gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb);
    ctx->gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb);
}

macs_status macsi_fbo_check(macs_context *ctx, const char *what)
{
    GLenum status = ctx->gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE)
        return MACS_OK;
    return macsi_fail(ctx, MACS_ERR_FRAMEBUFFER, "%s: framebuffer status 0x%04x", what, (unsigned)status);
}

static macs_status clear(macs_depth_stencil *ds, float depth, unsigned stencil, unsigned write_mask)
{
    macs_context *ctx = ds->ctx;
    const macs_gl *gl = &ctx->gl;
    macsi_bind_framebuffer(ctx, ctx->scratch_fbo);
    macsi_fbo_attach_depth_stencil(ctx, ds);
    /* A framebuffer without colour needs NONE draw and read buffers to be complete under EXT_fbo. */
    static const GLenum none = GL_NONE;
    gl->DrawBuffers(1, &none);
    gl->ReadBuffer(GL_NONE);
    macs_status st = macsi_fbo_check(ctx, "clearing a depth/stencil object");
    if (st == MACS_OK) {
        gl->Disable(GL_SCISSOR_TEST);
        gl->DepthMask(GL_TRUE);
        /* The reserved bit is always written, to 0: the split invariant holds after any clear. */
        gl->StencilMask((write_mask & MACS_STENCIL_CALLER_BITS) | MACS_STENCIL_RESERVED_BITS);
        gl->ClearDepth(depth < 0.0f ? 0.0 : depth > 1.0f ? 1.0 : (double)depth);
        gl->ClearStencil((GLint)(stencil & MACS_STENCIL_CALLER_BITS));
        gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    }
    macsi_fbo_attach_depth_stencil(ctx, NULL);
    macsi_bind_framebuffer(ctx, 0);
    if (st != MACS_OK)
        return st;
    return macsi_gl_check(ctx, "clearing a depth/stencil object");
}

static macs_status create(macs_context *ctx, int width, int height, bool internal, bool want_float,
                          macs_depth_stencil **out)
{
    *out = NULL;
    if (width <= 0 || height <= 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_depth_stencil_create: size %dx%d must be positive",
                         width, height);
    int max = ctx->effective.max_texture_size;
    if (width > max || height > max)
        return macsi_fail(ctx, MACS_ERR_LIMIT, "macs_depth_stencil_create: size %dx%d exceeds the maximum %d",
                         width, height, max);
    macs_depth_stencil *ds = macsi_calloc(&ctx->allocator, 1, sizeof *ds);
    if (!ds)
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "allocating a depth/stencil object");
    ds->ctx = ctx;
    ds->width = width;
    ds->height = height;
    ds->internal = internal;
    /* Internal buffers only ever carry the split marks, so float depth would buy nothing there. */
    bool use_float = !internal && want_float && ctx->allow_float_depth && ctx->features.depth_buffer_float;
    ds->format = use_float ? MACS_DEPTH32F_STENCIL8 : MACS_DEPTH24_STENCIL8;
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    gl->GenRenderbuffers(1, &ds->renderbuffer);
    gl->BindRenderbuffer(GL_RENDERBUFFER, ds->renderbuffer);
    gl->RenderbufferStorage(GL_RENDERBUFFER, use_float ? GL_DEPTH32F_STENCIL8 : GL_DEPTH24_STENCIL8, width, height);
    gl->BindRenderbuffer(GL_RENDERBUFFER, 0);
    /* What was asked, so that GL_OUT_OF_MEMORY (or a size only desc.claims allows) reads as such. */
    char what[256];
    int driver = ctx->real.max_texture_size;
    snprintf(what, sizeof what, "macs_depth_stencil_create: glRenderbufferStorage of a %dx%d %s buffer (%.0f MiB)%s",
             width, height, use_float ? "DEPTH32F_STENCIL8" : "DEPTH24_STENCIL8",
             (double)width * (double)height * (use_float ? 8.0 : 4.0) / (1024.0 * 1024.0),
             width > driver || height > driver ? ", beyond the driver's max_texture_size: only desc.claims allows it"
                                               : "");
    macs_status st = macsi_gl_check(ctx, what);
    /* New storage is undefined; depth 1 and stencil 0 make the first run behave and set the invariant. */
    if (st == MACS_OK)
        st = clear(ds, 1.0f, 0, 0xFF);
    if (st != MACS_OK) {
        gl->DeleteRenderbuffers(1, &ds->renderbuffer);
        macsi_free(&ctx->allocator, ds);
        return st;
    }
    MACS_LIST_PUSH(ctx->depth_stencils, ds);
    *out = ds;
    return MACS_OK;
}

macs_status macs_depth_stencil_create(macs_context *ctx, const macs_depth_stencil_desc *desc,
                                      macs_depth_stencil **out)
{
    if (out)
        *out = NULL;
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!desc || !out)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_depth_stencil_create: %s is NULL",
                         desc ? "out" : "desc");
    if (desc->format != 0 && desc->format != MACS_DEPTH24_STENCIL8 && desc->format != MACS_DEPTH32F_STENCIL8)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_depth_stencil_create: desc.format %d is not a "
                         "macs_depth_format (0, %d or %d)",
                         (int)desc->format, (int)MACS_DEPTH24_STENCIL8, (int)MACS_DEPTH32F_STENCIL8);
    return create(ctx, desc->width, desc->height, false, desc->format != MACS_DEPTH24_STENCIL8, out);
}

macs_status macsi_depth_stencil_internal(macs_context *ctx, int width, int height, macs_depth_stencil **out)
{
    for (macs_depth_stencil *ds = ctx->depth_stencils; ds; ds = ds->next)
        if (ds->internal && ds->width == width && ds->height == height) {
            *out = ds;
            return MACS_OK;
        }
    return create(ctx, width, height, true, false, out);
}

void macs_depth_stencil_destroy(macs_depth_stencil *ds)
{
    if (!ds)
        return;
    macs_context *ctx = ds->ctx;
    macsi_pass_forget_depth_stencil(ctx, ds);
    ctx->gl.DeleteRenderbuffers(1, &ds->renderbuffer);
    MACS_LIST_REMOVE(ctx->depth_stencils, ds);
    macsi_free(&ctx->allocator, ds);
}

macs_depth_format macs_depth_stencil_format(const macs_depth_stencil *ds)
{
    return ds ? ds->format : MACS_DEPTH24_STENCIL8;
}

macs_status macs_depth_stencil_clear(macs_depth_stencil *ds, float depth, unsigned stencil, unsigned write_mask)
{
    if (!ds)
        return MACS_ERR_INVALID_ARGUMENT;
    if (ds->internal)
        return macsi_fail(ds->ctx, MACS_ERR_INVALID_ARGUMENT, "internal depth/stencil objects are MACS's own");
    if (!(depth == depth))
        return macsi_fail(ds->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_depth_stencil_clear: depth is NaN");
    macsi_gl_drain(ds->ctx);
    return clear(ds, depth, stencil, write_mask);
}
