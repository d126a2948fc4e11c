/* "materials": name -> the fields of bg_material with the same names. A colour or scalar property is
 * a constant, or {"value": constant, "texture": name} (scalars also "channel"), whose value defaults
 * to 1 so that {"texture": "earth"} alone shows the texture as it is. */
#include "scenefile_internal.h"

static bg_status texture_ref(bgi_sf_ctx *ctx, const cJSON *obj, uint32_t *out)
{
    const cJSON *t = bgi_sf_member(obj, "texture");
    if (!t)
        return BG_OK;
    size_t at = bgi_sf_push_key(ctx, "texture");
    const char *name = NULL;
    bg_status st = bgi_sf_string(ctx, t, &name);
    if (st == BG_OK) {
        *out = bgi_sf_names_find(&ctx->textures, name);
        if (!*out)
            st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "no texture is named \"%s\" in \"textures\"", name);
    }
    bgi_sf_pop(ctx, at);
    return st;
}

static bg_status color_param(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bg_color_param *p)
{
    static const char *const keys[] = {"value", "texture", NULL};
    const cJSON *v = bgi_sf_member(obj, key);
    if (!v)
        return BG_OK;
    size_t at = bgi_sf_push_key(ctx, key);
    double rgb[3] = {p->r, p->g, p->b};
    bg_status st;
    if (cJSON_IsObject(v)) {
        rgb[0] = rgb[1] = rgb[2] = 1.0;
        p->texture = 0;
        st = bgi_sf_check_object(ctx, v, keys);
        if (st == BG_OK)
            st = bgi_sf_field_rgb(ctx, v, "value", bgi_sf_nonneg, rgb);
        if (st == BG_OK)
            st = texture_ref(ctx, v, &p->texture);
    } else {
        st = bgi_sf_rgb(ctx, v, bgi_sf_nonneg, rgb);
        if (st == BG_OK)
            p->texture = 0;
    }
    bgi_sf_pop(ctx, at);
    p->r = rgb[0];
    p->g = rgb[1];
    p->b = rgb[2];
    return st;
}

static bg_status scalar_param(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bg_scalar_param *p)
{
    static const char *const keys[] = {"value", "texture", "channel", NULL};
    const cJSON *v = bgi_sf_member(obj, key);
    if (!v)
        return BG_OK;
    size_t at = bgi_sf_push_key(ctx, key);
    bg_status st;
    if (cJSON_IsObject(v)) {
        p->value = 1.0;
        p->texture = 0; /* p->channel keeps its default: 0, or the alpha channel for coverage */
        st = bgi_sf_check_object(ctx, v, keys);
        if (st == BG_OK)
            st = bgi_sf_field_number(ctx, v, "value", bgi_sf_unit, &p->value);
        if (st == BG_OK)
            st = bgi_sf_field_int(ctx, v, "channel", 0, 3, &p->channel);
        if (st == BG_OK)
            st = texture_ref(ctx, v, &p->texture);
    } else {
        if (!cJSON_IsNumber(v))
            st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be a number or {\"value\", \"texture\", \"channel\"} (got %s)",
                             bgi_sf_type_name(v));
        else
            st = bgi_sf_number(ctx, v, bgi_sf_unit, &p->value);
        if (st == BG_OK)
            p->texture = 0;
    }
    bgi_sf_pop(ctx, at);
    return st;
}

static bg_status layer(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bg_schlick_layer *l, bool *present)
{
    static const char *const keys[] = {"reflectance", "roughness", "isotropy", NULL};
    const cJSON *v = bgi_sf_member(obj, key);
    if (!v)
        return BG_OK;
    if (present)
        *present = true;
    size_t at = bgi_sf_push_key(ctx, key);
    bg_status st = bgi_sf_check_object(ctx, v, keys);
    if (st == BG_OK)
        st = color_param(ctx, v, "reflectance", &l->reflectance);
    if (st == BG_OK)
        st = scalar_param(ctx, v, "roughness", &l->roughness);
    if (st == BG_OK)
        st = scalar_param(ctx, v, "isotropy", &l->isotropy);
    bgi_sf_pop(ctx, at);
    return st;
}

static bg_status read_material(bgi_sf_ctx *ctx, const cJSON *v, const char *name)
{
    static const char *const keys[] = {"base", "coat", "ambient", "emission", "transparency", "ior",
                                       "coverage", "coverage_cutoff", "sides", "glossy", NULL};
    static const char *const sides[] = {"solid", "front", "both", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    bg_material m = bg_material_init();
    BGI_SF_TRY(layer(ctx, v, "base", &m.base, NULL));
    BGI_SF_TRY(layer(ctx, v, "coat", &m.coat, &m.has_coat));
    BGI_SF_TRY(color_param(ctx, v, "ambient", &m.ambient));
    BGI_SF_TRY(color_param(ctx, v, "emission", &m.emission));
    BGI_SF_TRY(scalar_param(ctx, v, "transparency", &m.transparency));
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "ior", bgi_sf_positive, &m.ior));
    BGI_SF_TRY(scalar_param(ctx, v, "coverage", &m.coverage));
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "coverage_cutoff", bgi_sf_unit, &m.coverage_cutoff));
    int s = (int)m.sides;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "sides", sides, &s));
    m.sides = (bg_mesh_sides)s;
    BGI_SF_TRY(bgi_sf_field_bool(ctx, v, "glossy", &m.glossy));
    uint32_t handle;
    bg_status st = bg_scene_add_material(ctx->scene, &m, &handle);
    if (st != BG_OK)
        return bgi_sf_scene_fail(ctx, st, "the material");
    ctx->out->summary.materials++;
    return bgi_sf_names_add(ctx, &ctx->materials, name, handle);
}

bg_status bgi_sf_read_materials(bgi_sf_ctx *ctx, const cJSON *v)
{
    if (!cJSON_IsObject(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an object of name: material (got %s)",
                           bgi_sf_type_name(v));
    for (const cJSON *m = v->child; m; m = m->next) {
        size_t at = bgi_sf_push_key(ctx, m->string);
        bg_status st = bgi_sf_names_find(&ctx->materials, m->string)
                           ? bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "the material name is given twice")
                           : read_material(ctx, m, m->string);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    return BG_OK;
}
