/* Materials: defaults, add, replace and remove (refused while an object uses the material). */
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
    m.coverage = (bg_scalar_param){1.0, 0, 3};
    m.coverage_cutoff = 0.0;
    m.sides = BG_SIDES_SOLID;
    m.glossy = false;
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
    bg_status st = bgi_validate_material(scene, where, material);
    if (st != BG_OK)
        return st;
    return bgi_pool_add(scene, &scene->materials, where, material, out_material);
}

bg_status bg_scene_set_material(bg_scene *scene, uint32_t material, const bg_material *values)
{
    static const char call[] = "bg_scene_set_material";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->materials, call, "material", material, &slot);
    if (st != BG_OK)
        return st;
    if (!values)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: values is NULL", call);
    char where[64], text[BG_HANDLE_TEXT_SIZE];
    snprintf(where, sizeof where, "%s: material %s", call, bgi_handle_text(material, text));
    st = bgi_validate_material(scene, where, values);
    if (st != BG_OK)
        return st;
    *(bg_material *)bgi_pool_item(&scene->materials, slot) = *values;
    return BG_OK;
}

bg_status bg_scene_remove_material(bg_scene *scene, uint32_t material)
{
    static const char where[] = "bg_scene_remove_material";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->materials, where, "material", material, &slot);
    if (st != BG_OK)
        return st;
    /* An object keeps its material's id, so the material must outlive every object using it. */
    for (uint32_t o = 0; o < bgi_pool_slot_count(&scene->objects); o++) {
        const bg_object_desc *d = &((const bg_object_item *)bgi_pool_item(&scene->objects, o))->desc;
        if (!bgi_pool_live(&scene->objects, o) || d->material != material)
            continue;
        char m_text[BG_HANDLE_TEXT_SIZE], o_text[BG_HANDLE_TEXT_SIZE];
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT,
                             "%s: material %s is used by object %s (remove the object first)", where,
                             bgi_handle_text(material, m_text), bgi_handle_text(bgi_pool_id(&scene->objects, o), o_text));
    }
    bgi_pool_remove(&scene->materials, slot);
    return BG_OK;
}
