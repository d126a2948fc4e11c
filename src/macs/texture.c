/* RGBA textures: creation, upload (whole or a region) and read-back through caller buffers with a row
 * stride, clear. Wrapping a caller's GL texture is in texture_wrap.c. */
#include <stdio.h>
#include <string.h>

#include "internal.h"

size_t macsi_texel_size(macs_format f)
{
    return f == MACS_FORMAT_RGBA8 ? 4 : 16;
}

GLenum macsi_texel_type(macs_format f)
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

/* GL describes row strides in texels, so a stride must be a whole number of texels and hold a row
 * of row_texels. */
static macs_status set_row_length(macs_texture *t, GLenum pname, int row_texels, size_t stride, const char *what)
{
    size_t ts = macsi_texel_size(t->format);
    size_t tight = (size_t)row_texels * ts;
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

void macsi_reset_pixel_store(macs_context *ctx)
{
    /* Back to GL defaults so a caller sharing the context sees what it expects. */
    ctx->gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    ctx->gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    ctx->gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    ctx->gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
}

static const char *format_name(macs_format f)
{
    return f == MACS_FORMAT_RGBA16F ? "RGBA16F" : f == MACS_FORMAT_RGBA8 ? "RGBA8" : "RGBA32F";
}

/* The GL error of glTexImage2D, told as what was asked: its size in bytes where GL ran out of memory,
 * and the driver's own limit where the size is only allowed by desc.claims (GL then refuses it with
 * GL_INVALID_VALUE, or runs out of memory). A claim exists to test big-GPU paths on a small driver,
 * so its failures must read as what they are, never as a MACS or GL bug, and never crash. */
static macs_status check_image(macs_texture *t)
{
    macs_context *ctx = t->ctx;
    GLenum e = ctx->gl.GetError();
    if (e == GL_NO_ERROR)
        return MACS_OK;
    macsi_gl_drain(ctx);
    double mib = (double)t->width * (double)t->height * (double)macsi_texel_size(t->format) / (1024.0 * 1024.0);
    int driver = ctx->real.max_texture_size;
    if (t->width > driver || t->height > driver)
        return macsi_fail(ctx, e == GL_OUT_OF_MEMORY ? MACS_ERR_GPU_OUT_OF_MEMORY : MACS_ERR_LIMIT,
                         "macs_texture_create: a %dx%d %s texture (%.0f MiB) is beyond the driver's max_texture_size "
                         "%d: only desc.claims.max_texture_size %d allows it, and GL refused it (%s)",
                         t->width, t->height, format_name(t->format), mib, driver, ctx->effective.max_texture_size,
                         e == GL_OUT_OF_MEMORY ? "GL_OUT_OF_MEMORY" : e == GL_INVALID_VALUE ? "GL_INVALID_VALUE"
                                                                                           : "a GL error");
    if (e == GL_OUT_OF_MEMORY)
        return macsi_fail(ctx, MACS_ERR_GPU_OUT_OF_MEMORY,
                         "macs_texture_create: GL ran out of memory (GL_OUT_OF_MEMORY) for a %dx%d %s texture "
                         "(%.0f MiB)", t->width, t->height, format_name(t->format), mib);
    return macsi_fail(ctx, MACS_ERR_GL, "macs_texture_create: glTexImage2D of a %dx%d %s texture failed (GL error "
                     "0x%04x)", t->width, t->height, format_name(t->format), (unsigned)e);
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
    t->filter = desc->filter;
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    if (desc->data) {
        macs_status st = set_row_length(t, GL_UNPACK_ROW_LENGTH, t->width, desc->stride, "macs_texture_create");
        if (st != MACS_OK) {
            macsi_free(&ctx->allocator, t);
            return st;
        }
    }
    gl->GenTextures(1, &t->id);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, t->id);
    macsi_texture_apply_sampling(ctx, desc->filter, desc->wrap);
    macsi_tex_image(ctx, internal_format(t->format), t->width, t->height, GL_RGBA, macsi_texel_type(t->format),
                    desc->data);
    macsi_reset_pixel_store(ctx);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    macs_status st = check_image(t);
    if (st != MACS_OK) {
        gl->DeleteTextures(1, &t->id);
        macsi_free(&ctx->allocator, t);
        return st;
    }
    MACS_LIST_PUSH(ctx->textures, t);
    *out = t;
    return MACS_OK;
}

