/* Refusing a pass description before anything is built. Every message names the argument (output 1
 * "o__x", desc.blend, uniform 0 "k"), its bad value where it has one, and the rule it breaks, one
 * fault at a time, so that the caller can fix the call from the message alone. */
#include <stdio.h>
#include <string.h>

#include "internal.h"

/* Longer names are refused: GLSL 1.10 sets no bound, but drivers of its age do. */
enum { MAX_NAME_LENGTH = 128 };

static bool is_letter_or_underscore(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

/* Why a caller's name cannot stand in the generated shader, or NULL when it can. The reserved names
 * come first: "macs_uv" is a fine identifier, but one the generated code already declares. */
static const char *name_fault(const char *s)
{
    if (!*s)
        return "is empty";
    if (strncmp(s, "gl_", 3) == 0)
        return "starts with the reserved prefix \"gl_\", which belongs to GL";
    if (strncmp(s, "macs_", 5) == 0)
        return "starts with the reserved prefix \"macs_\", which belongs to the generated code";
    if (strstr(s, "__"))
        return "holds a double underscore \"__\", which GLSL reserves";
    if (!is_letter_or_underscore(s[0]))
        return "does not start with a letter or underscore";
    for (const char *p = s; *p; p++)
        if (!is_letter_or_underscore(*p) && !(*p >= '0' && *p <= '9'))
            return "is not an identifier: only letter, digit or underscore characters may follow the first";
    if (strlen(s) > MAX_NAME_LENGTH)
        return "is longer than 128 characters";
    return NULL;
}

/* Inputs and uniforms share the shader's one namespace: a name may be used once among them. */
static macs_status check_unique(macs_context *ctx, const macs_pass_desc *d, const char *kind, int index,
                                const char *name, int inputs_before, int uniforms_before)
{
    for (int i = 0; i < inputs_before; i++)
        if (strcmp(d->inputs[i].name, name) == 0)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: %s %d \"%s\": the name is "
                             "already used by input %d", kind, index, name, i);
    for (int i = 0; i < uniforms_before; i++)
        if (strcmp(d->uniforms[i].name, name) == 0)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: %s %d \"%s\": the name is "
                             "already used by uniform %d", kind, index, name, i);
    return MACS_OK;
}

/* kind and index say which argument holds the name ("uniform", 0). */
static macs_status check_name(macs_context *ctx, const char *kind, int index, const char *name)
{
    if (!name)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: %s %d name is NULL", kind, index);
    const char *fault = name_fault(name);
    if (fault)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: %s %d \"%s\": the name %s", kind,
                         index, name, fault);
    return MACS_OK;
}

/* A count and its array come together. */
static macs_status check_counts(macs_context *ctx, const macs_pass_desc *d)
{
    if (d->output_count < 1)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.output_count %d: at least one "
                         "output is required", d->output_count);
    if (!d->outputs || !d->output_textures)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.output_count %d but desc.%s is "
                         "NULL", d->output_count, d->outputs ? "output_textures" : "outputs");
    if (d->input_count < 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.input_count %d is negative",
                         d->input_count);
    if (d->input_count > 0 && !d->inputs)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.input_count %d but desc.inputs "
                         "is NULL", d->input_count);
    if (d->uniform_count < 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.uniform_count %d is negative",
                         d->uniform_count);
    if (d->uniform_count > 0 && !d->uniforms)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.uniform_count %d but "
                         "desc.uniforms is NULL", d->uniform_count);
    return MACS_OK;
}

/* Each output: a name, a value, a texture of this context, one size for all, no texture twice. */
static macs_status check_outputs(macs_context *ctx, const macs_pass_desc *d)
{
    const macs_texture *first = d->output_textures[0];
    for (int i = 0; i < d->output_count; i++) {
        const macs_output_desc *o = &d->outputs[i];
        const macs_texture *t = d->output_textures[i];
        macs_status st = check_name(ctx, "output", i, o->name);
        if (st != MACS_OK)
            return st;
        if (!o->value)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: output %d \"%s\": value is NULL, "
                             "a vec4 expression is required", i, o->name);
        if (!t)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: output %d \"%s\": "
                             "desc.output_textures[%d] is NULL", i, o->name, i);
        if (t->ctx != ctx)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: output %d \"%s\": its texture "
                             "belongs to another context", i, o->name);
        if (t->width != first->width || t->height != first->height)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: output %d \"%s\" is %dx%d but "
                             "output 0 is %dx%d", i, o->name, t->width, t->height, first->width, first->height);
        for (int j = 0; j < i; j++)
            if (d->output_textures[j] == t)
                return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: outputs %d and %d are the "
                                 "same texture", j, i);
    }
    return MACS_OK;
}

