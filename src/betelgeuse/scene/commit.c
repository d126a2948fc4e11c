/* Commit: validate the pending state, then derive what the renderers read. Validation and every
 * allocation happen before the first committed value is overwritten, so a failed commit leaves
 * the previous committed state intact. Committed arrays are reused (grown, never shrunk), so a
 * commit that changes only values allocates nothing. */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "../common/affine.h"
#include "../common/shapes.h"
#include "scene_private.h"

static const char where_commit[] = "bg_scene_commit";

/* The mapping BG_UV_DEFAULT resolves to, from each shape's row of common/shapes.h. */
static bg_uv_mapping default_uv(bg_shape shape)
{
#define DEFAULT_UV_OF(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = default_uv,
    static const bg_uv_mapping uv[BG_SHAPE_COUNT_] = {BG_SHAPES(DEFAULT_UV_OF)};
#undef DEFAULT_UV_OF
    return uv[shape];
}

/* Half extents along one world axis of the transformed prototype, from that axis's row (a b c)
 * of the linear part. For the box and rectangle this equals transforming their corners; for the
 * sphere and cylinder it is the exact (tighter) extent of the transformed surface. */
static double sphere_extent(double a, double b, double c)
{
    return sqrt(a * a + b * b + c * c);
}

static double box_extent(double a, double b, double c)
{
    return fabs(a) + fabs(b) + fabs(c);
}

static double cylinder_extent(double a, double b, double c)
{
    return fabs(b) + sqrt(a * a + c * c);
}

static double rectangle_extent(double a, double b, double c)
{
    (void)b; /* the prototype is flat in y */
    return fabs(a) + fabs(c);
}

typedef double (*half_extent_fn)(double a, double b, double c);
#define HALF_EXTENT_OF(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = half_extent,
static const half_extent_fn shape_half_extent[BG_SHAPE_COUNT_] = {BG_SHAPES(HALF_EXTENT_OF)};
#undef HALF_EXTENT_OF

/* World box of a bounded prototype under the affine m: centre m's translation, half extent per
 * axis from the shape, padded by a few ulps so rounding never cuts the object. */
static void object_bounds(half_extent_fn half_extent, const bg_mat4 *transform, double lo[3], double hi[3])
{
    const double (*m)[4] = transform->m;
    for (int i = 0; i < 3; i++) {
        double e = half_extent(m[i][0], m[i][1], m[i][2]);
        double t = m[i][3];
        e += 8.0 * DBL_EPSILON * (fabs(t) + e);
        lo[i] = t - e;
        hi[i] = t + e;
    }
}

bool bgi_object_world_box(const bg_object_desc *desc, double lo[3], double hi[3])
{
    half_extent_fn half_extent = shape_half_extent[desc->shape];
    if (half_extent) {
        object_bounds(half_extent, &desc->transform, lo, hi);
        return true;
    }
    for (int i = 0; i < 3; i++) {
        lo[i] = -DBL_MAX;
        hi[i] = DBL_MAX;
    }
    return false;
}

