/* Object transforms: a list of steps applied in order (the first one applies to the prototype
 * first), or a single step. The product is formed as a builder in C writes it,
 * bg_mat4_mul(last, ... bg_mat4_mul(second, first)), so a scene file and its C builder give the same
 * bits; a lone step is its own matrix, never multiplied by an identity. */
#include "scenefile_internal.h"

#include <math.h>
#include <string.h>

static bg_status read_matrix(bgi_sf_ctx *ctx, const cJSON *v, bg_mat4 *out)
{
    int rows = cJSON_IsArray(v) ? cJSON_GetArraySize(v) : 0;
    if (rows != 3 && rows != 4)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT,
                           "must be an array of 4 rows (or 3, the last row 0 0 0 1 implied) of 4 numbers (got %s%s)",
                           bgi_sf_type_name(v), cJSON_IsArray(v) ? " of another length" : "");
    bg_mat4 m = bg_mat4_identity();
    int r = 0;
    for (const cJSON *row = v->child; row; row = row->next, r++) {
        size_t at = bgi_sf_push_index(ctx, (size_t)r);
        bg_status st = bgi_sf_numbers(ctx, row, 4, bgi_sf_any, m.m[r]);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    *out = m;
    return BG_OK;
}

static bg_status read_rotate(bgi_sf_ctx *ctx, const cJSON *v, bg_mat4 *out)
{
    static const char *const keys[] = {"axis", "degrees", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    if (!bgi_sf_member(v, "axis") || !bgi_sf_member(v, "degrees"))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "needs both \"axis\" and \"degrees\"");
    bg_vec3 axis;
    double degrees = 0.0;
    BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "axis", &axis));
    if (axis.x == 0 && axis.y == 0 && axis.z == 0) {
        size_t at = bgi_sf_push_key(ctx, "axis");
        bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must not be zero");
        bgi_sf_pop(ctx, at);
        return st;
    }
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "degrees", bgi_sf_any, &degrees));
    *out = bg_mat4_rotate(axis, degrees);
    return BG_OK;
}

static bg_status read_step(bgi_sf_ctx *ctx, const cJSON *v, bg_mat4 *out)
{
    static const char *const keys[] = {"translate", "rotate", "scale", "matrix", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    if (cJSON_GetArraySize(v) != 1)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT,
                           "a step must hold exactly one of \"translate\", \"rotate\", \"scale\", \"matrix\" (got %d keys)",
                           cJSON_GetArraySize(v));
    const cJSON *s = v->child;
    size_t at = bgi_sf_push_key(ctx, s->string);
    bg_status st = BG_OK;
    if (strcmp(s->string, "translate") == 0) {
        bg_vec3 t;
        st = bgi_sf_vec3(ctx, s, &t);
        *out = bg_mat4_translate(t.x, t.y, t.z);
    } else if (strcmp(s->string, "scale") == 0) {
        double k[3];
        st = bgi_sf_rgb(ctx, s, bgi_sf_any, k);
        if (st == BG_OK && (k[0] == 0 || k[1] == 0 || k[2] == 0))
            st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must not be zero along any axis (got %g, %g, %g)", k[0],
                             k[1], k[2]);
        *out = bg_mat4_scale(k[0], k[1], k[2]);
    } else if (strcmp(s->string, "rotate") == 0) {
        st = read_rotate(ctx, s, out);
    } else {
        st = read_matrix(ctx, s, out);
    }
    bgi_sf_pop(ctx, at);
    return st;
}

bg_status bgi_sf_read_transform(bgi_sf_ctx *ctx, const cJSON *v, bg_mat4 *out)
{
    if (cJSON_IsObject(v))
        return read_step(ctx, v, out);
    if (!cJSON_IsArray(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an array of steps or one step (got %s)",
                           bgi_sf_type_name(v));
    bg_mat4 m = bg_mat4_identity();
    size_t i = 0;
    for (const cJSON *s = v->child; s; s = s->next, i++) {
        bg_mat4 step;
        size_t at = bgi_sf_push_index(ctx, i);
        bg_status st = read_step(ctx, s, &step);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
        m = i == 0 ? step : bg_mat4_mul(step, m);
    }
    *out = m;
    return BG_OK;
}

bg_vec3 bgi_sf_normalize(bg_vec3 v)
{
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (m == 0.0 || !isfinite(m))
        return v;
    double x = v.x / m, y = v.y / m, z = v.z / m;
    double l = sqrt(x * x + y * y + z * z);
    return bg_vec3_make(x / l, y / l, z / l);
}

/* The rule of bg_scene_add_plane (docs/shading.md): prototype y becomes n; x is world x projected
 * onto the plane, or world z when n is near the x axis; z is x cross n. */
bg_mat4 bgi_sf_plane_frame(bg_vec3 n)
{
    bg_vec3 r = fabs(n.x) < 0.9 ? bg_vec3_make(1, 0, 0) : bg_vec3_make(0, 0, 1);
    double d = r.x * n.x + r.y * n.y + r.z * n.z;
    bg_vec3 u = bg_vec3_make(r.x - d * n.x, r.y - d * n.y, r.z - d * n.z);
    double m = fmax(fabs(u.x), fmax(fabs(u.y), fabs(u.z)));
    double ux = u.x / m, uy = u.y / m, uz = u.z / m;
    double ul = m * sqrt(ux * ux + uy * uy + uz * uz);
    u.x /= ul; u.y /= ul; u.z /= ul;
    bg_vec3 w = bg_vec3_make(u.y * n.z - u.z * n.y, u.z * n.x - u.x * n.z, u.x * n.y - u.y * n.x);
    bg_mat4 f = bg_mat4_identity();
    double cols[3][3] = {{u.x, u.y, u.z}, {n.x, n.y, n.z}, {w.x, w.y, w.z}};
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++)
            f.m[row][c] = cols[c][row];
    return f;
}
