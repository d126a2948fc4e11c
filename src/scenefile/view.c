/* The view sections: camera, image and settings. They fill the result; the loader sets the camera
 * and ambient light on the scene once everything is read, so a bad later key changes nothing. */
#include "scenefile_internal.h"

#include <math.h>

bg_status bgi_sf_read_camera(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"position", "look_at", "up", "fov_y", "aperture_radius", "focus_distance",
                                       "projection", "half_height", NULL};
    static const char *const projections[] = {"perspective", "orthographic", NULL};
    static const bgi_sf_range fov = {0.0, 180.0, true, true};
    static const bgi_sf_range half_height = {1e-100, 1e100, false, false};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    bg_camera *c = &ctx->out->camera;
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "position", &c->position));
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "look_at", &c->look_at));
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "up", &c->up));
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "fov_y", fov, &c->fov_y_degrees));
    /* The thin lens: 0 is the pinhole and "in focus at look_at", the library's own zeros. */
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "aperture_radius", bgi_sf_nonneg, &c->aperture_radius));
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "focus_distance", bgi_sf_nonneg, &c->focus_distance));
    int projection = (int)c->projection;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "projection", projections, &projection));
    c->projection = (bg_projection)projection;
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "half_height", half_height, &c->half_height));
    ctx->out->camera_from_file = true;
    return BG_OK;
}

bg_status bgi_sf_read_image(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"width", "height", "samples", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    bg_scenefile_image *im = &ctx->out->image;
    BGI_SF_TRY(bgi_sf_field_int(ctx, v, "width", 1, BG_MAX_IMAGE_SIDE, &im->width));
    BGI_SF_TRY(bgi_sf_field_int(ctx, v, "height", 1, BG_MAX_IMAGE_SIDE, &im->height));
    return bgi_sf_field_int(ctx, v, "samples", 1, BG_MAX_SAMPLES, &im->samples);
}

bg_status bgi_sf_read_settings(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"max_depth", "background", "ambient", "encoding", "environment",
                                       "integrator", "path_ambient", NULL};
    static const char *const encodings[] = {"srgb", "linear", NULL};
    /* In bg_integrator's order: the index is the value. */
    static const char *const integrators[] = {"whitted", "path", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    bg_render_settings *s = &ctx->out->settings;
    BGI_SF_TRY(bgi_sf_field_int(ctx, v, "max_depth", 0, BG_MAX_DEPTH, &s->max_depth));
    int integrator = (int)s->integrator;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "integrator", integrators, &integrator));
    s->integrator = (bg_integrator)integrator;
    /* Read whatever the integrator: a caller that switches to path later (the command's
       --integrator) gets the file's wish with it. */
    BGI_SF_TRY(bgi_sf_field_bool(ctx, v, "path_ambient", &s->path_ambient));
    BGI_SF_TRY(bgi_sf_field_rgb(ctx, v, "background", bgi_sf_nonneg, s->background));
    BGI_SF_TRY(bgi_sf_field_rgb(ctx, v, "ambient", bgi_sf_nonneg, ctx->out->ambient));
    int e = (int)s->encoding;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "encoding", encodings, &e));
    s->encoding = (bg_output_encoding)e;
    const cJSON *env = bgi_sf_member(v, "environment");
    if (!env)
        return BG_OK;
    size_t at = bgi_sf_push_key(ctx, "environment");
    bg_status st = bgi_sf_read_environment(ctx, env);
    bgi_sf_pop(ctx, at);
    return st;
}
