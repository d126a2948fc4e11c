/* The work counters (macs_work): every GL call they count goes through one function here, which
 * counts it and issues it, so a count cannot drift from the calls. The rest of libmacs calls these
 * instead of the table's entries for glDrawArrays, glUseProgram, glBindFramebuffer, glUniform*,
 * glTexImage2D, glTexSubImage2D, glGetTexImage (into host memory or a pixel pack buffer), glMapBuffer of
 * a read-back buffer, glFinish and the GL_QUERY_RESULT reads of glGetQueryObjectuiv and
 * glGetQueryObjectui64v.
 * Bytes are the texel data a call hands over or takes: width x height x bytes per texel of the
 * format and type given, whatever the row stride in host memory. */
#include "internal.h"

/* The fields of macs_work, once, for the difference. */
#define MACS_WORK_FIELDS(X) \
    X(draws) X(program_binds) X(framebuffer_binds) X(uniform_calls) X(upload_bytes) X(vertex_bytes) X(readback_bytes) \
    X(syncs) X(programs_compiled) X(timer_results)

/* Bytes per texel of the GL_RGBA data MACS exchanges (it never uses another client format). */
static uint64_t texel_bytes(GLenum format, GLenum type)
{
    uint64_t components = format == GL_RGBA ? 4 : 1;
    return components * (type == GL_FLOAT ? 4u : 1u);
}

static uint64_t image_bytes(GLsizei width, GLsizei height, GLenum format, GLenum type)
{
    if (width <= 0 || height <= 0)
        return 0;
    return (uint64_t)width * (uint64_t)height * texel_bytes(format, type);
}

void macsi_draw_triangle(macs_context *ctx)
{
    ctx->work.draws++;
    ctx->gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

void macsi_draw_triangles(macs_context *ctx, GLint first, GLsizei count)
{
    ctx->work.draws++;
    ctx->gl.DrawArrays(GL_TRIANGLES, first, count);
}

void macsi_buffer_data(macs_context *ctx, GLintptr offset, GLsizeiptr bytes, const void *data, bool create)
{
    if (data)
        ctx->work.vertex_bytes += (uint64_t)bytes;
    if (create)
        ctx->gl.BufferData(GL_ARRAY_BUFFER, bytes, data, GL_STATIC_DRAW);
    else
        ctx->gl.BufferSubData(GL_ARRAY_BUFFER, offset, bytes, data);
}

void macsi_use_program(macs_context *ctx, GLuint program)
{
    ctx->work.program_binds++;
    ctx->gl.UseProgram(program);
}

void macsi_bind_framebuffer(macs_context *ctx, GLuint framebuffer)
{
    ctx->work.framebuffer_binds++;
    ctx->gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

void macsi_uniform(macs_context *ctx, macs_uniform_type type, GLint location, GLsizei count, const void *value)
{
    const macs_gl *gl = &ctx->gl;
    const GLfloat *f = value;
    const GLint *iv = value;
    ctx->work.uniform_calls++;
    switch (type) {
    case MACS_UNIFORM_FLOAT: gl->Uniform1fv(location, count, f); break;
    case MACS_UNIFORM_VEC2: gl->Uniform2fv(location, count, f); break;
    case MACS_UNIFORM_VEC3: gl->Uniform3fv(location, count, f); break;
    case MACS_UNIFORM_VEC4: gl->Uniform4fv(location, count, f); break;
    case MACS_UNIFORM_INT:
    case MACS_UNIFORM_BOOL: gl->Uniform1iv(location, count, iv); break;
    case MACS_UNIFORM_MAT3: gl->UniformMatrix3fv(location, count, GL_FALSE, f); break;
    case MACS_UNIFORM_MAT4: gl->UniformMatrix4fv(location, count, GL_FALSE, f); break;
    }
}

void macsi_tex_image(macs_context *ctx, GLint internal_format, GLsizei width, GLsizei height, GLenum format,
                     GLenum type, const void *pixels)
{
    if (pixels)
        ctx->work.upload_bytes += image_bytes(width, height, format, type);
    ctx->gl.TexImage2D(GL_TEXTURE_2D, 0, internal_format, width, height, 0, format, type, pixels);
}

void macsi_tex_sub_image(macs_context *ctx, const int region[4], GLenum format, GLenum type, const void *pixels)
{
    ctx->work.upload_bytes += image_bytes(region[2], region[3], format, type);
    ctx->gl.TexSubImage2D(GL_TEXTURE_2D, 0, region[0], region[1], region[2], region[3], format, type, pixels);
}

void macsi_get_tex_image(macs_context *ctx, GLsizei width, GLsizei height, GLenum format, GLenum type, void *pixels)
{
    /* The host cannot have the texels before the GPU has written them: a read waits. */
    ctx->work.syncs++;
    ctx->work.readback_bytes += image_bytes(width, height, format, type);
    ctx->gl.GetTexImage(GL_TEXTURE_2D, 0, format, type, pixels);
}

void macsi_get_tex_image_queued(macs_context *ctx, GLsizei width, GLsizei height, GLenum format, GLenum type)
{
    /* Into the bound pixel pack buffer: GL queues the copy behind the work that writes the texture and
     * returns, so the bytes move but the host does not wait here; macsi_map_pack_buffer does. */
    ctx->work.readback_bytes += image_bytes(width, height, format, type);
    ctx->gl.GetTexImage(GL_TEXTURE_2D, 0, format, type, NULL);
}

void *macsi_map_pack_buffer(macs_context *ctx)
{
    /* The host sees the buffer only once the queued copy into it is done: a map may wait. */
    ctx->work.syncs++;
    return ctx->gl.MapBuffer(GL_PIXEL_PACK_BUFFER, GL_READ_ONLY);
}

void macsi_finish(macs_context *ctx)
{
    ctx->work.syncs++;
    ctx->gl.Finish();
}

void macsi_query_result(macs_context *ctx, GLuint query, GLuint *value)
{
    /* GL_QUERY_RESULT (not GL_QUERY_RESULT_AVAILABLE) waits until the query's commands are done. */
    ctx->work.syncs++;
    ctx->gl.GetQueryObjectuiv(query, GL_QUERY_RESULT, value);
}

void macsi_timer_result(macs_context *ctx, GLuint query, GLuint64 *nanoseconds)
{
    /* The same wait as above; a timer read after the frame's read-back finds its result ready. */
    ctx->work.syncs++;
    ctx->work.timer_results++;
    ctx->query_result64(query, GL_QUERY_RESULT, nanoseconds);
}

void macs_context_get_work(const macs_context *ctx, macs_work *work)
{
    if (!work)
        return;
    if (!ctx) {
        *work = (macs_work){0};
        return;
    }
    *work = ctx->work;
    work->programs_compiled = ctx->programs_compiled;
}

macs_work macs_work_since(const macs_work *after, const macs_work *before)
{
    macs_work d = {0};
    if (!after || !before)
        return d;
#define MACS_WORK_SUB_(field) d.field = after->field - before->field;
    MACS_WORK_FIELDS(MACS_WORK_SUB_)
#undef MACS_WORK_SUB_
    return d;
}
