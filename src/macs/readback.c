/* Asynchronous read-back (macs_readback): a texture read into a pixel pack buffer (core in GL 2.1),
 * queued without waiting, and taken later by mapping the buffer. The invariant: a readback holds at
 * most one read, and moves EMPTY -> PENDING (macs_texture_read_begin) -> MAPPED (macs_readback_map)
 * -> EMPTY (macs_readback_unmap); the buffer is bound to GL_PIXEL_PACK_BUFFER only inside these
 * calls, so every other read of MACS or of the caller still goes to host memory. The counted work
 * (work.c): the begin counts the bytes and no sync, the map one sync. */
#include <string.h>

#include "internal.h"

macs_status macs_readback_create(macs_context *ctx, macs_readback **out)
{
    if (out)
        *out = NULL;
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!out)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_readback_create: out is NULL");
    macs_status current = macsi_gl_current(ctx, "macs_readback_create");
    if (current != MACS_OK)
        return current;
    macs_readback *rb = macsi_calloc(&ctx->allocator, 1, sizeof *rb);
    if (!rb)
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "macs_readback_create: allocating the readback");
    rb->ctx = ctx;
    ctx->gl.GenBuffers(1, &rb->buffer);
    MACS_LIST_PUSH(ctx->readbacks, rb);
    *out = rb;
    return MACS_OK;
}

static void unmap(macs_readback *rb)
{
    const macs_gl *gl = &rb->ctx->gl;
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, rb->buffer);
    GLboolean intact = gl->UnmapBuffer(GL_PIXEL_PACK_BUFFER);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    rb->mapped = NULL;
    rb->state = MACSI_READBACK_EMPTY;
    (void)intact; /* the caller asks through macs_readback_unmap when it matters */
}

void macs_readback_destroy(macs_readback *rb)
{
    if (!rb)
        return;
    macs_context *ctx = rb->ctx;
    if (rb->state == MACSI_READBACK_MAPPED)
        unmap(rb);
    ctx->gl.DeleteBuffers(1, &rb->buffer);
    MACS_LIST_REMOVE(ctx->readbacks, rb);
    macsi_free(&ctx->allocator, rb);
}

/* The buffer's store made to hold bytes (only when the size changes: a tile after tile of one size
 * reuses it). */
static macs_status ensure_capacity(macs_readback *rb, size_t bytes)
{
    if (rb->capacity == bytes)
        return MACS_OK;
    macs_context *ctx = rb->ctx;
    rb->capacity = 0;
    ctx->gl.BufferData(GL_PIXEL_PACK_BUFFER, (GLsizeiptr)bytes, NULL, GL_STREAM_READ);
    GLenum e = ctx->gl.GetError();
    if (e != GL_NO_ERROR) {
        macsi_gl_drain(ctx);
        return macsi_fail(ctx, e == GL_OUT_OF_MEMORY ? MACS_ERR_GPU_OUT_OF_MEMORY : MACS_ERR_GL,
                         "macs_texture_read_begin: glBufferData of a %zu-byte read-back buffer failed (%s)", bytes,
                         e == GL_OUT_OF_MEMORY ? "GL_OUT_OF_MEMORY" : "a GL error");
    }
    rb->capacity = bytes;
    return MACS_OK;
}

macs_status macs_texture_read_begin(macs_texture *t, macs_readback *rb)
{
    if (!t)
        return rb ? macsi_fail(rb->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_read_begin: texture is NULL")
                  : MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = t->ctx;
    if (!rb)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_read_begin: readback is NULL");
    if (rb->ctx != ctx)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_read_begin: readback belongs to another macs_context than texture");
    if (rb->state == MACSI_READBACK_MAPPED)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_read_begin: readback is mapped; macs_readback_unmap it first");
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    size_t bytes = (size_t)t->width * (size_t)t->height * macsi_texel_size(t->format);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, rb->buffer);
    macs_status st = ensure_capacity(rb, bytes);
    if (st == MACS_OK) {
        gl->PixelStorei(GL_PACK_ROW_LENGTH, 0);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl->ActiveTexture(GL_TEXTURE0);
        gl->BindTexture(GL_TEXTURE_2D, t->id);
        macsi_get_tex_image_queued(ctx, t->width, t->height, GL_RGBA, macsi_texel_type(t->format));
        gl->BindTexture(GL_TEXTURE_2D, 0);
        macsi_reset_pixel_store(ctx);
    }
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (st == MACS_OK)
        st = macsi_gl_check(ctx, "macs_texture_read_begin: glGetTexImage into the read-back buffer");
    if (st != MACS_OK) {
        rb->state = MACSI_READBACK_EMPTY;
        return st;
    }
    /* Submitted, not waited for: the copy starts while the caller goes on. */
    gl->Flush();
    rb->state = MACSI_READBACK_PENDING;
    rb->width = t->width;
    rb->height = t->height;
    rb->format = t->format;
    return MACS_OK;
}

