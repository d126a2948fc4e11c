/* RGBA textures: creation, upload and read-back through caller buffers with a row stride, clear. */
#include <string.h>

#include "internal.h"

static size_t texel_size(macs_format f)
{
    return f == MACS_FORMAT_RGBA8 ? 4 : 16;
}

static GLenum texel_type(macs_format f)
{
    return f == MACS_FORMAT_RGBA8 ? GL_UNSIGNED_BYTE : GL_FLOAT;
}

static GLint internal_format(macs_format f)
{
    switch (f) {
    case MACS_FORMAT_RGBA16F: return GL_RGBA16F_ARB;
    case MACS_FORMAT_RGBA8: return GL_RGBA8;
    default: return GL_RGBA32F_ARB;
    }
}

/* GL describes row strides in texels, so a stride must be a whole number of texels and hold a row. */
static macs_status set_row_length(macs_texture *t, GLenum pname, size_t stride, const char *what)
{
    size_t ts = texel_size(t->format);
    size_t tight = (size_t)t->width * ts;
    if (stride == 0)
        stride = tight;
    if (stride < tight || stride % ts != 0 || stride / ts > 0x7FFFFFFF)
        return macsi_fail(t->ctx, MACS_ERR_INVALID_ARGUMENT,
                         "%s: stride %zu must be 0 or a multiple of %zu bytes of at least %zu", what, stride, ts,
                         tight);
    t->ctx->gl.PixelStorei(pname, (GLint)(stride / ts));
    t->ctx->gl.PixelStorei(pname == GL_UNPACK_ROW_LENGTH ? GL_UNPACK_ALIGNMENT : GL_PACK_ALIGNMENT, 1);
    return MACS_OK;
}

static void reset_pixel_store(macs_context *ctx)
{
    /* Back to GL defaults so a caller sharing the context sees what it expects. */
    ctx->gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    ctx->gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    ctx->gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    ctx->gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
}

macs_status macs_texture_create(macs_context *ctx, const macs_texture_desc *desc, macs_texture **out)
{
    if (out)
        *out = NULL;
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!desc || !out)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_create: %s is NULL", desc ? "out" : "desc");
    if (desc->width <= 0 || desc->height <= 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_create: size %dx%d must be positive",
                         desc->width, desc->height);
    int max = ctx->effective.max_texture_size;
    if (desc->width > max || desc->height > max)
        return macsi_fail(ctx, MACS_ERR_LIMIT, "macs_texture_create: size %dx%d exceeds the maximum %d",
                         desc->width, desc->height, max);
    if ((unsigned)desc->format > MACS_FORMAT_RGBA8)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_create: desc.format %d is not a macs_format "
                         "(0 .. %d)", (int)desc->format, (int)MACS_FORMAT_RGBA8);
    if ((unsigned)desc->filter > MACS_FILTER_LINEAR)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_create: desc.filter %d is not a macs_filter "
                         "(0 .. %d)", (int)desc->filter, (int)MACS_FILTER_LINEAR);
    if ((unsigned)desc->wrap > MACS_WRAP_REPEAT)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_create: desc.wrap %d is not a macs_wrap "
                         "(0 .. %d)", (int)desc->wrap, (int)MACS_WRAP_REPEAT);
    macs_status current = macsi_gl_current(ctx, "macs_texture_create");
    if (current != MACS_OK)
        return current;
    macs_texture *t = macsi_calloc(&ctx->allocator, 1, sizeof *t);
    if (!t)
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "macs_texture_create: allocating the texture");
    t->ctx = ctx;
    t->width = desc->width;
    t->height = desc->height;
    t->format = desc->format == MACS_FORMAT_DEFAULT ? MACS_FORMAT_RGBA32F : desc->format;
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    if (desc->data) {
        macs_status st = set_row_length(t, GL_UNPACK_ROW_LENGTH, desc->stride, "macs_texture_create");
        if (st != MACS_OK) {
            macsi_free(&ctx->allocator, t);
            return st;
        }
    }
    GLint filter = desc->filter == MACS_FILTER_LINEAR ? GL_LINEAR : GL_NEAREST;
    GLint wrap = desc->wrap == MACS_WRAP_REPEAT ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    gl->GenTextures(1, &t->id);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, t->id);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
    gl->TexImage2D(GL_TEXTURE_2D, 0, internal_format(t->format), t->width, t->height, 0, GL_RGBA,
                   texel_type(t->format), desc->data);
    reset_pixel_store(ctx);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    macs_status st = macsi_gl_check(ctx, "macs_texture_create: glTexImage2D");
    if (st != MACS_OK) {
        gl->DeleteTextures(1, &t->id);
        macsi_free(&ctx->allocator, t);
        return st;
    }
    MACS_LIST_PUSH(ctx->textures, t);
    *out = t;
    return MACS_OK;
}

