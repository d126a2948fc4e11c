/* Commit: derive the whole pending state aside (the p_ arrays: live items in slot order, with
 * handles translated to dense indices), then copy it over the committed arrays. Every check and
 * every allocation happens before the first committed value is overwritten, so a failed commit
 * leaves the previous committed state intact and renderable. Committed arrays are reused (grown,
 * never shrunk), so a commit that changes only values allocates nothing. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "../common/affine.h"
#include "../common/alloc.h"
#include "scene_private.h"

static const char where_commit[] = "bg_scene_commit";

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize3(double v[3])
{
    bg_vec3 n = bgi_vec3_normalize(bg_vec3_make(v[0], v[1], v[2]));
    v[0] = n.x; v[1] = n.y; v[2] = n.z;
}

bg_status bgi_camera_derive(bg_scene *scene, const char *where, const bg_camera *c, bg_camera_data *out)
{
    bg_status st = bgi_validate_camera(scene, where, c);
    if (st != BG_OK)
        return st;
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
    out->orthographic = c->projection == BG_PROJECTION_ORTHOGRAPHIC;
    out->half_y = out->orthographic ? c->half_height : tan(c->fov_y_degrees * (3.14159265358979323846 / 360.0));
    double to_look = bgi_vec3_length(bg_vec3_make(c->look_at.x - c->position.x, c->look_at.y - c->position.y,
                                                  c->look_at.z - c->position.z));
    out->focus = c->focus_distance > 0.0 ? c->focus_distance : to_look;
    return BG_OK;
}

static bool shows_shape(const bg_light *l);
static void light_shape_item(const bg_light *l, bg_object_item *out);

bg_status bgi_light_derive(bg_scene *scene, const char *where, const bg_light *in, bg_light *out)
{
    bg_status st = bgi_validate_light(scene, where, in);
    if (st != BG_OK)
        return st;
    *out = *in;
    /* A sphere of radius 0 is the point light, so that it renders as one bit for bit. */
    if (in->type == BG_LIGHT_SPHERE && in->radius == 0.0)
        out->type = BG_LIGHT_POINT;
    /* A zero direction is unused (a point light without a cone); keep the committed state
     * normalised anyway. bgi_vec3_normalize also takes directions whose length overflows. */
    bg_vec3 d = bgi_vec3_length(in->direction) == 0.0 ? bg_vec3_make(0, -1, 0) : in->direction;
    out->direction = bgi_vec3_normalize(d);
    /* A visible light's shape is checked here, as an object would be when added, so that a shape
     * no renderer can draw (edges of 1e-120 or 1e200, a 1000 x 1e-4 strip) is refused by the call
     * that set it, rather than failing every later commit. */
    if (shows_shape(out)) {
        bg_object_item item;
        bg_object_data shape;
        light_shape_item(out, &item);
        st = bgi_object_derive_shape(scene, where, in->type == BG_LIGHT_SPHERE ? "visible shape (radius)"
                                                                                : "visible shape (edge_u, edge_v)",
                                     &item, &shape);
    }
    return st;
}

/* Grows the committed arrays to the live counts, and the commit's own arrays; after each step the
 * committed pointers follow the (possibly moved) storage, whose contents realloc kept, so the old
 * committed state stays readable on failure. */
/* Whether a light is drawn: a visible area light with a shape (a sphere of radius 0 is a point). */
static bool shows_shape(const bg_light *l)
{
    return l->visible && ((l->type == BG_LIGHT_SPHERE && l->radius >= 1e-100) || l->type == BG_LIGHT_RECTANGLE);
}

/* The object a visible area light shows (bg_light.visible): a sphere of its radius, or the
 * rectangle of its edges, casting no shadow. */
