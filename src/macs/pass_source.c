/* Builds the GLSL 1.10 sources of a pass from the caller's strings: the fragment source of each chunk,
 * and the vertex source of a geometry pass. */
#include <stdio.h>
#include <string.h>

#include "internal.h"

static const char *glsl_type(macs_uniform_type t)
{
    switch (t) {
    case MACS_UNIFORM_FLOAT: return "float";
    case MACS_UNIFORM_VEC2: return "vec2";
    case MACS_UNIFORM_VEC3: return "vec3";
    case MACS_UNIFORM_VEC4: return "vec4";
    case MACS_UNIFORM_INT: return "int";
    case MACS_UNIFORM_BOOL: return "bool";
    case MACS_UNIFORM_MAT3: return "mat3";
    case MACS_UNIFORM_MAT4: return "mat4";
    default: return NULL;
    }
}

size_t macsi_uniform_value_size(macs_uniform_type t, int count)
{
    size_t n;
    switch (t) {
    case MACS_UNIFORM_FLOAT: case MACS_UNIFORM_INT: case MACS_UNIFORM_BOOL: n = 1; break;
    case MACS_UNIFORM_VEC2: n = 2; break;
    case MACS_UNIFORM_VEC3: n = 3; break;
    case MACS_UNIFORM_VEC4: n = 4; break;
    case MACS_UNIFORM_MAT3: n = 9; break;
    case MACS_UNIFORM_MAT4: n = 16; break;
    default: return 0;
    }
    /* int and float are both 4 bytes on every platform GL runs on; bool travels as int. */
    return n * 4 * (size_t)(count > 0 ? count : 1);
}

/* A growing string; on allocation failure it stays failed and the result is NULL. */
typedef struct text {
    const macs_allocator *a;
    char *s;
    size_t len, cap;
    bool failed;
} text;

static void append(text *t, const char *s)
{
    if (t->failed || !s)
        return;
    size_t n = strlen(s);
    if (t->len + n + 1 > t->cap) {
        size_t cap = (t->cap ? t->cap * 2 : 1024);
        while (cap < t->len + n + 1)
            cap *= 2;
        char *grown = macsi_alloc(t->a, cap);
        if (!grown) {
            t->failed = true;
            return;
        }
        if (t->s)
            memcpy(grown, t->s, t->len + 1);
        macsi_free(t->a, t->s);
        t->s = grown;
        t->cap = cap;
    }
    memcpy(t->s + t->len, s, n + 1);
    t->len += n;
}

static void append_line_directive(text *t, int source)
{
    /* GLSL 1.10: the line after "#line L S" is line L + 1 of source string S, so L = 0 makes info logs
     * count lines from 1 within the caller's own string. (Mesa honours the line but prints source 0.) */
    char buf[48];
    snprintf(buf, sizeof buf, "\n#line 0 %d\n", source);
    append(t, buf);
}

const char *macsi_attribute_type(int size)
{
    static const char *const types[4] = {"float", "vec2", "vec3", "vec4"};
    return size >= 1 && size <= 4 ? types[size - 1] : NULL;
}

static void append_uniforms(text *t, const macs_pass_desc *desc)
{
    char buf[256];
    for (int i = 0; i < desc->uniform_count; i++) {
        const macs_uniform_desc *u = &desc->uniforms[i];
        if (u->count > 0)
            snprintf(buf, sizeof buf, "uniform %s %s[%d];\n", glsl_type(u->type), u->name, u->count);
        else
            snprintf(buf, sizeof buf, "uniform %s %s;\n", glsl_type(u->type), u->name);
        append(t, buf);
    }
}

static char *finish(const macs_allocator *a, text *t)
{
    if (t->failed) {
        macsi_free(a, t->s);
        return NULL;
    }
    return t->s;
}

char *macsi_pass_vertex_source(const macs_allocator *a, const macs_pass_desc *desc)
{
    text t = {a, NULL, 0, 0, false};
    char buf[256];
    append(&t, "#version 110\n");
    for (int i = 0; i < desc->attribute_count; i++) {
        snprintf(buf, sizeof buf, "attribute %s %s;\n", macsi_attribute_type(desc->attributes[i].size),
                 desc->attributes[i].name);
        append(&t, buf);
    }
    append_uniforms(&t, desc);
    append(&t, desc->varyings);
    append_line_directive(&t, 1);
    append(&t, desc->vertex_functions);
    append(&t, "\n#line 0 0\nvoid main()\n{");
    append_line_directive(&t, 2);
    append(&t, desc->vertex_main);
    append(&t, "\n}\n");
    return finish(a, &t);
}

char *macsi_pass_source(const macs_allocator *a, const macs_pass_desc *desc, int first_output, int output_count)
{
    text t = {a, NULL, 0, 0, false};
    char buf[256];
    /* A geometry pass has no full-screen triangle to interpolate macs_uv over: the same point comes
     * from the pixel's window position. */
    if (desc->vertex_main)
        append(&t, "#version 110\nuniform vec2 macs_inverse_size;\nvec2 macs_uv;\n");
    else
        append(&t, "#version 110\nvarying vec2 macs_uv;\n");
    for (int i = 0; i < desc->input_count; i++) {
        snprintf(buf, sizeof buf, "uniform sampler2D %s;\n", desc->inputs[i].name);
        append(&t, buf);
    }
    append_uniforms(&t, desc);
    append(&t, desc->varyings);
    append_line_directive(&t, 1);
    append(&t, desc->functions);
    append(&t, "\n#line 0 0\nvoid main()\n{");
    if (desc->vertex_main)
        append(&t, "\nmacs_uv = gl_FragCoord.xy * macs_inverse_size;");
    append_line_directive(&t, 2);
    append(&t, desc->main);
    for (int i = 0; i < output_count; i++) {
        append_line_directive(&t, 3 + first_output + i);
        /* No vec4() around the value: a float expression must be an error, not a silent splat. */
        snprintf(buf, sizeof buf, "gl_FragData[%d] = (", i);
        append(&t, buf);
        append(&t, desc->outputs[first_output + i].value);
        append(&t, ");");
    }
    append(&t, "\n}\n");
    return finish(a, &t);
}