macs_status macs_readback_map(macs_readback *rb, const void **texels, size_t *stride)
{
    if (texels)
        *texels = NULL;
    if (stride)
        *stride = 0;
    if (!rb)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = rb->ctx;
    if (!texels)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_readback_map: texels is NULL");
    if (rb->state == MACSI_READBACK_MAPPED)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_readback_map: readback is mapped already");
    if (rb->state == MACSI_READBACK_EMPTY)
        return macsi_fail(ctx, MACS_ERR_NO_RESULT, "macs_readback_map: no read was begun into readback "
                         "(macs_texture_read_begin), or its texels were taken already");
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, rb->buffer);
    const void *p = macsi_map_pack_buffer(ctx);
    GLenum e = gl->GetError();
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (!p || e != GL_NO_ERROR) {
        macsi_gl_drain(ctx);
        /* The read is lost either way: a mapped pointer that came with an error is not trusted. */
        if (p) {
            rb->state = MACSI_READBACK_MAPPED;
            unmap(rb);
        }
        rb->state = MACSI_READBACK_EMPTY;
        return macsi_fail(ctx, e == GL_OUT_OF_MEMORY ? MACS_ERR_GPU_OUT_OF_MEMORY : MACS_ERR_GL,
                         "macs_readback_map: glMapBuffer of the %dx%d read-back buffer %s (GL error 0x%04x); its "
                         "texels are lost: read the texture again",
                         rb->width, rb->height, p ? "raised an error" : "returned NULL", (unsigned)e);
    }
    rb->state = MACSI_READBACK_MAPPED;
    rb->mapped = p;
    *texels = p;
    if (stride)
        *stride = (size_t)rb->width * macsi_texel_size(rb->format);
    return MACS_OK;
}

macs_status macs_readback_unmap(macs_readback *rb)
{
    if (!rb)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = rb->ctx;
    if (rb->state != MACSI_READBACK_MAPPED)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_readback_unmap: readback is not mapped");
    const macs_gl *gl = &ctx->gl;
    macsi_gl_drain(ctx);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, rb->buffer);
    GLboolean intact = gl->UnmapBuffer(GL_PIXEL_PACK_BUFFER);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    rb->mapped = NULL;
    rb->state = MACSI_READBACK_EMPTY;
    /* GL_FALSE: the store was lost while mapped (a mode switch, say), so what the caller read may be
     * garbage (GL 2.1, 2.9.2). */
    if (!intact)
        return macsi_fail(ctx, MACS_ERR_GL, "macs_readback_unmap: glUnmapBuffer says the buffer's contents were "
                         "lost while mapped; read the texture again");
    return macsi_gl_check(ctx, "macs_readback_unmap: glUnmapBuffer");
}

macs_status macs_readback_read(macs_readback *rb, void *data, size_t stride)
{
    if (!rb)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = rb->ctx;
    if (!data)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_readback_read: data is NULL");
    if (rb->state != MACSI_READBACK_PENDING)
        return macsi_fail(ctx, rb->state == MACSI_READBACK_EMPTY ? MACS_ERR_NO_RESULT : MACS_ERR_INVALID_ARGUMENT,
                         "macs_readback_read: %s", rb->state == MACSI_READBACK_EMPTY
                             ? "no read was begun into readback (macs_texture_read_begin), or its texels were taken "
                               "already"
                             : "readback is mapped; take the texels from the map or macs_readback_unmap it first");
    size_t ts = macsi_texel_size(rb->format), tight = (size_t)rb->width * ts;
    if (stride == 0)
        stride = tight;
    if (stride < tight || stride % ts != 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_readback_read: stride %zu must be 0 or a multiple of %zu bytes of at least %zu", stride,
                         ts, tight);
    const void *texels = NULL;
    size_t row = 0;
    macs_status st = macs_readback_map(rb, &texels, &row);
    if (st != MACS_OK)
        return st;
    for (int y = 0; y < rb->height; y++)
        memcpy((unsigned char *)data + (size_t)y * stride, (const unsigned char *)texels + (size_t)y * row, row);
    return macs_readback_unmap(rb);
}

void macs_context_flush(macs_context *ctx)
{
    if (ctx)
        ctx->gl.Flush();
}
