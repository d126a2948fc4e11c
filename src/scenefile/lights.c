/* "lights": an array of the fields of bg_light, type "point" (default) or "directional". */
#include "scenefile_internal.h"

static bg_status read_light(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"type", "position", "direction", "color", "intensity", "attenuation",
                                       "spot_cutoff_degrees", "spot_exponent", NULL};
    static const char *const types[] = {"point", "directional", NULL};
    static const bgi_sf_range cutoff = {0.0, 180.0, true, false};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    bg_light l = bg_light_init();
    int type = (int)l.type;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "type", types, &type));
    l.type = (bg_light_type)type;
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "position", &l.position));
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
    if (l.spot_cutoff_degrees > 90.0 && l.spot_cutoff_degrees != 180.0) {
        size_t at = bgi_sf_push_key(ctx, "spot_cutoff_degrees");
        bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be in (0, 90], or 180 for no cone (got %g)",
                                   l.spot_cutoff_degrees);
        bgi_sf_pop(ctx, at);
        return st;
    }
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "spot_exponent", bgi_sf_nonneg, &l.spot_exponent));
    uint32_t handle;
    bg_status st = bg_scene_add_light(ctx->scene, &l, &handle);
    if (st != BG_OK)
        return bgi_sf_scene_fail(ctx, st, "the light");
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