void macsi_texture_apply_sampling(macs_context *ctx, macs_filter filter, macs_wrap wrap)
{
    GLint f = filter == MACS_FILTER_LINEAR ? GL_LINEAR : GL_NEAREST;
    GLint w = wrap == MACS_WRAP_REPEAT ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    ctx->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, f);
    ctx->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, f);
    ctx->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, w);
    ctx->gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, w);
}

void macs_texture_destroy(macs_texture *t)
{
    if (!t)
        return;
    macs_context *ctx = t->ctx;
    macsi_pass_forget_texture(ctx, t);
    /* A wrapped texture is the caller's: it outlives its macs_texture. */
    if (!t->wrapped)
        ctx->gl.DeleteTextures(1, &t->id);
    MACS_LIST_REMOVE(ctx->textures, t);
    macsi_free(&ctx->allocator, t);
}

/* Upload and read-back differ only in direction: the pixel-store row length, then one GL call.
 * glGetTexImage reads the texture itself: no framebuffer, no read-colour clamping. A read is always
 * of the whole texture (GL 2.1 has no region read of a texture); an upload may be of a region. */
static macs_status transfer(macs_texture *t, bool upload, const int region[4], void *data, size_t stride,
                            const char *fn)
{
    macs_context *ctx = t->ctx;
    macsi_gl_drain(ctx);
    macs_status st = set_row_length(t, upload ? GL_UNPACK_ROW_LENGTH : GL_PACK_ROW_LENGTH, region[2], stride, fn);
    if (st != MACS_OK)
        return st;
    ctx->gl.ActiveTexture(GL_TEXTURE0);
    ctx->gl.BindTexture(GL_TEXTURE_2D, t->id);
    if (upload)
        macsi_tex_sub_image(ctx, region, GL_RGBA, macsi_texel_type(t->format), data);
    else
        macsi_get_tex_image(ctx, t->width, t->height, GL_RGBA, macsi_texel_type(t->format), data);
    ctx->gl.BindTexture(GL_TEXTURE_2D, 0);
    macsi_reset_pixel_store(ctx);
    char what[64];
    snprintf(what, sizeof what, "%s: %s", fn, upload ? "glTexSubImage2D" : "glGetTexImage");
    return macsi_gl_check(ctx, what);
}

static macs_status transfer_whole(macs_texture *t, bool upload, void *data, size_t stride)
{
    const char *fn = upload ? "macs_texture_upload" : "macs_texture_read";
    if (!t)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!data)
        return macsi_fail(t->ctx, MACS_ERR_INVALID_ARGUMENT, "%s: data is NULL", fn);
    const int whole[4] = {0, 0, t->width, t->height};
    return transfer(t, upload, whole, data, stride, fn);
}

macs_status macs_texture_upload(macs_texture *t, const void *data, size_t stride)
{
    /* transfer() only reads through data when upload is true. */
    return transfer_whole(t, true, (void *)(uintptr_t)data, stride);
}

macs_status macs_texture_upload_region(macs_texture *t, int x, int y, int width, int height, const void *data,
                                       size_t stride)
{
    if (!t)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!data)
        return macsi_fail(t->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_upload_region: data is NULL");
    /* Compared as differences, so that no sum can overflow. */
    if (x < 0 || y < 0 || width <= 0 || height <= 0 || x > t->width - width || y > t->height - height)
        return macsi_fail(t->ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_upload_region: region %dx%d at (%d, %d) is not a non-empty part of the %dx%d "
                         "texture",
                         width, height, x, y, t->width, t->height);
    const int region[4] = {x, y, width, height};
    return transfer(t, true, region, (void *)(uintptr_t)data, stride, "macs_texture_upload_region");
}

macs_status macs_texture_read(macs_texture *t, void *data, size_t stride)
{
    return transfer_whole(t, false, data, stride);
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
    macsi_bind_framebuffer(ctx, ctx->scratch_fbo);
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
    macsi_bind_framebuffer(ctx, 0);
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

unsigned macs_texture_gl_name(const macs_texture *t)
{
    return t ? (unsigned)t->id : 0u;
}

macs_context *macs_texture_context(const macs_texture *t)
{
    return t ? t->ctx : NULL;
}
