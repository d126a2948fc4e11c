/* Render passes: chunk programs and framebuffers, and the inputs, outputs and uniforms that change
 * between runs (pass_validate.c refuses a bad description first). */
#include <stdio.h>
#include <string.h>

#include "internal.h"

static void free_pass(macs_pass *p)
{
    macs_context *ctx = p->ctx;
    const macs_allocator *a = &ctx->allocator;
    for (int c = 0; p->chunks && c < p->chunk_count; c++) {
        macsi_program_release(ctx, p->chunks[c].program);
        if (p->chunks[c].fbo)
            ctx->gl.DeleteFramebuffers(1, &p->chunks[c].fbo);
        macsi_free(a, p->chunks[c].uniform_locations);
    }
    macsi_free(a, p->chunks);
    macsi_query_destroy(p);
    for (int i = 0; p->input_names && i < p->input_count; i++)
        macsi_free(a, p->input_names[i]);
    for (int i = 0; p->output_names && i < p->output_count; i++)
        macsi_free(a, p->output_names[i]);
    for (int i = 0; p->uniforms && i < p->uniform_count; i++) {
        macsi_free(a, p->uniforms[i].name);
        macsi_free(a, p->uniforms[i].value);
    }
    macsi_free(a, p->input_names);
    macsi_free(a, p->output_names);
    macsi_free(a, p->inputs);
    macsi_free(a, p->outputs);
    macsi_free(a, p->uniforms);
    macsi_free(a, p);
}

static macs_status copy_desc(macs_pass *p, const macs_pass_desc *d)
{
    const macs_allocator *a = &p->ctx->allocator;
    p->input_count = d->input_count;
    p->output_count = d->output_count;
    p->uniform_count = d->uniform_count;
    p->input_names = macsi_calloc(a, (size_t)d->input_count, sizeof *p->input_names);
    p->inputs = macsi_calloc(a, (size_t)d->input_count, sizeof *p->inputs);
    p->output_names = macsi_calloc(a, (size_t)d->output_count, sizeof *p->output_names);
    p->outputs = macsi_calloc(a, (size_t)d->output_count, sizeof *p->outputs);
    p->uniforms = macsi_calloc(a, (size_t)d->uniform_count, sizeof *p->uniforms);
    if (!p->input_names || !p->inputs || !p->output_names || !p->outputs || !p->uniforms)
        return MACS_ERR_OUT_OF_MEMORY;
    for (int i = 0; i < d->input_count; i++) {
        if (!(p->input_names[i] = macsi_strdup(a, d->inputs[i].name)))
            return MACS_ERR_OUT_OF_MEMORY;
        p->inputs[i] = d->input_textures ? d->input_textures[i] : NULL;
    }
    for (int i = 0; i < d->output_count; i++) {
        if (!(p->output_names[i] = macsi_strdup(a, d->outputs[i].name)))
            return MACS_ERR_OUT_OF_MEMORY;
        p->outputs[i] = d->output_textures[i];
    }
    for (int i = 0; i < d->uniform_count; i++) {
        macs_pass_uniform *u = &p->uniforms[i];
        u->type = d->uniforms[i].type;
        u->count = d->uniforms[i].count;
        u->size = macsi_uniform_value_size(u->type, u->count);
        u->name = macsi_strdup(a, d->uniforms[i].name);
        u->value = macsi_calloc(a, 1, u->size); /* unset uniforms read as zero, like fresh GL uniforms */
        if (!u->name || !u->value)
            return MACS_ERR_OUT_OF_MEMORY;
    }
    return MACS_OK;
}

/* A geometry pass's attribute layout, and its refusal to split: its vertices would be drawn once
 * per chunk, and its depth writes would then meet their own earlier values. */
static macs_status geometry_layout(macs_pass *p, const macs_pass_desc *d, int per_chunk)
{
    p->geometry = true;
    p->attribute_count = d->attribute_count;
    for (int i = 0; i < d->attribute_count; i++) {
        p->attribute_sizes[i] = d->attributes[i].size;
        p->attribute_floats += d->attributes[i].size;
    }
    if (d->output_count > per_chunk)
        return macsi_fail(p->ctx, MACS_ERR_LIMIT, "macs_pass_create: desc.output_count %d: a geometry pass cannot be "
                         "split, and this context writes at most %d outputs in one program", d->output_count, per_chunk);
    return MACS_OK;
}

