/* Running a pass: framebuffer attachments, GL state, uniforms, then one full-screen triangle per chunk
 * (macs_pass_run) or a geometry's triangles (macs_pass_draw, geometry passes). */
#include "internal.h"

/* Attaches outputs and the depth/stencil object to every chunk's framebuffer and checks completeness. */
static macs_status attach(macs_pass *p, macs_depth_stencil *ds)
{
    macs_context *ctx = p->ctx;
    const macs_gl *gl = &ctx->gl;
    macs_status st = MACS_OK;
    for (int c = 0; c < p->chunk_count && st == MACS_OK; c++) {
        const macs_chunk *ch = &p->chunks[c];
        macsi_bind_framebuffer(ctx, ch->fbo);
        for (int j = 0; j < ch->output_count; j++)
            gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)j, GL_TEXTURE_2D,
                                     p->outputs[ch->first_output + j]->id, 0);
        macsi_fbo_attach_depth_stencil(ctx, ds);
        GLenum buffers[64];
        for (int j = 0; j < ch->output_count; j++)
            buffers[j] = GL_COLOR_ATTACHMENT0 + (GLenum)j;
        gl->DrawBuffers(ch->output_count, buffers);
        gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
        st = macsi_fbo_check(ctx, "attaching pass outputs");
    }
    macsi_bind_framebuffer(ctx, 0);
    if (st == MACS_OK) {
        p->attached_ds = ds;
        p->attachments_dirty = false;
    }
    return st;
}

static void apply_uniforms(const macs_pass *p, const macs_chunk *ch)
{
    for (int i = 0; i < p->uniform_count; i++) {
        const macs_pass_uniform *u = &p->uniforms[i];
        GLint loc = ch->uniform_locations[i];
        if (loc < 0)
            continue; /* unused by this chunk's code, so the compiler removed it */
        macsi_uniform(p->ctx, u->type, loc, u->count > 0 ? u->count : 1, u->value);
    }
}

static void apply_common_state(const macs_pass *p, const macs_run_desc *run)
{
    const macs_gl *gl = &p->ctx->gl;
    gl->Viewport(0, 0, p->width, p->height);
    if (run->scissor) {
        gl->Enable(GL_SCISSOR_TEST);
        gl->Scissor(run->scissor_x, run->scissor_y, run->scissor_width, run->scissor_height);
    } else {
        gl->Disable(GL_SCISSOR_TEST);
    }
    switch (p->blend) {
    case MACS_BLEND_ADD: gl->Enable(GL_BLEND); gl->BlendFunc(GL_ONE, GL_ONE); break;
    case MACS_BLEND_MULTIPLY: gl->Enable(GL_BLEND); gl->BlendFunc(GL_DST_COLOR, GL_ZERO); break;
    case MACS_BLEND_MAX: gl->Enable(GL_BLEND); gl->BlendFunc(GL_ONE, GL_ONE); break;
    default: gl->Disable(GL_BLEND); break;
    }
    gl->BlendEquation(p->blend == MACS_BLEND_MAX ? GL_MAX : GL_FUNC_ADD);
    unsigned m = p->color_mask == 0 ? 15u : (p->color_mask & MACS_COLOR_MASK_NONE) ? 0u : p->color_mask;
    gl->ColorMask((m & 1) != 0, (m & 2) != 0, (m & 4) != 0, (m & 8) != 0);
    /* Fixed-function state a shared caller context may have left on, which would alter results. */
    gl->Disable(GL_ALPHA_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->Disable(GL_DITHER);
    gl->Disable(GL_COLOR_LOGIC_OP);
    for (int i = 0; i < p->input_count; i++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)i);
        gl->BindTexture(GL_TEXTURE_2D, p->inputs[i]->id);
    }
    gl->ActiveTexture(GL_TEXTURE0);
}

static macs_status validate_run(macs_pass *p, const macs_run_desc *run)
{
    macs_context *ctx = p->ctx;
    for (int i = 0; i < p->output_count; i++)
        if (!p->outputs[i])
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_run: output %d (%s) has no texture", i,
                             p->output_names[i]);
    for (int i = 0; i < p->input_count; i++)
        if (!p->inputs[i])
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_run: input %d (%s) has no texture", i,
                             p->input_names[i]);
    if ((p->depth.test || p->stencil.test) && !p->depth_stencil)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_run: the depth/stencil object is gone");
    if (run->scissor && (run->scissor_width < 0 || run->scissor_height < 0))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_run: negative scissor size %dx%d",
                         run->scissor_width, run->scissor_height);
    return MACS_OK;
}

