/* Materials: defaults, add and replace. */
#include <stdio.h>
#include <string.h>

#include "scene_private.h"

static bg_color_param color(double r, double g, double b)
{
    bg_color_param c = {r, g, b, 0};
    return c;
}

static bg_scalar_param scalar(double v)
{
    bg_scalar_param s = {v, 0, 0};
    return s;
}

bg_material bg_material_init(void)
{
    bg_material m;
    memset(&m, 0, sizeof m);
    m.base.reflectance = color(0.8, 0.8, 0.8);
    m.base.roughness = scalar(1.0);
    m.base.isotropy = scalar(1.0);
    /* An unused but sensible coat, so setting has_coat alone gives a clear glossy varnish. */
    m.has_coat = false;
    m.coat.reflectance = color(0.04, 0.04, 0.04);
    m.coat.roughness = scalar(0.1);
    m.coat.isotropy = scalar(1.0);
    m.ambient = color(0.1, 0.1, 0.1);
    m.emission = color(0, 0, 0);
    m.transparency = scalar(0.0);
    m.ior = 1.5;
    return m;
}

bg_status bg_scene_add_material(bg_scene *scene, const bg_material *material, uint32_t *out_material)
{
    static const char where[] = "bg_scene_add_material";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!material)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: material is NULL", where);
    if (!out_material)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_material is NULL", where);
    bg_status st = bgi_validate_material(scene, where, material, scene->textures.count);
    if (st == BG_OK)
        st = bgi_array_reserve(scene, &scene->materials, scene->materials.count + 1, sizeof(bg_material), where);
    if (st != BG_OK)
        return st;
    ((bg_material *)scene->materials.data)[scene->materials.count++] = *material;
    *out_material = scene->materials.count;
    return BG_OK;
}

bg_status bg_scene_set_material(bg_scene *scene, uint32_t material, const bg_material *values)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t index;
    bg_status st = bgi_scene_handle(scene, "bg_scene_set_material", "material", material,
                                   scene->materials.count, &index);
    if (st != BG_OK)
        return st;
    if (!values)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "bg_scene_set_material: values is NULL");
    char where[64];
    snprintf(where, sizeof where, "bg_scene_set_material: material %u", material);
    st = bgi_validate_material(scene, where, values, scene->textures.count);
    if (st != BG_OK)
        return st;
    ((bg_material *)scene->materials.data)[index] = *values;
    return BG_OK;
}