static macs_status build_chunks(macs_pass *p, const macs_pass_desc *d)
{
    macs_context *ctx = p->ctx;
    const macs_allocator *a = &ctx->allocator;
    int per_chunk = macsi_outputs_per_chunk(ctx);
    char *vertex = NULL;
    const char *attribute_names[16];
    if (d->vertex_main) {
        macs_status st = geometry_layout(p, d, per_chunk);
        if (st != MACS_OK)
            return st;
        for (int i = 0; i < d->attribute_count; i++)
            attribute_names[i] = d->attributes[i].name;
        if (!(vertex = macsi_pass_vertex_source(a, d)))
            return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "building the vertex source of a geometry pass");
    }
    p->chunk_count = (d->output_count + per_chunk - 1) / per_chunk;
    p->chunks = macsi_calloc(a, (size_t)p->chunk_count, sizeof *p->chunks);
    if (!p->chunks) {
        p->chunk_count = 0;
        macsi_free(a, vertex);
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "allocating pass chunks");
    }
    for (int c = 0; c < p->chunk_count; c++) {
        macs_chunk *ch = &p->chunks[c];
        ch->first_output = c * per_chunk;
        ch->output_count = d->output_count - ch->first_output < per_chunk ? d->output_count - ch->first_output
                                                                          : per_chunk;
        ch->uniform_locations = macsi_calloc(a, (size_t)p->uniform_count, sizeof *ch->uniform_locations);
        char *source = macsi_pass_source(a, d, ch->first_output, ch->output_count);
        if (!ch->uniform_locations || !source) {
            macsi_free(a, source);
            macsi_free(a, vertex);
            return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "building the shader source of a pass");
        }
        macs_status st = macsi_program_acquire(ctx, vertex, source, p->input_count, p->input_names,
                                               d->attribute_count, attribute_names, &ch->program);
        macsi_free(a, source);
        if (st != MACS_OK) {
            macsi_free(a, vertex);
            return st;
        }
        for (int i = 0; i < p->uniform_count; i++)
            ch->uniform_locations[i] = ctx->gl.GetUniformLocation(ch->program->id, p->uniforms[i].name);
        if (p->geometry)
            p->inverse_size_location = ctx->gl.GetUniformLocation(ch->program->id, "macs_inverse_size");
        ctx->gl.GenFramebuffers(1, &ch->fbo);
    }
    macsi_free(a, vertex);
    return macsi_gl_check(ctx, "building pass chunks");
}

macs_status macs_pass_create(macs_context *ctx, const macs_pass_desc *desc, macs_pass **out)
{
    if (out)
        *out = NULL;
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!desc || !out)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: %s is NULL",
                         desc ? "out" : "desc");
    macs_status st = macsi_pass_validate(ctx, desc);
    if (st != MACS_OK)
        return st;
    int per_chunk = macsi_outputs_per_chunk(ctx);
    st = macsi_split_check_state(ctx, &desc->stencil, (desc->output_count + per_chunk - 1) / per_chunk);
    if (st == MACS_OK)
        st = macsi_gl_current(ctx, "macs_pass_create");
    if (st != MACS_OK)
        return st;
    macsi_gl_drain(ctx);
    macs_pass *p = macsi_calloc(&ctx->allocator, 1, sizeof *p);
    if (!p)
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "allocating a pass");
    p->ctx = ctx;
    p->width = desc->output_textures[0]->width;
    p->height = desc->output_textures[0]->height;
    p->depth_stencil = desc->depth_stencil;
    p->depth = desc->depth;
    p->stencil = desc->stencil;
    p->blend = desc->blend;
    p->color_mask = desc->color_mask;
    p->attachments_dirty = true;
    st = copy_desc(p, desc);
    if (st != MACS_OK) {
        free_pass(p);
        return macsi_fail(ctx, st, "copying the pass description");
    }
    st = build_chunks(p, desc);
    if (st != MACS_OK) {
        free_pass(p);
        return st;
    }
    MACS_LIST_PUSH(ctx->passes, p);
    *out = p;
    return MACS_OK;
}

void macs_pass_destroy(macs_pass *pass)
{
    if (!pass)
        return;
    MACS_LIST_REMOVE(pass->ctx->passes, pass);
    free_pass(pass);
}

int macs_pass_chunk_count(const macs_pass *pass)
{
    return pass ? pass->chunk_count : 0;
}

macs_status macs_pass_set_input(macs_pass *pass, int index, macs_texture *texture)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    if (index < 0 || index >= pass->input_count)
        return macsi_fail(pass->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_input: index %d outside 0..%d", index,
                         pass->input_count - 1);
    if (texture && texture->ctx != pass->ctx)
        return macsi_fail(pass->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_input: texture of another context");
    for (int i = 0; texture && i < pass->output_count; i++)
        if (pass->outputs[i] == texture)
            return macsi_fail(pass->ctx, MACS_ERR_INVALID_ARGUMENT,
                             "macs_pass_set_input: input %d (%s) would also be output %d", index,
                             pass->input_names[index], i);
    char where[160];
    snprintf(where, sizeof where, "macs_pass_set_input: input %d \"%.64s\"", index, pass->input_names[index]);
    macs_status st = macsi_check_filterable(pass->ctx, texture, where);
    if (st != MACS_OK)
        return st;
    pass->inputs[index] = texture;
    return MACS_OK;
}

