/* Lights: defaults, add and replace. */
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
    bg_status st = bgi_validate_light(scene, where, light);
    if (st == BG_OK)
        st = bgi_array_reserve(scene, &scene->lights, scene->lights.count + 1, sizeof(bg_light), where);
    if (st != BG_OK)
        return st;
    ((bg_light *)scene->lights.data)[scene->lights.count++] = *light;
    *out_light = scene->lights.count;
    return BG_OK;
}

bg_status bg_scene_set_light(bg_scene *scene, uint32_t light, const bg_light *values)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t index;
    bg_status st = bgi_scene_handle(scene, "bg_scene_set_light", "light", light, scene->lights.count, &index);
    if (st != BG_OK)
        return st;
    if (!values)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "bg_scene_set_light: values is NULL");
    char where[64];
    snprintf(where, sizeof where, "bg_scene_set_light: light %u", light);
    st = bgi_validate_light(scene, where, values);
    if (st != BG_OK)
        return st;
    ((bg_light *)scene->lights.data)[index] = *values;
    return BG_OK;
}