/* Float features GL 2.1 cannot report: an input sampled linearly, or an output blended, in a format
 * the context cannot do that for is refused (float_features.c). */
static macs_status check_float_features(macs_context *ctx, const macs_pass_desc *d)
{
    char where[160];
    for (int i = 0; d->input_textures && i < d->input_count; i++) {
        snprintf(where, sizeof where, "macs_pass_create: input %d \"%.64s\"", i, d->inputs[i].name);
        macs_status st = macsi_check_filterable(ctx, d->input_textures[i], where);
        if (st != MACS_OK)
            return st;
    }
    for (int i = 0; i < d->output_count; i++) {
        snprintf(where, sizeof where, "macs_pass_create: output %d \"%.64s\"", i, d->outputs[i].name);
        macs_status st = macsi_check_blendable(ctx, d->output_textures[i], d->blend, where);
        if (st != MACS_OK)
            return st;
    }
    return MACS_OK;
}

/* Each input: a name of its own, and a texture (if given now) of this context that is no output. */
static macs_status check_inputs(macs_context *ctx, const macs_pass_desc *d)
{
    for (int i = 0; i < d->input_count; i++) {
        const char *name = d->inputs[i].name;
        macs_status st = check_name(ctx, "input", i, name);
        if (st == MACS_OK)
            st = check_unique(ctx, d, "input", i, name, i, 0);
        if (st != MACS_OK)
            return st;
        const macs_texture *t = d->input_textures ? d->input_textures[i] : NULL;
        if (t && t->ctx != ctx)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: input %d \"%s\" is a texture of "
                             "another context", i, name);
        for (int j = 0; t && j < d->output_count; j++)
            if (d->output_textures[j] == t)
                return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: input %d \"%s\" is also "
                                 "output %d", i, name, j);
    }
    return MACS_OK;
}

/* Each uniform: a name no input or earlier uniform has, a known type, a count in range. */
static macs_status check_uniforms(macs_context *ctx, const macs_pass_desc *d)
{
    for (int i = 0; i < d->uniform_count; i++) {
        const macs_uniform_desc *u = &d->uniforms[i];
        macs_status st = check_name(ctx, "uniform", i, u->name);
        if (st == MACS_OK)
            st = check_unique(ctx, d, "uniform", i, u->name, d->input_count, i);
        if (st != MACS_OK)
            return st;
        if (u->type < MACS_UNIFORM_FLOAT || u->type > MACS_UNIFORM_MAT4)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: uniform %d \"%s\": type %d is "
                             "not a macs_uniform_type (%d .. %d)", i, u->name, (int)u->type,
                             (int)MACS_UNIFORM_FLOAT, (int)MACS_UNIFORM_MAT4);
        if (u->count < 0 || u->count > 65536)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: uniform %d \"%s\": count %d is "
                             "outside 0 (one value) .. 65536", i, u->name, u->count);
    }
    return MACS_OK;
}

static macs_status check_depth_stencil(macs_context *ctx, const macs_pass_desc *d)
{
    const macs_depth_stencil *ds = d->depth_stencil;
    const macs_texture *first = d->output_textures[0];
    if (ds && (ds->ctx != ctx || ds->internal))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.depth_stencil belongs to another "
                         "context");
    if (ds && (ds->width != first->width || ds->height != first->height))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.depth_stencil is %dx%d but the "
                         "outputs are %dx%d", ds->width, ds->height, first->width, first->height);
    if ((d->depth.test || d->stencil.test) && !ds)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.%s.test is on but "
                         "desc.depth_stencil is NULL", d->depth.test ? "depth" : "stencil");
    return MACS_OK;
}

