/* GL_LINEAR and GL_NEAREST texture sampling and the evaluation of (textured) material parameters
 * (docs/shading.md section 5). */
#include <string.h>

#include "cpu_internal.h"

/* The texel index along one axis after the wrap mode. */
static int wrap_index(int i, int size, bg_texture_wrap wrap)
{
    if (wrap == BG_WRAP_CLAMP)
        return i < 0 ? 0 : (i >= size ? size - 1 : i);
    i %= size;
    return i < 0 ? i + size : i;
}

/* Reduces a coordinate as GL does before filtering: fract for REPEAT, clamp to [0, 1] for CLAMP
 * (clamping first gives exactly CLAMP_TO_EDGE and keeps floor() within int range). */
static double wrap_coord(double s, bg_texture_wrap wrap)
{
    if (wrap == BG_WRAP_CLAMP)
        return s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    return s - floor(s);
}

/* GL_NEAREST: the texel whose square holds the point, floor(s size) after the wrap; s = 1 (CLAMP's
 * upper edge) falls on the last texel, as in GL. */
static int nearest_index(double s, int size, bg_texture_wrap wrap)
{
    double x = floor(wrap_coord(s, wrap) * size);
    return wrap_index(x >= size ? size - 1 : (int)x, size, wrap);
}

static void sample_nearest(const bg_texture_data *texture, double u, double v, double rgba[4])
{
    int i = nearest_index(u, texture->width, texture->wrap), j = nearest_index(v, texture->height, texture->wrap);
    bgi_texture_texel(texture, (size_t)j * (size_t)texture->width + (size_t)i, rgba);
}

void bgi_cpu_texture_sample(const bg_texture_data *texture, double u, double v, double rgba[4])
{
    if (texture->filter == BG_FILTER_NEAREST) {
        sample_nearest(texture, u, v, rgba);
        return;
    }
    int w = texture->width, h = texture->height;
    double x = wrap_coord(u, texture->wrap) * w - 0.5;
    double y = wrap_coord(v, texture->wrap) * h - 0.5;
    double fx = floor(x), fy = floor(y);
    double ax = x - fx, ay = y - fy;
    int i0 = wrap_index((int)fx, w, texture->wrap), i1 = wrap_index((int)fx + 1, w, texture->wrap);
    int j0 = wrap_index((int)fy, h, texture->wrap), j1 = wrap_index((int)fy + 1, h, texture->wrap);
    /* Each texel decoded (an 8-bit one through bgi_srgb_table) before the weights: the filter works
     * in linear light, as the GPU's bg_texture_filter.glsl does. */
    double t00[4], t10[4], t01[4], t11[4];
    bgi_texture_texel(texture, (size_t)j0 * (size_t)w + (size_t)i0, t00);
    bgi_texture_texel(texture, (size_t)j0 * (size_t)w + (size_t)i1, t10);
    bgi_texture_texel(texture, (size_t)j1 * (size_t)w + (size_t)i0, t01);
    bgi_texture_texel(texture, (size_t)j1 * (size_t)w + (size_t)i1, t11);
    for (int c = 0; c < 4; c++)
        rgba[c] = (1.0 - ax) * (1.0 - ay) * t00[c] + ax * (1.0 - ay) * t10[c] + (1.0 - ax) * ay * t01[c] +
                  ax * ay * t11[c];
}

static const bg_texture_data *texture_of(const bg_scene_state *state, uint32_t handle)
{
    if (handle == 0 || handle > state->texture_count)
        return NULL;
    return &state->textures[handle - 1];
}

static double clamp01(double x)
{
    return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
}

static void color_param(const bg_scene_state *state, const bg_color_param *param, const double uv[2], double out[3])
{
    bg_v3_set(out, param->r, param->g, param->b);
    const bg_texture_data *tex = texture_of(state, param->texture);
    if (tex) {
        double texel[4];
        bgi_cpu_texture_sample(tex, uv[0], uv[1], texel);
        for (int i = 0; i < 3; i++)
            out[i] *= texel[i];
    }
}

static double scalar_param(const bg_scene_state *state, const bg_scalar_param *param, const double uv[2])
{
    double value = param->value;
    const bg_texture_data *tex = texture_of(state, param->texture);
    if (tex) {
        double texel[4];
        int channel = param->channel < 0 ? 0 : (param->channel > 3 ? 3 : param->channel);
        bgi_cpu_texture_sample(tex, uv[0], uv[1], texel);
        value *= texel[channel];
    }
    return value;
}

static void layer(const bg_scene_state *state, const bg_schlick_layer *in, const double uv[2], bg_cpu_layer *out)
{
    color_param(state, &in->reflectance, uv, out->c);
    for (int i = 0; i < 3; i++)
        out->c[i] = clamp01(out->c[i]);
    out->r = clamp01(scalar_param(state, &in->roughness, uv));
    out->p = clamp01(scalar_param(state, &in->isotropy, uv));
}

void bgi_cpu_surface_eval(const bg_scene_state *state, const bg_material *material, const double uv[2],
                         bg_cpu_surface *surface)
{
    memset(surface, 0, sizeof *surface);
    layer(state, &material->base, uv, &surface->base);
    surface->has_coat = material->has_coat;
    if (material->has_coat)
        layer(state, &material->coat, uv, &surface->coat);
    color_param(state, &material->ambient, uv, surface->ambient);
    color_param(state, &material->emission, uv, surface->emission);
    for (int i = 0; i < 3; i++) {
        surface->ambient[i] = surface->ambient[i] > 0.0 ? surface->ambient[i] : 0.0;
        surface->emission[i] = surface->emission[i] > 0.0 ? surface->emission[i] : 0.0;
    }
    surface->transparency = clamp01(scalar_param(state, &material->transparency, uv));
    surface->ior = material->ior > 0.0 ? material->ior : 1.0;
}
