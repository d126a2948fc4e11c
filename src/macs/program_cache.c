/* Context-level cache of linked programs keyed on the full fragment source and the vertex source
 * (NULL for the shared full-screen one): identical pass chunks share one program, and a program is
 * deleted when the last chunk using it goes. */
#include <string.h>

#include "internal.h"

static uint64_t hash_source(const char *s, const char *vertex)
{
    uint64_t h = 1469598103934665603ull; /* FNV-1a: cheap, and strcmp settles collisions anyway */
    for (; vertex && *vertex; vertex++) {
        h ^= (unsigned char)*vertex;
        h *= 1099511628211ull;
    }
    for (; *s; s++) {
        h ^= (unsigned char)*s;
        h *= 1099511628211ull;
    }
    return h;
}

/* The vertex shader of a geometry pass, compiled; 0 after recording the failure. */
static GLuint compile_vertex(macs_context *ctx, const char *source)
{
    const macs_gl *gl = &ctx->gl;
    char log[MACS_MESSAGE_SIZE - 256];
    GLint ok = 0;
    GLuint vs = gl->CreateShader(GL_VERTEX_SHADER);
    gl->ShaderSource(vs, 1, &source, NULL);
    gl->CompileShader(vs);
    gl->GetShaderiv(vs, GL_COMPILE_STATUS, &ok);
    if (ok)
        return vs;
    log[0] = '\0';
    gl->GetShaderInfoLog(vs, (GLsizei)sizeof log, NULL, log);
    gl->DeleteShader(vs);
    macsi_fail(ctx, MACS_ERR_SHADER_COMPILE, "vertex shader (source 1 = vertex_functions, 2 = vertex_main):\n%s", log);
    return 0;
}

static macs_status compile_and_link(macs_context *ctx, const char *vertex_source, const char *source,
                                    int input_count, char *const *input_names, int attribute_count,
                                    const char *const *attribute_names, GLuint *out)
{
    const macs_gl *gl = &ctx->gl;
    char log[MACS_MESSAGE_SIZE - 256];
    GLint ok = 0;
    GLuint vs = ctx->vertex_shader;
    if (vertex_source && !(vs = compile_vertex(ctx, vertex_source)))
        return MACS_ERR_SHADER_COMPILE;
    GLuint fs = gl->CreateShader(GL_FRAGMENT_SHADER);
    gl->ShaderSource(fs, 1, &source, NULL);
    gl->CompileShader(fs);
    gl->GetShaderiv(fs, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        log[0] = '\0';
        gl->GetShaderInfoLog(fs, (GLsizei)sizeof log, NULL, log);
        gl->DeleteShader(fs);
        if (vertex_source)
            gl->DeleteShader(vs);
        return macsi_fail(ctx, MACS_ERR_SHADER_COMPILE,
                         "fragment shader (source 1 = functions, 2 = main, 3+i = output i):\n%s", log);
    }
    GLuint program = gl->CreateProgram();
    gl->AttachShader(program, vs);
    gl->AttachShader(program, fs);
    if (vertex_source)
        for (int i = 0; i < attribute_count; i++)
            gl->BindAttribLocation(program, (GLuint)i, attribute_names[i]);
    else
        gl->BindAttribLocation(program, 0, "macs_position");
    gl->LinkProgram(program);
    /* The program keeps the shaders alive as long as it needs them. */
    gl->DeleteShader(fs);
    if (vertex_source)
        gl->DeleteShader(vs);
    gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        log[0] = '\0';
        gl->GetProgramInfoLog(program, (GLsizei)sizeof log, NULL, log);
        gl->DeleteProgram(program);
        return macsi_fail(ctx, MACS_ERR_SHADER_LINK, "%s", log);
    }
    /* Input i always samples texture unit i; the source names the inputs in order, so every pass
     * sharing this program binds its inputs the same way. */
    macsi_use_program(ctx, program);
    for (int i = 0; i < input_count; i++) {
        GLint loc = gl->GetUniformLocation(program, input_names[i]);
        if (loc >= 0)
            macsi_uniform(ctx, MACS_UNIFORM_INT, loc, 1, &i);
    }
    macsi_use_program(ctx, 0);
    macs_status st = macsi_gl_check(ctx, "linking a pass program");
    if (st != MACS_OK) {
        gl->DeleteProgram(program);
        return st;
    }
    *out = program;
    return MACS_OK;
}

static bool same_vertex(const char *a, const char *b)
{
    return a == b || (a && b && strcmp(a, b) == 0);
}

macs_status macsi_program_acquire(macs_context *ctx, const char *vertex_source, const char *source,
                                 int input_count, char *const *input_names, int attribute_count,
                                 const char *const *attribute_names, macs_program **out)
{
    uint64_t h = hash_source(source, vertex_source);
    for (macs_program *p = ctx->programs; p; p = p->next)
        if (p->hash == h && strcmp(p->source, source) == 0 && same_vertex(p->vertex_source, vertex_source)) {
            p->refs++;
            *out = p;
            return MACS_OK;
        }
    macs_program *p = macsi_calloc(&ctx->allocator, 1, sizeof *p);
    char *copy = macsi_strdup(&ctx->allocator, source);
    char *vertex_copy = vertex_source ? macsi_strdup(&ctx->allocator, vertex_source) : NULL;
    if (!p || !copy || (vertex_source && !vertex_copy)) {
        macsi_free(&ctx->allocator, p);
        macsi_free(&ctx->allocator, copy);
        macsi_free(&ctx->allocator, vertex_copy);
        return macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "allocating a program cache entry");
    }
    macs_status st = compile_and_link(ctx, vertex_source, source, input_count, input_names, attribute_count,
                                      attribute_names, &p->id);
    if (st != MACS_OK) {
        macsi_free(&ctx->allocator, p);
        macsi_free(&ctx->allocator, copy);
        macsi_free(&ctx->allocator, vertex_copy);
        return st;
    }
    p->vertex_source = vertex_copy;
    ctx->programs_compiled++;
    p->source = copy;
    p->hash = h;
    p->refs = 1;
    p->next = ctx->programs;
    ctx->programs = p;
    *out = p;
    return MACS_OK;
}

void macsi_program_release(macs_context *ctx, macs_program *program)
{
    if (!program || --program->refs > 0)
        return;
    for (macs_program **pp = &ctx->programs; *pp; pp = &(*pp)->next)
        if (*pp == program) {
            *pp = program->next;
            break;
        }
    ctx->gl.DeleteProgram(program->id);
    macsi_free(&ctx->allocator, program->vertex_source);
    macsi_free(&ctx->allocator, program->source);
    macsi_free(&ctx->allocator, program);
}

void macsi_program_cache_destroy(macs_context *ctx)
{
    while (ctx->programs) {
        macs_program *p = ctx->programs;
        ctx->programs = p->next;
        ctx->gl.DeleteProgram(p->id);
        macsi_free(&ctx->allocator, p->vertex_source);
        macsi_free(&ctx->allocator, p->source);
        macsi_free(&ctx->allocator, p);
    }
}

uint64_t macs_context_programs_compiled(const macs_context *ctx)
{
    return ctx ? ctx->programs_compiled : 0;
}
