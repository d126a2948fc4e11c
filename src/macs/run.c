/* Running a pass: framebuffer attachments, GL state, uniforms, one full-screen triangle per chunk. */
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
    default: gl->Disable(GL_BLEND); break;
    }
    unsigned m = p->color_mask == 0 ? 15u : (p->color_mask & MACS_COLOR_MASK_NONE) ? 0u : p->color_mask;
    gl->ColorMask((m & 1) != 0, (m & 2) != 0, (m & 4) != 0, (m & 8) != 0);
    /* Fixed-function state a shared caller context may have left on, which would alter results. */
    gl->Disable(GL_ALPHA_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->Disable(GL_DITHER);
    gl->Disable(GL_COLOR_LOGIC_OP);
    gl->BindBuffer(GL_ARRAY_BUFFER, p->ctx->vertex_buffer);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, 0);
    gl->EnableVertexAttribArray(0);
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

macs_status macs_pass_run(macs_pass *pass, const macs_run_desc *run)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    static const macs_run_desc defaults = {0};
    if (!run)
        run = &defaults;
    macs_context *ctx = pass->ctx;
    const macs_gl *gl = &ctx->gl;
    macs_status st = validate_run(pass, run);
    if (st == MACS_OK)
        st = macsi_gl_current(ctx, "macs_pass_run");
    if (st != MACS_OK)
        return st;
    macsi_gl_drain(ctx);
    /* A split pass needs a stencil for its marks even when the caller brought no depth/stencil. */
    macs_depth_stencil *ds = pass->depth_stencil;
    if (!ds && pass->chunk_count > 1) {
        st = macsi_depth_stencil_internal(ctx, pass->width, pass->height, &ds);
        if (st != MACS_OK)
            return st;
    }
    if (pass->attachments_dirty || pass->attached_ds != ds) {
        st = attach(pass, ds);
        if (st != MACS_OK)
            return st;
    }
    apply_common_state(pass, run);
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
    /* Leave the caller's default framebuffer and no program bound, as a caller sharing the context
     * would expect. */
    macsi_use_program(ctx, 0);
    macsi_bind_framebuffer(ctx, 0);
    gl->BindBuffer(GL_ARRAY_BUFFER, 0);
    return macsi_gl_check(ctx, "macs_pass_run");
}