/* The framebuffers' attachments as the pass needs them now (a split pass needs a stencil for its marks
 * even when the caller brought no depth/stencil); *ds gets what is attached. */
static macs_status prepare_attachments(macs_pass *pass, macs_depth_stencil **ds_out)
{
    macs_depth_stencil *ds = pass->depth_stencil;
    macs_status st = MACS_OK;
    if (!ds && pass->chunk_count > 1)
        st = macsi_depth_stencil_internal(pass->ctx, pass->width, pass->height, &ds);
    if (st == MACS_OK && (pass->attachments_dirty || pass->attached_ds != ds))
        st = attach(pass, ds);
    *ds_out = ds;
    return st;
}

/* Leave the caller's default framebuffer and no program bound, as a caller sharing the context would
 * expect. */
static macs_status end_run(macs_context *ctx, const char *where)
{
    macsi_use_program(ctx, 0);
    macsi_bind_framebuffer(ctx, 0);
    ctx->gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    return macsi_gl_check(ctx, where);
}

/* What a run or a draw of a validated pass starts with: its GL context current, earlier GL errors
 * drained (they are not this call's), the outputs and depth/stencil attached (*ds the one bound). */
static macs_status begin(macs_pass *pass, const char *what, macs_depth_stencil **ds)
{
    macs_status st = macsi_gl_current(pass->ctx, what);
    if (st != MACS_OK)
        return st;
    macsi_gl_drain(pass->ctx);
    return prepare_attachments(pass, ds);
}

macs_status macs_pass_run(macs_pass *pass, const macs_run_desc *run)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    static const macs_run_desc defaults = {0};
    if (!run)
        run = &defaults;
    macs_context *ctx = pass->ctx;
    const macs_gl *gl = &ctx->gl;
    if (pass->geometry)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_run: the pass is a geometry pass (it has a "
                         "vertex_main): draw it with macs_pass_draw");
    macs_depth_stencil *ds = NULL;
    macs_status st = validate_run(pass, run);
    if (st == MACS_OK)
        st = begin(pass, "macs_pass_run", &ds);
    if (st != MACS_OK)
        return st;
    apply_common_state(pass, run);
    gl->BindBuffer(GL_ARRAY_BUFFER, ctx->vertex_buffer);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
    gl->EnableVertexAttribArray(0);
    for (int c = 0; c < pass->chunk_count; c++) {
        const macs_chunk *ch = &pass->chunks[c];
        macsi_bind_framebuffer(ctx, ch->fbo);
        macsi_use_program(ctx, ch->program->id);
        apply_uniforms(pass, ch);
        macsi_split_apply_state(pass, c, pass->depth_stencil != NULL, ds != NULL);
        if (c == 0 && run->occlusion_query)
            macsi_query_begin(pass);
        macsi_draw_triangle(ctx);
        if (c == 0 && run->occlusion_query)
            macsi_query_end(pass);
    }
    return end_run(ctx, "macs_pass_run");
}