macs_status macs_pass_set_output(macs_pass *pass, int index, macs_texture *texture)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = pass->ctx;
    if (index < 0 || index >= pass->output_count)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_output: index %d outside 0..%d", index,
                         pass->output_count - 1);
    if (!texture || texture->ctx != ctx)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_output: no texture of this context");
    if (texture->width != pass->width || texture->height != pass->height)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_output: texture is %dx%d, the pass is %dx%d",
                         texture->width, texture->height, pass->width, pass->height);
    for (int i = 0; i < pass->output_count; i++)
        if (i != index && pass->outputs[i] == texture)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_output: texture is already output %d", i);
    for (int i = 0; i < pass->input_count; i++)
        if (pass->inputs[i] == texture)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_output: texture is input %d (%s)", i,
                             pass->input_names[i]);
    char where[160];
    snprintf(where, sizeof where, "macs_pass_set_output: output %d \"%.64s\"", index, pass->output_names[index]);
    macs_status st = macsi_check_blendable(ctx, texture, pass->blend, where);
    if (st != MACS_OK)
        return st;
    if (pass->outputs[index] != texture) {
        pass->outputs[index] = texture;
        pass->attachments_dirty = true;
    }
    return MACS_OK;
}

macs_status macs_pass_set_depth_stencil(macs_pass *pass, macs_depth_stencil *ds)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    macs_context *ctx = pass->ctx;
    if (ds && (ds->ctx != ctx || ds->internal))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_depth_stencil: object of another context");
    if (ds && (ds->width != pass->width || ds->height != pass->height))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_depth_stencil: it is %dx%d, the pass %dx%d",
                         ds->width, ds->height, pass->width, pass->height);
    if (!ds && (pass->depth.test || pass->stencil.test))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_pass_set_depth_stencil: the pass tests depth or stencil and needs one");
    pass->depth_stencil = ds;
    pass->attachments_dirty = true;
    return MACS_OK;
}

macs_status macs_pass_set_uniform(macs_pass *pass, const char *name, const void *value)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!name || !value)
        return macsi_fail(pass->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_uniform: name and value are required");
    for (int i = 0; i < pass->uniform_count; i++)
        if (strcmp(pass->uniforms[i].name, name) == 0) {
            memcpy(pass->uniforms[i].value, value, pass->uniforms[i].size);
            return MACS_OK;
        }
    return macsi_fail(pass->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_set_uniform: the pass has no uniform \"%s\"",
                     name);
}

/* Takes output i's texture off its chunk's framebuffer. GL detaches a deleted texture from the bound
 * framebuffer only; elsewhere the attachment keeps the texture's storage alive, and a wrapped texture
 * is never deleted by MACS at all but must stop being drawn into once forgotten. */
static void detach_output(macs_pass *p, int i)
{
    const macs_gl *gl = &p->ctx->gl;
    for (int c = 0; c < p->chunk_count; c++) {
        const macs_chunk *ch = &p->chunks[c];
        if (!ch->fbo || i < ch->first_output || i >= ch->first_output + ch->output_count)
            continue;
        macsi_bind_framebuffer(p->ctx, ch->fbo);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)(i - ch->first_output), GL_TEXTURE_2D,
                                 0, 0);
        macsi_bind_framebuffer(p->ctx, 0);
    }
}

void macsi_pass_forget_texture(macs_context *ctx, const macs_texture *texture)
{
    for (macs_pass *p = ctx->passes; p; p = p->next) {
        for (int i = 0; i < p->input_count; i++)
            if (p->inputs[i] == texture)
                p->inputs[i] = NULL;
        for (int i = 0; i < p->output_count; i++)
            if (p->outputs[i] == texture) {
                p->outputs[i] = NULL;
                p->attachments_dirty = true;
                detach_output(p, i);
            }
    }
}

void macsi_pass_forget_depth_stencil(macs_context *ctx, const macs_depth_stencil *ds)
{
    for (macs_pass *p = ctx->passes; p; p = p->next) {
        if (p->depth_stencil == ds)
            p->depth_stencil = NULL;
        if (p->attached_ds == ds) {
            p->attached_ds = NULL;
            p->attachments_dirty = true;
        }
    }
}
