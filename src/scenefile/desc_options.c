/* What bg_scenefile_desc asks of a load beyond the file: checked before the file is read, so that a
 * bad value is named as the caller's field rather than found halfway; the model's up axis as a
 * rotation; the caller's camera parts (its place, field of view and lens) over the chosen camera. */
#include "scenefile_internal.h"

#include <math.h>
#include <string.h>

static bool finite3(const bg_vec3 *v)
{
    return isfinite(v->x) && isfinite(v->y) && isfinite(v->z);
}

bg_status bgi_sf_check_desc(bgi_sf_ctx *ctx, const bg_scenefile_desc *d, bool model)
{
    if (!d)
        return BG_OK;
    if ((int)d->up_axis < 0 || d->up_axis >= BG_SCENEFILE_UP_COUNT_)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->up_axis: %d is no bg_scenefile_up", (int)d->up_axis);
    if (!(d->smooth_angle_degrees >= 0 && d->smooth_angle_degrees <= 180))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->smooth_angle_degrees: must be in [0, 180] (got %g)",
                           d->smooth_angle_degrees);
    if (d->camera < BG_SCENEFILE_CAMERA_FRAME)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->camera: must be a camera number from 1, 0 or "
                           "BG_SCENEFILE_CAMERA_FRAME (got %d)", d->camera);
    if (d->fov_y_degrees != 0 && !(d->fov_y_degrees > 0 && d->fov_y_degrees < 180))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->fov_y_degrees: must be 0 or in (0, 180) (got %g)",
                           d->fov_y_degrees);
    if (d->look_from && !finite3(d->look_from))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->look_from: must be finite");
    if (d->look_at && !finite3(d->look_at))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->look_at: must be finite");
    if (d->aperture_radius && !(*d->aperture_radius >= 0 && isfinite(*d->aperture_radius)))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->aperture_radius: must be finite and >= 0 (got %g)",
                           *d->aperture_radius);
    if (d->focus_distance && !(*d->focus_distance >= 0 && isfinite(*d->focus_distance)))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "desc->focus_distance: must be finite and >= 0 (got %g)",
                           *d->focus_distance);
    /* A JSON scene places each of its meshes itself ("transform", "normals") and has one camera. */
    const char *model_only = d->up_axis ? "desc->up_axis" : d->smooth_angle_degrees ? "desc->smooth_angle_degrees"
                             : d->camera                ? "desc->camera"
                                                        : NULL;
    if (!model && model_only)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "%s: applies to model files only (a JSON scene gives its "
                           "meshes a \"transform\" and \"normals\", and has one \"camera\")", model_only);
    return BG_OK;
}

/* Exact quarter turns written out rather than computed from sines, so that a turned model's
 * coordinates are its file's, exchanged and negated, without rounding. */
bg_mat4 bgi_sf_up_transform(bg_scenefile_up up)
{
    bg_mat4 m = bg_mat4_identity();
    double c = 1, s = 0; /* the turn about x: y' = c y - s z, z' = s y + c z */
    if (up == BG_SCENEFILE_UP_Z)
        c = 0, s = -1;
    else if (up == BG_SCENEFILE_UP_NEG_Z)
        c = 0, s = 1;
    else if (up == BG_SCENEFILE_UP_NEG_Y)
        c = -1, s = 0;
    m.m[1][1] = c;
    m.m[1][2] = -s;
    m.m[2][1] = s;
    m.m[2][2] = c;
    return m;
}

static bool same_point(bg_vec3 a, bg_vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

bg_status bgi_sf_apply_view(bgi_sf_ctx *ctx, const bg_scenefile_desc *d)
{
    if (!d)
        return BG_OK;
    bg_camera *c = &ctx->out->camera;
    /* An orthographic view has no angle to widen; taking the value silently would leave the user's
     * option without effect. */
    if (d->fov_y_degrees != 0 && c->projection == BG_PROJECTION_ORTHOGRAPHIC)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT,
                           "desc->fov_y_degrees: the camera is orthographic (half_height %g), and a field of "
                           "view applies to a perspective camera only",
                           c->half_height);
    if (d->fov_y_degrees != 0)
        c->fov_y_degrees = d->fov_y_degrees;
    if (d->look_from)
        c->position = *d->look_from;
    if (d->look_at)
        c->look_at = *d->look_at;
    if (d->aperture_radius)
        c->aperture_radius = *d->aperture_radius;
    if (d->focus_distance)
        c->focus_distance = *d->focus_distance;
    if (!d->look_from && !d->look_at)
        return BG_OK;
    const char *field = d->look_from && d->look_at ? "desc->look_from and desc->look_at"
                        : d->look_from             ? "desc->look_from"
                                                   : "desc->look_at";
    const char *other = d->look_from && d->look_at ? "" : " (the other from the file's camera)";
    if (same_point(c->position, c->look_at))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "%s: the camera at (%g, %g, %g) would look at its own "
                           "position%s", field, c->position.x, c->position.y, c->position.z, other);
    bg_vec3 v = bg_vec3_make(c->look_at.x - c->position.x, c->look_at.y - c->position.y, c->look_at.z - c->position.z);
    bg_vec3 u = c->up;
    bg_vec3 x = bg_vec3_make(v.y * u.z - v.z * u.y, v.z * u.x - v.x * u.z, v.x * u.y - v.y * u.x);
    if (x.x == 0 && x.y == 0 && x.z == 0)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "%s: the view from (%g, %g, %g) to (%g, %g, %g) runs along "
                           "the camera's up (%g, %g, %g); look from a little aside", field, c->position.x,
                           c->position.y, c->position.z, c->look_at.x, c->look_at.y, c->look_at.z, u.x, u.y, u.z);
    return BG_OK;
}