/* A draw's arguments against its pass and geometry, one fault at a time. */
static macs_status validate_draw(macs_pass *p, const macs_draw_desc *d, int *count)
{
    macs_context *ctx = p->ctx;
    if (!p->geometry)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: the pass has no vertex_main: run it with "
                         "macs_pass_run");
    const macs_geometry *g = d->geometry;
    if (!g)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw.geometry is NULL");
    if (g->ctx != ctx)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw.geometry belongs to another context");
    if (g->floats_per_vertex != p->attribute_floats)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw.geometry has %d floats per vertex but "
                         "the pass's attributes take %d", g->floats_per_vertex, p->attribute_floats);
    if (d->first < 0 || d->first > g->vertex_count)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw.first %d is outside 0 .. %d (the "
                         "geometry's vertices)", d->first, g->vertex_count);
    *count = d->vertex_count ? d->vertex_count : g->vertex_count - d->first;
    if (d->vertex_count < 0 || *count > g->vertex_count - d->first)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw.vertex_count %d from vertex %d "
                         "exceeds the geometry's %d vertices", d->vertex_count, d->first, g->vertex_count);
    if (*count % 3)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: %d vertices are not whole triangles "
                         "(a multiple of 3)", *count);
    if ((unsigned)d->fill > (unsigned)MACS_FILL_CORNERS)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw.fill %d is not a macs_fill (0 .. %d)",
                         (int)d->fill, (int)MACS_FILL_CORNERS);
    float most = d->fill == MACS_FILL_EDGES ? ctx->features.max_line_width : ctx->features.max_point_size;
    if (!(d->size >= 0.0f) || (d->fill != MACS_FILL_SOLID && d->size > most))
        return macsi_fail(ctx, MACS_ERR_LIMIT, "macs_pass_draw: draw.size %g is outside 0 .. %g (macs_features.%s)",
                         (double)d->size, (double)most, d->fill == MACS_FILL_EDGES ? "max_line_width" : "max_point_size");
    macs_run_desc run = {d->scissor, d->scissor_x, d->scissor_y, d->scissor_width, d->scissor_height, false};
    return validate_run(p, &run);
}

/* The geometry's floats as the pass's attributes, packed in declaration order. */
static void bind_attributes(const macs_pass *p, const macs_geometry *g)
{
    const macs_gl *gl = &p->ctx->gl;
    gl->BindBuffer(GL_ARRAY_BUFFER, g->buffer);
    GLsizei stride = (GLsizei)(sizeof(float) * (size_t)g->floats_per_vertex);
    size_t offset = 0;
    for (int i = 0; i < p->attribute_count; i++) {
        gl->VertexAttribPointer((GLuint)i, p->attribute_sizes[i], GL_FLOAT, GL_FALSE, stride,
                                (const void *)(offset * sizeof(float)));
        gl->EnableVertexAttribArray((GLuint)i);
        offset += (size_t)p->attribute_sizes[i];
    }
}

static void unbind_attributes(const macs_pass *p)
{
    for (int i = 1; i < p->attribute_count; i++)
        p->ctx->gl.DisableVertexAttribArray((GLuint)i);
}

macs_status macs_pass_draw(macs_pass *pass, const macs_draw_desc *draw)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = pass->ctx;
    const macs_gl *gl = &ctx->gl;
    if (!draw)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw: draw is NULL");
    int count = 0;
    macs_depth_stencil *ds = NULL;
    macs_status st = validate_draw(pass, draw, &count);
    if (st == MACS_OK)
        st = begin(pass, "macs_pass_draw", &ds);
    if (st != MACS_OK)
        return st;
    macs_run_desc run = {draw->scissor, draw->scissor_x, draw->scissor_y, draw->scissor_width, draw->scissor_height,
                         false};
    apply_common_state(pass, &run);
    bind_attributes(pass, draw->geometry);
    static const GLenum modes[] = {GL_FILL, GL_LINE, GL_POINT};
    gl->PolygonMode(GL_FRONT_AND_BACK, modes[draw->fill]);
    float size = draw->size > 0.0f ? draw->size : 1.0f;
    if (draw->fill == MACS_FILL_EDGES)
        gl->LineWidth(size);
    else if (draw->fill == MACS_FILL_CORNERS)
        gl->PointSize(size);
    const macs_chunk *ch = &pass->chunks[0];
    macsi_bind_framebuffer(ctx, ch->fbo);
    macsi_use_program(ctx, ch->program->id);
    apply_uniforms(pass, ch);
    if (pass->inverse_size_location >= 0) {
        float inverse[2] = {1.0f / (float)pass->width, 1.0f / (float)pass->height};
        macsi_uniform(ctx, MACS_UNIFORM_VEC2, pass->inverse_size_location, 1, inverse);
    }
    macsi_split_apply_state(pass, 0, pass->depth_stencil != NULL, ds != NULL);
    if (count > 0)
        macsi_draw_triangles(ctx, draw->first, count);
    /* Back to the state a full-screen pass and a caller expect. */
    gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    unbind_attributes(pass);
    return end_run(ctx, "macs_pass_draw");
}