void macs_texture_destroy(macs_texture *t)
{
    if (!t)
        return;
    macs_context *ctx = t->ctx;
    macsi_pass_forget_texture(ctx, t);
    ctx->gl.DeleteTextures(1, &t->id);
    MACS_LIST_REMOVE(ctx->textures, t);
    macsi_free(&ctx->allocator, t);
}

/* Upload and read-back differ only in direction: the pixel-store row length, then one GL call.
 * glGetTexImage reads the texture itself: no framebuffer, no read-colour clamping. */
static macs_status transfer(macs_texture *t, bool upload, void *data, size_t stride)
{
    const char *fn = upload ? "macs_texture_upload" : "macs_texture_read";
    if (!t)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!data)
        return macsi_fail(t->ctx, MACS_ERR_INVALID_ARGUMENT, "%s: data is NULL", fn);
    macs_context *ctx = t->ctx;
    macsi_gl_drain(ctx);
    macs_status st = set_row_length(t, upload ? GL_UNPACK_ROW_LENGTH : GL_PACK_ROW_LENGTH, stride, fn);
    if (st != MACS_OK)
        return st;
    ctx->gl.ActiveTexture(GL_TEXTURE0);
    ctx->gl.BindTexture(GL_TEXTURE_2D, t->id);
    if (upload)
        ctx->gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t->width, t->height, GL_RGBA, texel_type(t->format), data);
    else
        ctx->gl.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, texel_type(t->format), data);
    ctx->gl.BindTexture(GL_TEXTURE_2D, 0);
    reset_pixel_store(ctx);
    return macsi_gl_check(ctx, upload ? "macs_texture_upload: glTexSubImage2D" : "macs_texture_read: glGetTexImage");
}

macs_status macs_texture_upload(macs_texture *t, const void *data, size_t stride)
{
    /* transfer() only reads through data when upload is true. */
    return transfer(t, true, (void *)(uintptr_t)data, stride);
}

macs_status macs_texture_read(macs_texture *t, void *data, size_t stride)
{
    return transfer(t, false, data, stride);
}

macs_status macs_texture_clear(macs_texture *t, const float rgba[4])
{
    if (!t)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!rgba)
        return macsi_fail(t->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_clear: rgba is NULL");
    macs_context *ctx = t->ctx;
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    gl->BindFramebuffer(GL_FRAMEBUFFER, ctx->scratch_fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->id, 0);
    static const GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &buffer);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    macs_status st = macsi_fbo_check(ctx, "macs_texture_clear");
    if (st == MACS_OK) {
        gl->Disable(GL_SCISSOR_TEST);
        gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl->ClearColor(rgba[0], rgba[1], rgba[2], rgba[3]);
        gl->Clear(GL_COLOR_BUFFER_BIT);
    }
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (st != MACS_OK)
        return st;
    return macsi_gl_check(ctx, "macs_texture_clear");
}

void macs_texture_size(const macs_texture *t, int *width, int *height)
{
    if (width)
        *width = t ? t->width : 0;
    if (height)
        *height = t ? t->height : 0;
}

macs_format macs_texture_format(const macs_texture *t)
{
    return t ? t->format : MACS_FORMAT_DEFAULT;
}
