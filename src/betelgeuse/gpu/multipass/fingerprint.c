/* A fingerprint of everything in a committed scene that the GPU renderer bakes into passes and
 * uploaded textures. The scene pointer and commit count alone cannot tell scenes apart: a scene
 * freed and another created can land at the same address with the same count. Fields are hashed
 * one by one (never raw structs, whose padding is undefined); the textures come in as the key of
 * the shared copy (shared/scene_textures.c), which hashes their texels. */
#include <string.h>

#include "multipass.h"

typedef struct hasher {
    uint64_t h;
} hasher;

static void mix(hasher *s, uint64_t v)
{
    s->h = bgi_gpu_hash_mix(s->h, v);
}

static void mix_double(hasher *s, double d)
{
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    mix(s, v);
}

static void mix_doubles(hasher *s, const double *d, size_t n)
{
    for (size_t i = 0; i < n; i++)
        mix_double(s, d[i]);
}

static void mix_color(hasher *s, const bg_color_param *c)
{
    mix_double(s, c->r);
    mix_double(s, c->g);
    mix_double(s, c->b);
    mix(s, c->texture);
}

static void mix_scalar(hasher *s, const bg_scalar_param *p)
{
    mix_double(s, p->value);
    mix(s, p->texture);
    mix(s, (uint64_t)p->channel);
}

static void mix_layer(hasher *s, const bg_schlick_layer *l)
{
    mix_color(s, &l->reflectance);
    mix_scalar(s, &l->roughness);
    mix_scalar(s, &l->isotropy);
}

uint64_t bgi_gpu_scene_fingerprint(const bg_scene_state *state, uint64_t textures)
{
    hasher s = {0x243f6a8885a308d3ull};
    const bg_camera_data *c = &state->camera;
    mix_double(&s, c->camera.position.x);
    mix_double(&s, c->camera.position.y);
    mix_double(&s, c->camera.position.z);
    mix_doubles(&s, c->forward, 3);
    mix_doubles(&s, c->right, 3);
    mix_doubles(&s, c->up, 3);
    mix_double(&s, c->half_y);
    mix_double(&s, c->orthographic ? 1.0 : 0.0);
    mix_double(&s, c->camera.aperture_radius);
    mix_double(&s, c->focus);
    mix_doubles(&s, state->ambient, 3);
    mix(&s, state->object_count);
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_object_data *o = &state->objects[i];
        mix(&s, (uint64_t)o->shape);
        mix_doubles(&s, &o->to_world[0][0], 16);
        mix_doubles(&s, &o->to_object[0][0], 16);
        mix_doubles(&s, &o->normal_to_world[0][0], 9);
        mix(&s, o->material);
        mix(&s, (uint64_t)o->uv_mapping);
        mix_doubles(&s, o->uv_scale, 2);
        mix(&s, o->casts_shadows);
        mix(&s, o->bounded);
        mix_doubles(&s, o->bounds_min, 3);
        mix_doubles(&s, o->bounds_max, 3);
    }
    mix(&s, state->material_count);
    for (uint32_t i = 0; i < state->material_count; i++) {
        const bg_material *m = &state->materials[i];
        mix_layer(&s, &m->base);
        mix(&s, m->has_coat);
        mix_layer(&s, &m->coat);
        mix_color(&s, &m->ambient);
        mix_color(&s, &m->emission);
        mix_scalar(&s, &m->transparency);
        mix_double(&s, m->ior);
        mix_scalar(&s, &m->coverage);
        mix_double(&s, m->coverage_cutoff);
        mix(&s, (uint64_t)m->sides);
        mix(&s, m->glossy);
    }
    mix(&s, state->light_count);
    for (uint32_t i = 0; i < state->light_count; i++) {
        const bg_light *l = &state->lights[i];
        mix(&s, (uint64_t)l->type);
        mix_double(&s, l->position.x);
        mix_double(&s, l->position.y);
        mix_double(&s, l->position.z);
        mix_double(&s, l->direction.x);
        mix_double(&s, l->direction.y);
        mix_double(&s, l->direction.z);
        mix_doubles(&s, l->color, 3);
        mix_double(&s, l->intensity);
        mix_doubles(&s, l->attenuation, 3);
        mix_double(&s, l->spot_cutoff_degrees);
        mix_double(&s, l->spot_exponent);
        mix_double(&s, l->radius);
        mix_double(&s, l->edge_u.x);
        mix_double(&s, l->edge_u.y);
        mix_double(&s, l->edge_u.z);
        mix_double(&s, l->edge_v.x);
        mix_double(&s, l->edge_v.y);
        mix_double(&s, l->edge_v.z);
    }
    mix(&s, textures);
    return s.h;
}
