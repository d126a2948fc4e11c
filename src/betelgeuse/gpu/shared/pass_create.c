/* Making one MACS pass for the renderer: the description every pass starts from, the shader text
 * assembled from glsl110/ files, and the trial creation that lets a batch fall back to smaller
 * passes. A leaf of gpu/ below every pass builder: it calls only shader_source.c and fail.c. */
#include <string.h>

#include "shared.h"

void bgi_gpu_pass_desc_init(macs_pass_desc *d, const char *main, const macs_input_desc *inputs,
                        macs_texture *const *input_tex, int input_count, const macs_uniform_desc *uniforms,
                        int uniform_count, const macs_output_desc *outputs, macs_texture *const *output_tex,
                        int output_count)
{
    memset(d, 0, sizeof *d);
    d->main = main;
    d->inputs = inputs;
    d->input_count = input_count;
    d->input_textures = input_tex;
    d->uniforms = uniforms;
    d->uniform_count = uniform_count;
    d->outputs = outputs;
    d->output_count = output_count;
    d->output_textures = output_tex;
}

bg_status bgi_gpu_pass_create(bg_renderer *r, const char *what, const char *const *files, const char *extra,
                          macs_pass_desc *desc, macs_pass **out)
{
    gpu_text t;
    bgi_gpu_text_init(&t, &r->allocator);
    const char *seen[32];
    int n = 0;
    for (int i = 0; files && files[i]; i++) {
        if (!bgi_gpu_text_snippet(&t, files[i], seen, &n, 32)) {
            bgi_gpu_text_free(&t);
            return bgi_gpu_fail(r, BG_ERR_GL, "%s: shader file %s (or one it requires) is missing", what,
                            files[i]);
        }
    }
    bgi_gpu_text_append(&t, extra);
    if (t.failed) {
        bgi_gpu_text_free(&t);
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory assembling the %s", what);
    }
    desc->functions = t.s;
    macs_status ms = macs_pass_create(r->ctx, desc, out);
    bgi_gpu_text_free(&t);
    if (ms != MACS_OK) {
        *out = NULL;
        return bgi_gpu_fail_macs(r, ms, what);
    }
    return BG_OK;
}

bg_status bgi_gpu_pass_create_trial(bg_renderer *r, const char *what, macs_pass_desc *desc, bool trial, macs_pass **out,
                                macs_status *refused, char *why, size_t why_size)
{
    *refused = MACS_OK;
    /* A refusal is forgotten only if nothing was wrong before it. */
    bool clean = macs_context_error(r->ctx) == MACS_OK;
    macs_status ms = macs_pass_create(r->ctx, desc, out);
    if (ms == MACS_OK)
        return BG_OK;
    *out = NULL;
    if (trial && clean && (ms == MACS_ERR_SHADER_COMPILE || ms == MACS_ERR_SHADER_LINK)) {
        *refused = ms;
        snprintf(why, why_size, "%s", macs_context_error_message(r->ctx));
        macs_context_clear_error(r->ctx);
        return BG_OK;
    }
    return bgi_gpu_fail_macs(r, ms, what);
}

bg_status bgi_gpu_pass_try(bg_renderer *r, const char *what, const char *functions, macs_pass_desc *desc, bool trial,
                       macs_pass **out, bool *rejected)
{
    desc->functions = functions;
    macs_status refused;
    char why[MACS_MESSAGE_SIZE];
    bg_status st = bgi_gpu_pass_create_trial(r, what, desc, trial, out, &refused, why, sizeof why);
    if (st == BG_OK && refused != MACS_OK) {
        /* The longer shader of a batch is beyond this GL: the caller falls back to smaller passes. */
        bgi_gpu_log(r, BG_LOG_WARNING,
                "%s: the batched shader was refused (%s), falling back to one object per pass: %s",
                what, macs_status_string(refused), why);
        if (rejected)
            *rejected = true;
    }
    return st;
}

bg_status bgi_gpu_pass_from_texts(bg_renderer *r, const char *what, gpu_text *main, gpu_text *functions, bool files_found,
                              macs_pass_desc *desc, bool trial, macs_pass **out, bool *rejected)
{
    bg_status st;
    if (main->failed || functions->failed)
        st = bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building the %s shader", what);
    else if (!files_found)
        st = bgi_gpu_fail(r, BG_ERR_GL, "%s: a glsl110 file its shader needs is missing", what);
    else
        st = bgi_gpu_pass_try(r, what, functions->s, desc, trial, out, rejected);
    bgi_gpu_text_free(main);
    bgi_gpu_text_free(functions);
    return st;
}

/* Uniform storage as old hardware allocates it: every float, vec2 or vec3 takes a whole vec4. */
int bgi_gpu_uniform_type_components(macs_uniform_type t)
{
    return t == MACS_UNIFORM_MAT4 ? 16 : t == MACS_UNIFORM_MAT3 ? 12 : 4;
}

int bgi_gpu_uniform_components(const macs_uniform_desc *u, int count)
{
    int components = 0;
    for (int i = 0; i < count; i++)
        components += bgi_gpu_uniform_type_components(u[i].type) * (u[i].count > 0 ? u[i].count : 1);
    return components;
}
