/* The environment's importance tables as NEAREST float textures, for the fused plans'
 * bg_environment.glsl; uploaded once per table set (docs/shading.md 7.1). */
#include <string.h>

#include "../../common/alloc.h"
#include "shared.h"

/* One table of w x h values into the R lane of a float texture. */
static bg_status upload(bg_renderer *r, const double *values, int w, int h, macs_texture **out)
{
    size_t n = (size_t)w * (size_t)h;
    float *texels = bgi_alloc(&r->allocator, n * 4 * sizeof *texels);
    if (!texels)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the environment's tables (%zu texels)", n);
    memset(texels, 0, n * 4 * sizeof *texels);
    for (size_t k = 0; k < n; k++)
        texels[4 * k] = (float)values[k];
    bg_status st = bgi_gpu_float_texture(r, w, h, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, texels,
                                         "environment tables", out);
    bgi_free(&r->allocator, texels);
    return st;
}

bg_status bgi_gpu_env_tables_prepare(bg_renderer *r, const bg_scene_state *state)
{
    const bg_environment_data *e = &state->environment;
    if (!e->on || !e->marginal || r->env_tables.id == e->tables_id)
        return BG_OK;
    bgi_gpu_env_tables_release(r);
    const bg_texture_data *t = &state->textures[e->texture - 1];
    bg_status st = upload(r, e->marginal, t->height, 1, &r->env_tables.marginal);
    if (st == BG_OK)
        st = upload(r, e->conditional, t->width, t->height, &r->env_tables.conditional);
    if (st != BG_OK) {
        bgi_gpu_env_tables_release(r);
        return st;
    }
    r->env_tables.id = e->tables_id;
    return BG_OK;
}

void bgi_gpu_env_tables_release(bg_renderer *r)
{
    macs_texture_destroy(r->env_tables.marginal);
    macs_texture_destroy(r->env_tables.conditional);
    memset(&r->env_tables, 0, sizeof r->env_tables);
}

void bgi_gpu_env_info(const bg_scene_state *state, float out[4])
{
    const bg_environment_data *e = &state->environment;
    const bg_texture_data *t = e->on ? &state->textures[e->texture - 1] : NULL;
    out[0] = e->on ? (float)e->intensity : 0.0f;
    out[1] = t ? (float)t->width : 1.0f;
    out[2] = t ? (float)t->height : 1.0f;
    out[3] = e->on && e->marginal ? 1.0f : 0.0f;
}
