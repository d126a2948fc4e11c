/* Scene lifetime, the sticky first error, arrays, the camera and the ambient light. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "scene_private.h"

/* Before the scene exists its failures can only go to the desc's logger. */
static bg_status create_fail(const bg_scene_desc *d, bg_status status, const char *message)
{
    if (d->logger.func)
        d->logger.func(BG_LOG_ERROR, message, d->logger.user);
    return status;
}

bg_status bg_scene_create(const bg_scene_desc *desc, bg_scene **out_scene)
{
    bg_scene_desc d;
    memset(&d, 0, sizeof d);
    if (desc)
        d = *desc;
    if (!out_scene)
        return create_fail(&d, BG_ERR_INVALID_ARGUMENT, "bg_scene_create: out_scene is NULL");
    *out_scene = NULL;
    if (!bgi_allocator_valid(&d.allocator))
        return create_fail(&d, BG_ERR_INVALID_ARGUMENT, "bg_scene_create: allocator must set alloc and free "
                                                        "together (realloc is optional), or nothing");
    bg_scene *s = bgi_alloc(&d.allocator, sizeof *s);
    if (!s)
        return create_fail(&d, BG_ERR_OUT_OF_MEMORY, "bg_scene_create: out of memory");
    memset(s, 0, sizeof *s);
    s->allocator = d.allocator;
    s->logger = d.logger;
    bgi_pool_init(&s->objects, "object", "an object", sizeof(bg_object_item));
    bgi_pool_init(&s->materials, "material", "a material", sizeof(bg_material));
    bgi_pool_init(&s->lights, "light", "a light", sizeof(bg_light));
    bgi_pool_init(&s->textures, "texture", "a texture", sizeof(bg_texture_data));
    s->camera = bg_camera_init();
    s->ambient[0] = s->ambient[1] = s->ambient[2] = 1.0;
    s->environment = bg_environment_init();
    *out_scene = s;
    return BG_OK;
}

void bg_scene_destroy(bg_scene *scene)
{
    if (!scene)
        return;
    for (uint32_t i = 0; i < bgi_pool_slot_count(&scene->textures); i++) {
        if (!bgi_pool_live(&scene->textures, i))
            continue;
        bg_texture_data *t = bgi_pool_item(&scene->textures, i);
        bgi_free(&scene->allocator, t->texels);
        bgi_free(&scene->allocator, t->bytes);
    }
    void **retired = scene->retired_texels.data;
    for (uint32_t i = 0; i < scene->retired_texels.count; i++)
        bgi_free(&scene->allocator, retired[i]);
    for (uint32_t i = 0; i < bgi_pool_slot_count(&scene->objects); i++)
        if (bgi_pool_live(&scene->objects, i))
            bgi_mesh_unref(scene, ((bg_object_item *)bgi_pool_item(&scene->objects, i))->mesh);
    bgi_mesh_free_retired(scene);
    bg_pool *pools[] = {&scene->objects, &scene->materials, &scene->lights, &scene->textures};
    for (size_t i = 0; i < sizeof pools / sizeof pools[0]; i++)
        bgi_pool_release(scene, pools[i]);
    bg_array *arrays[] = {&scene->retired_texels, &scene->c_objects, &scene->c_materials, &scene->c_lights,
                          &scene->c_textures, &scene->p_objects, &scene->p_materials, &scene->p_lights,
                          &scene->p_textures, &scene->material_map, &scene->texture_map};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        bgi_array_release(scene, arrays[i]);
    bgi_scene_tree_release(scene);
    bgi_environment_release(scene);
    bg_allocator a = scene->allocator;
    bgi_free(&a, scene);
}

bg_status bg_scene_error(const bg_scene *scene)
{
    return scene ? (bg_status)scene->error.status : BG_ERR_INVALID_ARGUMENT;
}

const char *bg_scene_error_message(const bg_scene *scene)
{
    return scene ? scene->error.message : "scene is NULL";
}

void bg_scene_clear_error(bg_scene *scene)
{
    if (!scene)
        return;
    macs_first_error_clear(&scene->error);
}

bg_status bgi_scene_fail(bg_scene *scene, bg_status status, const char *format, ...)
{
    if (!scene)
        return status;
    char buffer[BG_MESSAGE_SIZE];
    va_list args;
    va_start(args, format);
    const char *message = macs_first_error_vrecord(&scene->error, status, buffer, NULL, format, args);
    va_end(args);
    if (scene->logger.func)
        scene->logger.func(BG_LOG_ERROR, message, scene->logger.user);
    return status;
}

bg_status bgi_array_reserve(bg_scene *scene, bg_array *array, uint32_t need, size_t elem,
                           const char *where)
{
    if (need <= array->capacity)
        return BG_OK;
    if (need > BG_MAX_ITEMS)
        return bgi_scene_fail(scene, BG_ERR_LIMIT, "%s: more than %u items", where, BG_MAX_ITEMS);
    uint32_t cap = array->capacity ? array->capacity : 4;
    while (cap < need)
        cap = cap > BG_MAX_ITEMS / 2 ? BG_MAX_ITEMS : cap * 2;
    void *p = bgi_realloc(&scene->allocator, array->data, (size_t)array->capacity * elem,
                         (size_t)cap * elem);
    if (!p)
        return bgi_scene_fail(scene, BG_ERR_OUT_OF_MEMORY, "%s: out of memory growing to %u items",
                             where, cap);
    array->data = p;
    array->capacity = cap;
    return BG_OK;
}

void bgi_array_release(bg_scene *scene, bg_array *array)
{
    bgi_free(&scene->allocator, array->data);
    memset(array, 0, sizeof *array);
}

bg_camera bg_camera_init(void)
{
    bg_camera c;
    /* Padding too (after projection): a caller may compare cameras with memcmp. */
    memset(&c, 0, sizeof c);
    c.position = bg_vec3_make(0, 0, 5);
    c.look_at = bg_vec3_make(0, 0, 0);
    c.up = bg_vec3_make(0, 1, 0);
    c.fov_y_degrees = 45.0;
    c.aperture_radius = 0.0;
    c.focus_distance = 0.0;
    c.projection = BG_PROJECTION_PERSPECTIVE;
    c.half_height = 1.0;
    return c;
}

bg_status bg_scene_set_camera(bg_scene *scene, const bg_camera *camera)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!camera)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "bg_scene_set_camera: camera is NULL");
    bg_camera_data derived;
    bg_status st = bgi_camera_derive(scene, "bg_scene_set_camera", camera, &derived);
    if (st != BG_OK)
        return st;
    scene->camera = *camera;
    return BG_OK;
}

bg_status bg_scene_set_ambient(bg_scene *scene, const double rgb[3])
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!rgb)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "bg_scene_set_ambient: rgb is NULL");
    bg_status st = bgi_validate_color3(scene, "bg_scene_set_ambient", "rgb", rgb);
    if (st != BG_OK)
        return st;
    memcpy(scene->ambient, rgb, sizeof scene->ambient);
    return BG_OK;
}