static void light_shape_item(const bg_light *l, bg_object_item *out)
{
    memset(out, 0, sizeof *out);
    bool sphere = l->type == BG_LIGHT_SPHERE;
    out->desc = bg_object_desc_init(sphere ? BG_SHAPE_SPHERE : BG_SHAPE_RECTANGLE, 0);
    out->desc.casts_shadows = false;
    if (sphere) {
        out->desc.transform = bg_mat4_mul(bg_mat4_translate(l->position.x, l->position.y, l->position.z),
                                          bg_mat4_scale(l->radius, l->radius, l->radius));
    } else {
        /* The prototype square [-1, 1]^2 of y = 0 onto the parallelogram: x along edge_u / 2, z
         * along edge_v / 2, y along their unit normal times the shorter half edge. */
        bg_vec3 u = l->edge_u, v = l->edge_v;
        bg_vec3 n = bgi_vec3_normalize(bg_vec3_make(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z,
                                                    u.x * v.y - u.y * v.x));
        double lu = bgi_vec3_length(u), lv = bgi_vec3_length(v), k = 0.5 * (lu < lv ? lu : lv);
        const double cols[3][3] = {{0.5 * u.x, 0.5 * u.y, 0.5 * u.z}, {k * n.x, k * n.y, k * n.z},
                                   {0.5 * v.x, 0.5 * v.y, 0.5 * v.z}};
        const double c[3] = {l->position.x + 0.5 * (u.x + v.x), l->position.y + 0.5 * (u.y + v.y),
                             l->position.z + 0.5 * (u.z + v.z)};
        out->desc.transform = bg_mat4_identity();
        for (int r = 0; r < 3; r++) {
            for (int j = 0; j < 3; j++)
                out->desc.transform.m[r][j] = cols[j][r];
            out->desc.transform.m[r][3] = c[r];
        }
    }
}

/* The pending visible area lights: each adds an object and its material at commit. */
static uint32_t light_shapes(const bg_scene *s)
{
    uint32_t n = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->lights); slot++)
        if (bgi_pool_live(&s->lights, slot))
            n += shows_shape(bgi_pool_item(&s->lights, slot)) ? 1u : 0u;
    return n;
}

static bg_status reserve_all(bg_scene *s)
{
    uint32_t shapes = light_shapes(s);
    struct {
        bg_array *committed, *derived;
        const void **pointer;
        uint32_t count;
        size_t elem;
    } lists[] = {
        {&s->c_objects, &s->p_objects, (const void **)&s->state.objects, s->objects.live + shapes, sizeof(bg_object_data)},
        {&s->c_materials, &s->p_materials, (const void **)&s->state.materials, s->materials.live + shapes,
         sizeof(bg_material)},
        {&s->c_lights, &s->p_lights, (const void **)&s->state.lights, s->lights.live, sizeof(bg_light)},
        {&s->c_textures, &s->p_textures, (const void **)&s->state.textures, s->textures.live, sizeof(bg_texture_data)},
    };
    bg_status st;
    for (size_t i = 0; i < sizeof lists / sizeof lists[0]; i++) {
        if ((st = bgi_array_reserve(s, lists[i].committed, lists[i].count, lists[i].elem, where_commit)) != BG_OK)
            return st;
        *lists[i].pointer = lists[i].committed->data;
        if ((st = bgi_array_reserve(s, lists[i].derived, lists[i].count, lists[i].elem, where_commit)) != BG_OK)
            return st;
    }
    if ((st = bgi_array_reserve(s, &s->material_map, bgi_pool_slot_count(&s->materials), sizeof(uint32_t),
                               where_commit)) != BG_OK)
        return st;
    return bgi_array_reserve(s, &s->texture_map, bgi_pool_slot_count(&s->textures), sizeof(uint32_t), where_commit);
}

static void item_where(char *where, size_t size, const char *kind, const bg_pool *pool, uint32_t slot)
{
    char text[BG_HANDLE_TEXT_SIZE];
    snprintf(where, size, "%s: %s %s", where_commit, kind, bgi_handle_text(bgi_pool_id(pool, slot), text));
}

static bg_status derive_textures(bg_scene *s)
{
    bg_texture_data *out = s->p_textures.data;
    uint32_t *map = s->texture_map.data, k = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->textures); slot++) {
        if (!bgi_pool_live(&s->textures, slot))
            continue;
        const bg_texture_data *t = bgi_pool_item(&s->textures, slot);
        if ((!t->texels && !t->bytes) || t->width <= 0 || t->height <= 0) {
            char where[64];
            item_where(where, sizeof where, "texture", &s->textures, slot);
            return bgi_scene_fail(s, BG_ERR_INVALID_ARGUMENT, "%s has no texels", where);
        }
        map[slot] = k;
        out[k++] = *t;
    }
    s->p_textures.count = k;
    return BG_OK;
}