/* Every enum field of the fixed-function state, with the last value its type has. */
#define MACS_PASS_STATE_FIELDS(X) \
    X(depth.func, MACS_COMPARE_ALWAYS, "macs_compare") \
    X(stencil.func, MACS_COMPARE_ALWAYS, "macs_compare") \
    X(stencil.fail, MACS_STENCIL_OP_INVERT, "macs_stencil_op") \
    X(stencil.depth_fail, MACS_STENCIL_OP_INVERT, "macs_stencil_op") \
    X(stencil.pass, MACS_STENCIL_OP_INVERT, "macs_stencil_op") \
    X(blend, MACS_BLEND_MAX, "macs_blend")

static macs_status check_state(macs_context *ctx, const macs_pass_desc *d)
{
#define MACS_CHECK_STATE_(field, last, type) \
    if ((unsigned)d->field > (unsigned)(last)) \
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc." #field " %d is not a " type \
                         " (0 .. %d)", (int)d->field, (int)(last));
    MACS_PASS_STATE_FIELDS(MACS_CHECK_STATE_)
#undef MACS_CHECK_STATE_
    if (d->color_mask > 31)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.color_mask %u holds bits other "
                         "than MACS_COLOR_MASK_R, _G, _B, _A and _NONE", d->color_mask);
    return MACS_OK;
}

/* A geometry pass: attributes with names of their own and sizes 1 .. 4; none without vertex_main. */
static macs_status check_geometry(macs_context *ctx, const macs_pass_desc *d)
{
    if (!d->vertex_main) {
        if (d->attribute_count != 0 || d->vertex_functions || d->varyings)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.%s is set but desc.vertex_main "
                             "is NULL (only a geometry pass has a vertex shader)",
                             d->attribute_count ? "attribute_count" : d->vertex_functions ? "vertex_functions" : "varyings");
        return MACS_OK;
    }
    if (d->attribute_count < 1 || d->attribute_count > 16)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.attribute_count %d is outside 1 .. 16 "
                         "(a geometry pass draws vertices, which need an attribute)", d->attribute_count);
    if (!d->attributes)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: desc.attribute_count %d but "
                         "desc.attributes is NULL", d->attribute_count);
    for (int i = 0; i < d->attribute_count; i++) {
        const macs_attribute_desc *a = &d->attributes[i];
        macs_status st = check_name(ctx, "attribute", i, a->name);
        if (st == MACS_OK)
            st = check_unique(ctx, d, "attribute", i, a->name, d->input_count, d->uniform_count);
        if (st != MACS_OK)
            return st;
        for (int j = 0; j < i; j++)
            if (strcmp(d->attributes[j].name, a->name) == 0)
                return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: attribute %d \"%s\": the name is "
                                 "already used by attribute %d", i, a->name, j);
        if (a->size < 1 || a->size > 4)
            return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_create: attribute %d \"%s\": size %d is "
                             "outside 1 .. 4 floats", i, a->name, a->size);
    }
    return MACS_OK;
}

macs_status macsi_pass_validate(macs_context *ctx, const macs_pass_desc *desc)
{
    macs_status st = check_counts(ctx, desc);
    if (st == MACS_OK)
        st = check_outputs(ctx, desc);
    if (st == MACS_OK)
        st = check_inputs(ctx, desc);
    if (st == MACS_OK)
        st = check_uniforms(ctx, desc);
    if (st == MACS_OK)
        st = check_depth_stencil(ctx, desc);
    if (st == MACS_OK)
        st = check_state(ctx, desc);
    if (st == MACS_OK)
        st = check_geometry(ctx, desc);
    if (st == MACS_OK)
        st = check_float_features(ctx, desc);
    if (st != MACS_OK)
        return st;
    if (desc->input_count > ctx->effective.max_texture_units)
        return macsi_fail(ctx, MACS_ERR_LIMIT, "macs_pass_create: desc.input_count: %d inputs but only %d texture "
                         "units",
                         desc->input_count, ctx->effective.max_texture_units);
    return MACS_OK;
}
