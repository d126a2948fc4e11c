/* The material parameters as both plans' shaders read them: one table (GPU_PARAMS) of names, types
 * and clamps, and one rule for a parameter's uniform value (docs/shading.md 5). */
#include "shared.h"

static const struct {
    const char *local;
    bool color, unit;
} param_row[GPU_P_COUNT_] = {
#define PARAM_ROW_(id, local, color, unit, need) [GPU_P_##id] = {local, color, unit},
    GPU_PARAMS(PARAM_ROW_)
#undef PARAM_ROW_
};

const char *bgi_gpu_param_local(gpu_param p)
{
    return param_row[p].local;
}

bool bgi_gpu_param_is_color(gpu_param p)
{
    return param_row[p].color;
}

bool bgi_gpu_param_is_unit(gpu_param p)
{
    return param_row[p].unit;
}

void bgi_gpu_param_of(const bg_material *m, gpu_param p, double v[3], uint32_t *texture, int *channel)
{
    const bg_color_param *c = NULL;
    const bg_scalar_param *s = NULL;
    switch (p) {
    case GPU_P_BASE_C: c = &m->base.reflectance; break;
    case GPU_P_BASE_R: s = &m->base.roughness; break;
    case GPU_P_BASE_P: s = &m->base.isotropy; break;
    case GPU_P_AMBIENT: c = &m->ambient; break;
    case GPU_P_EMISSION: c = &m->emission; break;
    case GPU_P_TRANSPARENCY: s = &m->transparency; break;
    case GPU_P_COAT_C: c = &m->coat.reflectance; break;
    case GPU_P_COAT_R: s = &m->coat.roughness; break;
    case GPU_P_COAT_P: s = &m->coat.isotropy; break;
    default: break;
    }
    v[0] = v[1] = v[2] = 0.0;
    *texture = 0;
    *channel = 0;
    if (c) {
        v[0] = c->r;
        v[1] = c->g;
        v[2] = c->b;
        *texture = c->texture;
    } else if (s) {
        v[0] = s->value;
        *texture = s->texture;
        *channel = s->channel & 3;
    }
}

void bgi_gpu_param_value(const bg_scene_state *state, const bg_material *m, gpu_param p, float out[3])
{
    double v[3];
    uint32_t texture;
    int channel;
    bgi_gpu_param_of(m, p, v, &texture, &channel);
    /* The scene's ambient light folds into the material's ambient colour here. */
    if (p == GPU_P_AMBIENT)
        for (int k = 0; k < 3; k++)
            v[k] *= state->ambient[k];
    if (!m->has_coat && p == GPU_P_COAT_C)
        v[0] = v[1] = v[2] = 0.0;
    if (!m->has_coat && p == GPU_P_COAT_R)
        v[0] = -1.0;
    if (!m->has_coat && p == GPU_P_COAT_P)
        v[0] = 1.0;
    for (int k = 0; k < 3; k++)
        out[k] = (float)v[k];
}