/* Materials keep their public form, but their texture handles become dense 1-based indices. */
static bg_status derive_materials(bg_scene *s)
{
    bg_material *out = s->p_materials.data;
    const uint32_t *texture_map = s->texture_map.data;
    uint32_t *map = s->material_map.data, k = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->materials); slot++) {
        if (!bgi_pool_live(&s->materials, slot))
            continue;
        char where[64];
        item_where(where, sizeof where, "material", &s->materials, slot);
        const bg_material *m = bgi_pool_item(&s->materials, slot);
        bg_status st = bgi_validate_material(s, where, m);
        if (st != BG_OK)
            return st;
        bg_material *c = &out[k];
        *c = *m;
#define TRANSLATE(field)         \
    if (c->field.texture != 0) \
        c->field.texture = texture_map[bgi_handle_slot(c->field.texture)] + 1;
        BG_MATERIAL_TEXTURES(TRANSLATE)
#undef TRANSLATE
        map[slot] = k++;
    }
    s->p_materials.count = k;
    return BG_OK;
}

static bg_status derive_lights(bg_scene *s)
{
    bg_light *out = s->p_lights.data;
    uint32_t k = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->lights); slot++) {
        if (!bgi_pool_live(&s->lights, slot))
            continue;
        char where[64];
        item_where(where, sizeof where, "light", &s->lights, slot);
        bg_status st = bgi_light_derive(s, where, bgi_pool_item(&s->lights, slot), &out[k++]);
        if (st != BG_OK)
            return st;
    }
    s->p_lights.count = k;
    return BG_OK;
}

static bg_status derive_objects(bg_scene *s)
{
    bg_object_data *out = s->p_objects.data;
    const uint32_t *material_map = s->material_map.data;
    uint32_t k = 0, meshes = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->objects); slot++) {
        if (!bgi_pool_live(&s->objects, slot))
            continue;
        char where[64];
        item_where(where, sizeof where, "object", &s->objects, slot);
        bg_status st = bgi_object_derive(s, where, "transform", bgi_pool_item(&s->objects, slot), &out[k]);
        if (st != BG_OK)
            return st;
        out[k].material = material_map[out[k].material];
        meshes += out[k].mesh != NULL;
        k++;
    }
    s->p_objects.count = k;
    s->p_mesh_objects = meshes;
    return BG_OK;
}

/* Each visible area light's shape (bg_light.visible), after the caller's objects and materials: an
 * emissive black material and a sphere or rectangle object that casts no shadow. */
static bg_status derive_light_shapes(bg_scene *s)
{
    bg_object_data *objects = s->p_objects.data;
    bg_material *materials = s->p_materials.data;
    const bg_light *lights = s->p_lights.data;
    for (uint32_t i = 0; i < s->p_lights.count; i++) {
        const bg_light *l = &lights[i];
        if (!shows_shape(l))
            continue;
        bg_material m = bg_material_init();
        m.base.reflectance = (bg_color_param){0, 0, 0, 0};
        m.ambient = (bg_color_param){0, 0, 0, 0};
        m.emission = (bg_color_param){l->color[0] * l->intensity, l->color[1] * l->intensity,
                                      l->color[2] * l->intensity, 0};
        uint32_t material = s->p_materials.count++;
        materials[material] = m;
        bg_object_item item;
        light_shape_item(l, &item);
        char where[64];
        snprintf(where, sizeof where, "%s: the shape of visible light %u", where_commit, (unsigned)i);
        uint32_t k = s->p_objects.count;
        bg_status st = bgi_object_derive_shape(s, where, "transform", &item, &objects[k]);
        if (st != BG_OK)
            return st;
        objects[k].material = material;
        objects[k].light = i + 1;
        s->p_objects.count++;
    }
    return BG_OK;
}

