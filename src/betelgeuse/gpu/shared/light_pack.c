/* One light as bg_light.glsl reads it, for both plans: the multipass sets a group's arrays of up to
 * four (light_pass.c), the fused plan one array of every light (fused_uniforms.c). Positions are
 * camera-relative (origin.c); a directional light's direction stands in its place, w 1. */
#include <math.h>

#include "shared.h"

#define PI 3.14159265358979323846

gpu_packed_light bgi_gpu_light_pack(const bg_scene_state *state, uint32_t k)
{
    const bg_light *l = &state->lights[k];
    gpu_packed_light p;
    bool directional = l->type == BG_LIGHT_DIRECTIONAL;
    if (directional) {
        p.pos[0] = (float)l->direction.x;
        p.pos[1] = (float)l->direction.y;
        p.pos[2] = (float)l->direction.z;
    } else {
        bgi_gpu_origin_point(state, &l->position, p.pos);
    }
    p.pos[3] = directional ? 1.0f : 0.0f;
    for (int c = 0; c < 3; c++) {
        p.rad[c] = (float)(l->color[c] * l->intensity);
        p.att[c] = (float)l->attenuation[c];
    }
    double axis[3] = {l->direction.x, l->direction.y, l->direction.z};
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    bool cone = !directional && l->spot_cutoff_degrees < 180.0 && len > 0.0;
    for (int c = 0; c < 3; c++)
        p.spot[c] = cone ? (float)(axis[c] / len) : 0.0f;
    /* -2: no cone (bg_light.glsl), below every cosine. */
    p.spot[3] = cone ? (float)cos(l->spot_cutoff_degrees * (PI / 180.0)) : -2.0f;
    p.exponent = (float)l->spot_exponent;
    /* The kind in edge_u's w: 0 point or directional, 1 sphere, 2 rectangle (bg_area_light.glsl). */
    const bg_vec3 *eu = &l->edge_u, *ev = &l->edge_v;
    bool rectangle = l->type == BG_LIGHT_RECTANGLE;
    float u[3] = {(float)eu->x, (float)eu->y, (float)eu->z}, v[3] = {(float)ev->x, (float)ev->y, (float)ev->z};
    for (int c = 0; c < 3; c++) {
        p.edge_u[c] = rectangle ? u[c] : 0.0f;
        p.edge_v[c] = rectangle ? v[c] : 0.0f;
    }
    p.edge_u[3] = l->type == BG_LIGHT_SPHERE ? 1.0f : rectangle ? 2.0f : 0.0f;
    p.edge_v[3] = l->type == BG_LIGHT_SPHERE ? (float)l->radius : 0.0f;
    return p;
}

bool bgi_gpu_scene_has_area_lights(const bg_scene_state *state)
{
    for (uint32_t k = 0; k < state->light_count; k++)
        if (state->lights[k].type == BG_LIGHT_SPHERE || state->lights[k].type == BG_LIGHT_RECTANGLE)
            return true;
    return false;
}
