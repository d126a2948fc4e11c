/* "lights": an array of the fields of bg_light, type "point" (default), "directional", "sphere" or
 * "rectangle". An area light is placed by a key named for its shape, as an object is
 * ({"sphere": {"center", "radius"}}, {"rectangle": {"corner", "edge_u", "edge_v"}}), so that each
 * point of the file says which light's place it is; the key gives the type, and "position", the
 * place of a point light, may not stand beside it. */
#include "scenefile_internal.h"

/* In bg_light_type's order: a name's index is its type. */
static const char *const types[] = {"point", "directional", "sphere", "rectangle", NULL};

/* The shape key's object into l (whose type is already the shape's). */
static bg_status read_area(bgi_sf_ctx *ctx, const cJSON *v, bg_light *l)
{
    static const char *const sphere_keys[] = {"center", "radius", NULL};
    static const char *const rectangle_keys[] = {"corner", "edge_u", "edge_v", NULL};
    static const bgi_sf_range radius = {0.0, 1e100, false, false};
    if (l->type == BG_LIGHT_SPHERE) {
        BGI_SF_TRY(bgi_sf_check_object(ctx, v, sphere_keys));
        BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "center", &l->position));
        return bgi_sf_field_number(ctx, v, "radius", radius, &l->radius);
    }
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, rectangle_keys));
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "corner", &l->position));
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "edge_u", &l->edge_u));
    return bgi_sf_field_vec3(ctx, v, "edge_v", &l->edge_v);
}

/* The type, from "type" and the shape key together; *shape gets the key's name (NULL: none). */
static bg_status read_type(bgi_sf_ctx *ctx, const cJSON *v, bg_light *l, const char **shape)
{
    bool sphere = bgi_sf_member(v, "sphere") != NULL, rectangle = bgi_sf_member(v, "rectangle") != NULL;
    if (sphere && rectangle)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT,
                           "has two shapes, \"sphere\" and \"rectangle\" (one per light)");
    *shape = sphere ? "sphere" : rectangle ? "rectangle" : NULL;
    if (*shape && bgi_sf_member(v, "position"))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "has both \"position\" and \"%s\": a %s light is placed by "
                           "\"%s.%s\"", *shape, *shape, *shape, sphere ? "center" : "corner");
    int type = *shape ? (sphere ? BG_LIGHT_SPHERE : BG_LIGHT_RECTANGLE) : (int)l->type;
    int given = type;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "type", types, &given));
    if (given != type && *shape) {
        size_t at = bgi_sf_push_key(ctx, "type");
        bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "\"%s\" does not match the \"%s\" key (leave "
                                   "\"type\" out, or make it \"%s\")", types[given], *shape, *shape);
        bgi_sf_pop(ctx, at);
        return st;
    }
    if (!*shape && (given == BG_LIGHT_SPHERE || given == BG_LIGHT_RECTANGLE))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "type \"%s\" needs a \"%s\" key to place it (%s)",
                           types[given], types[given],
                           given == BG_LIGHT_SPHERE ? "{\"center\": vec3, \"radius\": number}"
                                                    : "{\"corner\": vec3, \"edge_u\": vec3, \"edge_v\": vec3}");
    l->type = (bg_light_type)given;
    return BG_OK;
}

static bg_status read_light(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"type", "position", "sphere", "rectangle", "direction", "color", "intensity",
                                       "attenuation", "spot_cutoff_degrees", "spot_exponent", "visible", NULL};
    static const bgi_sf_range cutoff = {0.0, 180.0, true, false};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    bg_light l = bg_light_init();
    const char *shape = NULL;
    BGI_SF_TRY(read_type(ctx, v, &l, &shape));
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "position", &l.position));
    if (shape) {
        size_t at = bgi_sf_push_key(ctx, shape);
        bg_status st = read_area(ctx, bgi_sf_member(v, shape), &l);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "direction", &l.direction));
    BGI_SF_TRY(bgi_sf_field_rgb(ctx, v, "color", bgi_sf_nonneg, l.color));
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "intensity", bgi_sf_nonneg, &l.intensity));
    const cJSON *a = bgi_sf_member(v, "attenuation");
    if (a) {
        size_t at = bgi_sf_push_key(ctx, "attenuation");
        bg_status st = bgi_sf_numbers(ctx, a, 3, bgi_sf_nonneg, l.attenuation);
        if (st == BG_OK && l.attenuation[0] == 0 && l.attenuation[1] == 0 && l.attenuation[2] == 0)
            st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must not be all zero (constant, linear, quadratic)");
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "spot_cutoff_degrees", cutoff, &l.spot_cutoff_degrees));
    if (l.spot_cutoff_degrees != 180.0 && (l.spot_cutoff_degrees > 90.0 || l.type == BG_LIGHT_RECTANGLE)) {
        size_t at = bgi_sf_push_key(ctx, "spot_cutoff_degrees");
        bg_status st = l.type == BG_LIGHT_RECTANGLE
                           ? bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be 180: a rectangle light has no spot "
                                         "cone (got %g)", l.spot_cutoff_degrees)
                           : bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be in (0, 90], or 180 for no cone "
                                         "(got %g)", l.spot_cutoff_degrees);
        bgi_sf_pop(ctx, at);
        return st;
    }
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "spot_exponent", bgi_sf_nonneg, &l.spot_exponent));
    BGI_SF_TRY(bgi_sf_field_bool(ctx, v, "visible", &l.visible));
    if (l.visible && !shape) {
        size_t at = bgi_sf_push_key(ctx, "visible");
        bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "only an area light (\"sphere\" or \"rectangle\") "
                                   "has a shape to show");
        bgi_sf_pop(ctx, at);
        return st;
    }
    uint32_t handle;
    bg_status st = bg_scene_add_light(ctx->scene, &l, &handle);
    if (st != BG_OK) {
        /* All a rectangle light can still be refused for is its shape (edges zero or parallel, or a
         * far corner beyond the double range): the message points into "rectangle". */
        bool rect = l.type == BG_LIGHT_RECTANGLE;
        size_t at = rect ? bgi_sf_push_key(ctx, "rectangle") : ctx->path_len;
        st = bgi_sf_scene_fail(ctx, st, "the light");
        bgi_sf_pop(ctx, at);
        return st;
    }
    ctx->out->summary.lights++;
    return BG_OK;
}

bg_status bgi_sf_read_lights(bgi_sf_ctx *ctx, const cJSON *v)
{
    if (!cJSON_IsArray(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an array of lights (got %s)", bgi_sf_type_name(v));
    size_t i = 0;
    for (const cJSON *l = v->child; l; l = l->next, i++) {
        size_t at = bgi_sf_push_index(ctx, i);
        bg_status st = read_light(ctx, l);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    ctx->out->lights_from_file = true;
    return BG_OK;
}