static void normalize3(double v[3])
{
    double l = bgi_vec3_length(bg_vec3_make(v[0], v[1], v[2]));
    v[0] /= l; v[1] /= l; v[2] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void camera_data(const bg_camera *c, bg_camera_data *out)
{
    out->camera = *c;
    double f[3] = {c->look_at.x - c->position.x, c->look_at.y - c->position.y, c->look_at.z - c->position.z};
    double up[3] = {c->up.x, c->up.y, c->up.z};
    normalize3(f);
    normalize3(up);
    double r[3], u[3];
    cross3(f, up, r);
    normalize3(r);
    cross3(r, f, u);
    normalize3(u);
    memcpy(out->forward, f, sizeof f);
    memcpy(out->right, r, sizeof r);
    memcpy(out->up, u, sizeof u);
    out->tan_half_fov_y = tan(c->fov_y_degrees * (3.14159265358979323846 / 360.0));
}

static bg_status validate_all(bg_scene *s)
{
    char where[64];
    bg_status st;
    if ((st = bgi_validate_camera(s, "bg_scene_commit: camera", &s->camera)) != BG_OK ||
        (st = bgi_validate_color3(s, where_commit, "ambient", s->ambient)) != BG_OK)
        return st;
    const bg_texture_data *t = s->textures.data;
    for (uint32_t i = 0; i < s->textures.count; i++)
        if (!t[i].texels || t[i].width <= 0 || t[i].height <= 0)
            return bgi_scene_fail(s, BG_ERR_INVALID_ARGUMENT, "%s: texture %u has no texels", where_commit, i + 1);
    const bg_material *m = s->materials.data;
    for (uint32_t i = 0; i < s->materials.count; i++) {
        snprintf(where, sizeof where, "%s: material %u", where_commit, i + 1);
        if ((st = bgi_validate_material(s, where, &m[i], s->textures.count)) != BG_OK)
            return st;
    }
    const bg_light *l = s->lights.data;
    for (uint32_t i = 0; i < s->lights.count; i++) {
        snprintf(where, sizeof where, "%s: light %u", where_commit, i + 1);
        if ((st = bgi_validate_light(s, where, &l[i])) != BG_OK)
            return st;
    }
    const bg_object_desc *o = s->objects.data;
    for (uint32_t i = 0; i < s->objects.count; i++) {
        snprintf(where, sizeof where, "%s: object %u", where_commit, i + 1);
        if ((st = bgi_validate_object(s, where, &o[i], s->materials.count)) != BG_OK)
            return st;
        /* The inverse itself must be finite too (validate_object only tests the ratio). */
        double inv[4][4];
        bg_affine_check c = bgi_affine_inverse(&o[i].transform, inv);
        if (c != BG_AFFINE_OK)
            return bgi_scene_fail(s, BG_ERR_INVALID_ARGUMENT, "%s: transform %s", where, bgi_affine_check_string(c));
    }
    return BG_OK;
}

/* Grows the committed arrays; after each step the committed pointers follow the (possibly moved)
 * storage, whose contents realloc kept, so the old committed state stays readable on failure. */
static bg_status reserve_all(bg_scene *s)
{
    bg_status st;
    if ((st = bgi_array_reserve(s, &s->c_objects, s->objects.count, sizeof(bg_object_data), where_commit)) != BG_OK)
        return st;
    s->state.objects = s->c_objects.data;
    if ((st = bgi_array_reserve(s, &s->c_materials, s->materials.count, sizeof(bg_material), where_commit)) != BG_OK)
        return st;
    s->state.materials = s->c_materials.data;
    if ((st = bgi_array_reserve(s, &s->c_lights, s->lights.count, sizeof(bg_light), where_commit)) != BG_OK)
        return st;
    s->state.lights = s->c_lights.data;
    if ((st = bgi_array_reserve(s, &s->c_textures, s->textures.count, sizeof(bg_texture_data), where_commit)) != BG_OK)
        return st;
    s->state.textures = s->c_textures.data;
    return BG_OK;
}

static void commit_object(const bg_object_desc *d, bg_object_data *o)
{
    o->shape = d->shape;
    memcpy(o->to_world, d->transform.m, sizeof o->to_world);
    bgi_affine_inverse(&d->transform, o->to_object); /* checked in validate_all */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            o->normal_to_world[i][j] = o->to_object[j][i];
    o->material = d->material - 1;
    o->uv_mapping = d->uv_mapping == BG_UV_DEFAULT ? default_uv(d->shape) : d->uv_mapping;
    o->uv_scale[0] = d->uv_scale[0];
    o->uv_scale[1] = d->uv_scale[1];
    o->casts_shadows = d->casts_shadows;
    o->bounded = bgi_object_world_box(d, o->bounds_min, o->bounds_max);
}

static void commit_light(const bg_light *in, bg_light *out)
{
    *out = *in;
    double d[3] = {in->direction.x, in->direction.y, in->direction.z};
    if (bgi_vec3_length(in->direction) == 0.0) {
        /* Unused (a point light without a cone); keep the committed state normalised anyway. */
        d[0] = 0; d[1] = -1; d[2] = 0;
    }
    normalize3(d);
    out->direction = bg_vec3_make(d[0], d[1], d[2]);
}

/* Scenes may commit on several threads at once; C99 has no atomics. */
static pthread_mutex_t serial_lock = PTHREAD_MUTEX_INITIALIZER;
static uint64_t last_serial;

static uint64_t next_serial(void)
{
    pthread_mutex_lock(&serial_lock);
    uint64_t serial = ++last_serial;
    pthread_mutex_unlock(&serial_lock);
    return serial;
}

bg_status bg_scene_commit(bg_scene *scene)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    bg_status st = validate_all(scene);
    if (st == BG_OK)
        st = reserve_all(scene);
    if (st == BG_OK)
        st = bgi_scene_tree_prepare(scene);
    if (st != BG_OK)
        return st;

    bg_scene_state *state = &scene->state;
    bg_object_data *objects = scene->c_objects.data;
    const bg_object_desc *descs = scene->objects.data;
    state->has_bounded_objects = false;
    for (int i = 0; i < 3; i++) {
        state->bounds_min[i] = 0;
        state->bounds_max[i] = 0;
    }
    for (uint32_t i = 0; i < scene->objects.count; i++) {
        commit_object(&descs[i], &objects[i]);
        if (!objects[i].bounded)
            continue;
        for (int k = 0; k < 3; k++) {
            if (!state->has_bounded_objects || objects[i].bounds_min[k] < state->bounds_min[k])
                state->bounds_min[k] = objects[i].bounds_min[k];
            if (!state->has_bounded_objects || objects[i].bounds_max[k] > state->bounds_max[k])
                state->bounds_max[k] = objects[i].bounds_max[k];
        }
        state->has_bounded_objects = true;
    }
    if (scene->materials.count)
        memcpy(scene->c_materials.data, scene->materials.data, scene->materials.count * sizeof(bg_material));
    if (scene->textures.count)
        memcpy(scene->c_textures.data, scene->textures.data, scene->textures.count * sizeof(bg_texture_data));
    bg_light *lights = scene->c_lights.data;
    const bg_light *pending_lights = scene->lights.data;
    for (uint32_t i = 0; i < scene->lights.count; i++)
        commit_light(&pending_lights[i], &lights[i]);
    camera_data(&scene->camera, &state->camera);
    memcpy(state->ambient, scene->ambient, sizeof state->ambient);
    state->object_count = scene->objects.count;
    state->material_count = scene->materials.count;
    state->texture_count = scene->textures.count;
    state->light_count = scene->lights.count;
    state->objects = scene->c_objects.data;
    state->materials = scene->c_materials.data;
    state->textures = scene->c_textures.data;
    state->lights = scene->c_lights.data;
    bgi_scene_tree_install(scene);
    state->commit_count++;
    state->serial = next_serial();
    scene->committed = true;
    return BG_OK;
}

uint64_t bg_scene_commit_count(const bg_scene *scene)
{
    return scene ? scene->state.commit_count : 0;
}

const bg_scene_state *bgi_scene_committed(const bg_scene *scene)
{
    return scene && scene->committed ? &scene->state : NULL;
}
