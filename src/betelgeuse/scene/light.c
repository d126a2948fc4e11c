/* Lights: defaults, add, replace and remove. */
#include <stdio.h>
#include <string.h>

#include "scene_private.h"

bg_light bg_light_init(void)
{
    bg_light l;
    memset(&l, 0, sizeof l);
    l.type = BG_LIGHT_POINT;
    l.position = bg_vec3_make(0, 0, 0);
    /* Straight down: a usable spot axis or sun direction if the caller only changes the type. */
    l.direction = bg_vec3_make(0, -1, 0);
    l.color[0] = l.color[1] = l.color[2] = 1.0;
    l.intensity = 1.0;
    l.attenuation[0] = 1.0;
    l.spot_cutoff_degrees = 180.0;
    l.spot_exponent = 0.0;
    l.radius = 0.0;
    l.edge_u = bg_vec3_make(1, 0, 0);
    l.edge_v = bg_vec3_make(0, 0, 1);
    l.visible = false;
    return l;
}

bg_status bg_scene_add_light(bg_scene *scene, const bg_light *light, uint32_t *out_light)
{
    static const char where[] = "bg_scene_add_light";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!light)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: light is NULL", where);
    if (!out_light)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_light is NULL", where);
    bg_light derived;
    bg_status st = bgi_light_derive(scene, where, light, &derived);
    if (st != BG_OK)
        return st;
    return bgi_pool_add(scene, &scene->lights, where, light, out_light);
}

bg_status bg_scene_set_light(bg_scene *scene, uint32_t light, const bg_light *values)
{
    static const char call[] = "bg_scene_set_light";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->lights, call, "light", light, &slot);
    if (st != BG_OK)
        return st;
    if (!values)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: values is NULL", call);
    char where[64], text[BG_HANDLE_TEXT_SIZE];
    snprintf(where, sizeof where, "%s: light %s", call, bgi_handle_text(light, text));
    bg_light derived;
    st = bgi_light_derive(scene, where, values, &derived);
    if (st != BG_OK)
        return st;
    *(bg_light *)bgi_pool_item(&scene->lights, slot) = *values;
    return BG_OK;
}

bg_status bg_scene_remove_light(bg_scene *scene, uint32_t light)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->lights, "bg_scene_remove_light", "light", light, &slot);
    if (st != BG_OK)
        return st;
    bgi_pool_remove(&scene->lights, slot);
    return BG_OK;
}