/* Copies one derived array over its committed one. */
static uint32_t install(bg_array *committed, const bg_array *derived, size_t elem)
{
    if (derived->count)
        memcpy(committed->data, derived->data, (size_t)derived->count * elem);
    committed->count = derived->count;
    return derived->count;
}

static void install_bounds(bg_scene_state *state)
{
    state->has_bounded_objects = false;
    for (int i = 0; i < 3; i++) {
        state->bounds_min[i] = 0;
        state->bounds_max[i] = 0;
    }
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_object_data *o = &state->objects[i];
        if (!o->bounded)
            continue;
        for (int k = 0; k < 3; k++) {
            if (!state->has_bounded_objects || o->bounds_min[k] < state->bounds_min[k])
                state->bounds_min[k] = o->bounds_min[k];
            if (!state->has_bounded_objects || o->bounds_max[k] > state->bounds_max[k])
                state->bounds_max[k] = o->bounds_max[k];
        }
        state->has_bounded_objects = true;
    }
}

/* Scenes may commit on several threads at once; C99 has no atomics. */
static pthread_mutex_t serial_lock = PTHREAD_MUTEX_INITIALIZER;
static uint64_t last_serial;

uint64_t bgi_scene_next_serial(void)
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
    bg_camera_data camera;
    bg_status st = reserve_all(scene);
    if (st == BG_OK)
        st = bgi_camera_derive(scene, "bg_scene_commit: camera", &scene->camera, &camera);
    if (st == BG_OK)
        st = bgi_validate_color3(scene, where_commit, "ambient", scene->ambient);
    if (st == BG_OK)
        st = derive_textures(scene);
    if (st == BG_OK)
        st = derive_materials(scene);
    if (st == BG_OK)
        st = derive_lights(scene);
    if (st == BG_OK)
        st = derive_objects(scene);
    if (st == BG_OK)
        st = derive_light_shapes(scene);
    if (st == BG_OK)
        st = bgi_scene_tree_prepare(scene);
    if (st != BG_OK)
        return st;
    char gpu_range[BGI_GPU_RANGE_NOTE_SIZE];
    bgi_gpu_range_note(scene, &camera, gpu_range, sizeof gpu_range);

    bg_scene_state *state = &scene->state;
    state->object_count = install(&scene->c_objects, &scene->p_objects, sizeof(bg_object_data));
    state->material_count = install(&scene->c_materials, &scene->p_materials, sizeof(bg_material));
    state->light_count = install(&scene->c_lights, &scene->p_lights, sizeof(bg_light));
    state->texture_count = install(&scene->c_textures, &scene->p_textures, sizeof(bg_texture_data));
    state->objects = scene->c_objects.data;
    state->materials = scene->c_materials.data;
    state->lights = scene->c_lights.data;
    state->textures = scene->c_textures.data;
    install_bounds(state);
    state->mesh_object_count = scene->p_mesh_objects;
    state->camera = camera;
    memcpy(state->gpu_range, gpu_range, sizeof gpu_range);
    memcpy(state->ambient, scene->ambient, sizeof state->ambient);
    bgi_environment_commit(scene, scene->texture_map.data, &state->environment);
    state->distribution = camera.camera.aperture_radius > 0.0 || (state->environment.on && state->environment.lights);
    for (uint32_t k = 0; k < state->light_count; k++)
        state->distribution |= state->lights[k].type == BG_LIGHT_SPHERE || state->lights[k].type == BG_LIGHT_RECTANGLE;
    for (uint32_t k = 0; k < state->material_count; k++)
        state->distribution |= state->materials[k].glossy;
    bgi_scene_tree_install(scene);
    state->commit_count++;
    state->serial = bgi_scene_next_serial();
    scene->committed = true;
    /* No committed state holds the texels of textures removed before this commit any more. */
    void **retired = scene->retired_texels.data;
    for (uint32_t i = 0; i < scene->retired_texels.count; i++)
        bgi_free(&scene->allocator, retired[i]);
    scene->retired_texels.count = 0;
    bgi_mesh_free_retired(scene);
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
