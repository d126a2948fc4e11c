/* Geometries: vertex buffers that geometry passes draw (run.c, macs_pass_draw). Their bytes are
 * counted as vertex_bytes (work.c), and a buffer GL cannot allocate is named with its size. */
#include "internal.h"

static macs_status check_desc(macs_context *ctx, const macs_geometry_desc *d)
{
    if (d->vertex_count <= 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_geometry_create: desc.vertex_count %d: at least "
                         "one vertex is required", d->vertex_count);
    if (d->floats_per_vertex < 1 || d->floats_per_vertex > 64)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_geometry_create: desc.floats_per_vertex %d is "
                         "outside 1 .. 64", d->floats_per_vertex);
    /* GLsizeiptr is signed and may be 32 bits wide on the drivers of GL 2.1's age. */
    if ((uint64_t)d->vertex_count * (uint64_t)d->floats_per_vertex > (uint64_t)INT32_MAX / sizeof(float))
        return macsi_fail(ctx, MACS_ERR_LIMIT, "macs_geometry_create: %d vertices of %d floats exceed 2 GiB, the "
                         "largest buffer size every GL 2.1 driver can take", d->vertex_count, d->floats_per_vertex);
    return MACS_OK;
}

/* GL_OUT_OF_MEMORY from glBufferData becomes MACS_ERR_GPU_OUT_OF_MEMORY naming the bytes. */
static macs_status check_store(macs_context *ctx, size_t bytes, const char *where)
{
    GLenum e = ctx->gl.GetError();
    if (e == GL_OUT_OF_MEMORY)
        return macsi_fail(ctx, MACS_ERR_GPU_OUT_OF_MEMORY, "%s: GL could not allocate a %zu-byte vertex buffer", where,
                         bytes);
    if (e != GL_NO_ERROR)
        return macsi_fail(ctx, MACS_ERR_GL, "%s: GL error 0x%04x storing %zu vertex bytes", where, (unsigned)e, bytes);
    return MACS_OK;
}

macs_status macs_geometry_create(macs_context *ctx, const macs_geometry_desc *desc, macs_geometry **out)
{
    if (out)
        *out = NULL;
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!desc || !out)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_geometry_create: %s is NULL", desc ? "out" : "desc");
    macs_status st = check_desc(ctx, desc);
    if (st == MACS_OK)
        st = macsi_gl_current(ctx, "macs_geometry_create");
    if (st != MACS_OK)
        return st;
    macsi_gl_drain(ctx);
    macs_geometry *g = macsi_calloc(&ctx->allocator, 1, sizeof *g);
    if (!g)
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "allocating a geometry");
    g->ctx = ctx;
    g->vertex_count = desc->vertex_count;
    g->floats_per_vertex = desc->floats_per_vertex;
    size_t bytes = (size_t)desc->vertex_count * (size_t)desc->floats_per_vertex * sizeof(float);
    ctx->gl.GenBuffers(1, &g->buffer);
    ctx->gl.BindBuffer(GL_ARRAY_BUFFER, g->buffer);
    macsi_buffer_data(ctx, 0, (GLsizeiptr)bytes, desc->vertices, true);
    st = check_store(ctx, bytes, "macs_geometry_create");
    ctx->gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    if (st != MACS_OK) {
        ctx->gl.DeleteBuffers(1, &g->buffer);
        macsi_free(&ctx->allocator, g);
        return st;
    }
    MACS_LIST_PUSH(ctx->geometries, g);
    *out = g;
    return MACS_OK;
}

macs_status macs_geometry_upload(macs_geometry *geometry, int first, int count, const float *vertices)
{
    if (!geometry)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = geometry->ctx;
    if (!vertices)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_geometry_upload: vertices is NULL");
    if (first < 0 || count < 0 || count > geometry->vertex_count - first)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_geometry_upload: vertices %d .. %d + %d are outside "
                         "the geometry's 0 .. %d", first, first, count, geometry->vertex_count);
    macs_status st = macsi_gl_current(ctx, "macs_geometry_upload");
    if (st != MACS_OK || count == 0)
        return st;
    macsi_gl_drain(ctx);
    size_t per = (size_t)geometry->floats_per_vertex * sizeof(float);
    ctx->gl.BindBuffer(GL_ARRAY_BUFFER, geometry->buffer);
    macsi_buffer_data(ctx, (GLintptr)((size_t)first * per), (GLsizeiptr)((size_t)count * per), vertices, false);
    ctx->gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    return macsi_gl_check(ctx, "macs_geometry_upload");
}

void macs_geometry_destroy(macs_geometry *geometry)
{
    if (!geometry)
        return;
    macs_context *ctx = geometry->ctx;
    MACS_LIST_REMOVE(ctx->geometries, geometry);
    ctx->gl.DeleteBuffers(1, &geometry->buffer);
    macsi_free(&ctx->allocator, geometry);
}
