/* Field-by-field validation. Each message names the call (or commit and the item), the field
 * and the offending value, so a caller can fix the first bad field without a debugger. */
#include <math.h>
#include <stdio.h>

#include "../common/affine.h"
#include "scene_private.h"

#define FAIL(...) bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, __VA_ARGS__)

/* Cosine of the angle below which the up vector counts as parallel to the view (about 0.06 deg). */
#define BG_UP_PARALLEL_SIN 1e-3

static bool finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static bg_status vec3_finite(bg_scene *scene, const char *where, const char *field, bg_vec3 v)
{
    if (!bgi_vec3_finite(v))
        return FAIL("%s: %s = (%g, %g, %g) is not finite", where, field, v.x, v.y, v.z);
    return BG_OK;
}

bg_status bgi_validate_camera(bg_scene *scene, const char *where, const bg_camera *c)
{
    bg_status st;
    if ((st = vec3_finite(scene, where, "position", c->position)) != BG_OK ||
        (st = vec3_finite(scene, where, "look_at", c->look_at)) != BG_OK ||
        (st = vec3_finite(scene, where, "up", c->up)) != BG_OK)
        return st;
    if (!(c->fov_y_degrees > 0.0 && c->fov_y_degrees < 180.0))
        return FAIL("%s: fov_y_degrees = %g is outside (0, 180)", where, c->fov_y_degrees);
    bg_vec3 f = bg_vec3_make(c->look_at.x - c->position.x, c->look_at.y - c->position.y,
                             c->look_at.z - c->position.z);
    if (!bgi_vec3_finite(f))
        return FAIL("%s: look_at - position overflows", where);
    if (bgi_vec3_length(f) == 0.0)
        return FAIL("%s: look_at equals position (%g, %g, %g)", where, c->position.x,
                    c->position.y, c->position.z);
    if (bgi_vec3_length(c->up) == 0.0)
        return FAIL("%s: up = (0, 0, 0) is zero", where);
    /* Normalised as commit derives the basis (bgi_camera_derive): lengths that overflow are fine. */
    f = bgi_vec3_normalize(f);
    bg_vec3 u = bgi_vec3_normalize(c->up);
    bg_vec3 x = bg_vec3_make(f.y * u.z - f.z * u.y, f.z * u.x - f.x * u.z, f.x * u.y - f.y * u.x);
    if (bgi_vec3_length(x) < BG_UP_PARALLEL_SIN)
        return FAIL("%s: up = (%g, %g, %g) is parallel to the view direction", where, c->up.x,
                    c->up.y, c->up.z);
    if (!isfinite(c->aperture_radius) || c->aperture_radius < 0.0)
        return FAIL("%s: aperture_radius = %g must be finite and >= 0", where, c->aperture_radius);
    if (!isfinite(c->focus_distance) || c->focus_distance < 0.0)
        return FAIL("%s: focus_distance = %g must be finite and >= 0 (0: the distance to look_at)", where,
                    c->focus_distance);
    if (c->projection != BG_PROJECTION_PERSPECTIVE && c->projection != BG_PROJECTION_ORTHOGRAPHIC)
        return FAIL("%s: projection = %d is neither BG_PROJECTION_PERSPECTIVE nor BG_PROJECTION_ORTHOGRAPHIC", where,
                    (int)c->projection);
    if (c->projection == BG_PROJECTION_ORTHOGRAPHIC) {
        if (!(c->half_height >= 1e-100 && c->half_height <= 1e100))
            return FAIL("%s: half_height = %g of an orthographic camera is outside [1e-100, 1e100]", where,
                        c->half_height);
        /* A thin lens focuses rays that leave one point; parallel rays have no such point. */
        if (c->aperture_radius > 0.0)
            return FAIL("%s: aperture_radius = %g: depth of field needs a perspective camera, and this one is "
                        "orthographic", where, c->aperture_radius);
    }
    return BG_OK;
}

bg_status bgi_validate_color3(bg_scene *scene, const char *where, const char *field, const double rgb[3])
{
    if (!finite3(rgb))
        return FAIL("%s: %s = (%g, %g, %g) is not finite", where, field, rgb[0], rgb[1], rgb[2]);
    if (rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0)
        return FAIL("%s: %s = (%g, %g, %g) has a negative component", where, field, rgb[0], rgb[1], rgb[2]);
    return BG_OK;
}

static bg_status color_param(bg_scene *scene, const char *where, const char *field,
                             const bg_color_param *p)
{
    double rgb[3] = {p->r, p->g, p->b};
    if (!finite3(rgb))
        return FAIL("%s: %s = (%g, %g, %g) is not finite", where, field, p->r, p->g, p->b);
    if (p->r < 0 || p->g < 0 || p->b < 0)
        return FAIL("%s: %s = (%g, %g, %g) has a negative component", where, field, p->r, p->g, p->b);
    return BG_OK;
}

/* A scalar parameter in [0, 1] (unit) or just finite and positive (not unit). */
static bg_status scalar_param(bg_scene *scene, const char *where, const char *field,
                              const bg_scalar_param *p)
{
    if (!isfinite(p->value))
        return FAIL("%s: %s.value = %g is not finite", where, field, p->value);
    if (p->value < 0.0 || p->value > 1.0)
        return FAIL("%s: %s.value = %g is outside [0, 1]", where, field, p->value);
    if (p->channel < 0 || p->channel > 3)
        return FAIL("%s: %s.channel = %d is outside 0..3", where, field, p->channel);
    return BG_OK;
}

static bg_status layer(bg_scene *scene, const char *where, const char *name, const bg_schlick_layer *l)
{
    char field[64];
    bg_status st;
    snprintf(field, sizeof field, "%s.reflectance", name);
    if ((st = color_param(scene, where, field, &l->reflectance)) != BG_OK)
        return st;
    snprintf(field, sizeof field, "%s.roughness", name);
    if ((st = scalar_param(scene, where, field, &l->roughness)) != BG_OK)
        return st;
    snprintf(field, sizeof field, "%s.isotropy", name);
    return scalar_param(scene, where, field, &l->isotropy);
}

bg_status bgi_validate_material(bg_scene *scene, const char *where, const bg_material *m)
{
    bg_status st;
    /* The coat is checked even when unused, so a committed material never holds garbage. */
    if ((st = layer(scene, where, "base", &m->base)) != BG_OK ||
        (st = layer(scene, where, "coat", &m->coat)) != BG_OK ||
        (st = color_param(scene, where, "ambient", &m->ambient)) != BG_OK ||
        (st = color_param(scene, where, "emission", &m->emission)) != BG_OK ||
        (st = scalar_param(scene, where, "transparency", &m->transparency)) != BG_OK ||
        (st = scalar_param(scene, where, "coverage", &m->coverage)) != BG_OK)
        return st;
    if ((int)m->sides < 0 || m->sides >= BG_SIDES_COUNT_)
        return FAIL("%s: sides = %d is not a bg_mesh_sides", where, (int)m->sides);
    if (!(m->coverage_cutoff >= 0.0 && m->coverage_cutoff <= 1.0))
        return FAIL("%s: coverage_cutoff = %g must be in [0, 1]", where, m->coverage_cutoff);
    if (!isfinite(m->ior) || m->ior <= 0.0)
        return FAIL("%s: ior = %g must be finite and > 0", where, m->ior);
    uint32_t slot;
#define TEXTURE_REF(field)                                                                              \
    if (m->field.texture != 0 &&                                                                        \
        (st = bgi_pool_lookup(scene, &scene->textures, where, #field ".texture", m->field.texture, &slot)) != BG_OK) \
        return st;
    BG_MATERIAL_TEXTURES(TEXTURE_REF)
#undef TEXTURE_REF
    return BG_OK;
}

bg_status bgi_validate_light(bg_scene *scene, const char *where, const bg_light *l)
{
    bg_status st;
    if ((int)l->type < 0 || l->type >= BG_LIGHT_TYPE_COUNT_)
        return FAIL("%s: type = %d is not a bg_light_type", where, (int)l->type);
    if ((st = vec3_finite(scene, where, "position", l->position)) != BG_OK ||
        (st = vec3_finite(scene, where, "direction", l->direction)) != BG_OK ||
        (st = bgi_validate_color3(scene, where, "color", l->color)) != BG_OK)
        return st;
    if (!isfinite(l->intensity) || l->intensity < 0.0)
        return FAIL("%s: intensity = %g must be finite and >= 0", where, l->intensity);
    const double *a = l->attenuation;
    if (!finite3(a))
        return FAIL("%s: attenuation = (%g, %g, %g) is not finite", where, a[0], a[1], a[2]);
    if (a[0] < 0 || a[1] < 0 || a[2] < 0)
        return FAIL("%s: attenuation = (%g, %g, %g) has a negative term", where, a[0], a[1], a[2]);
    if (a[0] == 0 && a[1] == 0 && a[2] == 0)
        return FAIL("%s: attenuation = (0, 0, 0) must not be all zero", where);
    double cut = l->spot_cutoff_degrees;
    if (!(cut == 180.0 || (cut > 0.0 && cut <= 90.0)))
        return FAIL("%s: spot_cutoff_degrees = %g is outside (0, 90] and not 180", where, cut);
    if (!isfinite(l->spot_exponent) || l->spot_exponent < 0.0)
        return FAIL("%s: spot_exponent = %g must be finite and >= 0", where, l->spot_exponent);
    if (l->type == BG_LIGHT_SPHERE && !(l->radius >= 0.0 && l->radius <= 1e100))
        return FAIL("%s: radius = %g of the sphere light must be finite and in [0, 1e100]", where, l->radius);
    if (l->type == BG_LIGHT_RECTANGLE) {
        if ((st = vec3_finite(scene, where, "edge_u", l->edge_u)) != BG_OK ||
            (st = vec3_finite(scene, where, "edge_v", l->edge_v)) != BG_OK)
            return st;
        /* On unit vectors, so that no length in the double range overflows the test. */
        double lu = bgi_vec3_length(l->edge_u), lv = bgi_vec3_length(l->edge_v);
        bg_vec3 u = lu > 0.0 ? bgi_vec3_normalize(l->edge_u) : l->edge_u;
        bg_vec3 v = lv > 0.0 ? bgi_vec3_normalize(l->edge_v) : l->edge_v;
        bg_vec3 n = bg_vec3_make(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
        if (!(bgi_vec3_length(n) >= 1e-12))
            return FAIL("%s: edge_u = (%g, %g, %g) and edge_v = (%g, %g, %g) of the rectangle light are zero or "
                        "parallel", where, l->edge_u.x, l->edge_u.y, l->edge_u.z, l->edge_v.x, l->edge_v.y,
                        l->edge_v.z);
        if (!bgi_vec3_finite(bg_vec3_make(l->position.x + l->edge_u.x + l->edge_v.x,
                                          l->position.y + l->edge_u.y + l->edge_v.y,
                                          l->position.z + l->edge_u.z + l->edge_v.z)))
            return FAIL("%s: position + edge_u + edge_v of the rectangle light overflows", where);
        if (cut != 180.0)
            return FAIL("%s: spot_cutoff_degrees = %g: a rectangle light has no spot cone (180)", where, cut);
    }
    bool needs_direction = l->type == BG_LIGHT_DIRECTIONAL || cut != 180.0;
    if (needs_direction && bgi_vec3_length(l->direction) == 0.0)
        return FAIL("%s: direction = (0, 0, 0) is zero but the %s needs it", where,
                    l->type == BG_LIGHT_DIRECTIONAL ? "directional light" : "spot cone");
    return BG_OK;
}

bg_status bgi_validate_object_fields(bg_scene *scene, const char *where, const bg_object_desc *d, bool mesh,
                                    uint32_t *out_material_slot)
{
    if (mesh ? d->shape != BGI_SHAPE_MESH : (int)d->shape < 0 || d->shape >= BG_SHAPE_COUNT_)
        return FAIL("%s: shape = %d is not a bg_shape", where, (int)d->shape);
    if ((int)d->uv_mapping < 0 || d->uv_mapping >= BG_UV_COUNT_)
        return FAIL("%s: uv_mapping = %d is not a bg_uv_mapping", where, (int)d->uv_mapping);
    for (int i = 0; i < 2; i++)
        if (!isfinite(d->uv_scale[i]) || d->uv_scale[i] <= 0.0)
            return FAIL("%s: uv_scale[%d] = %g must be finite and > 0", where, i, d->uv_scale[i]);
    return bgi_pool_lookup(scene, &scene->materials, where, "material", d->material, out_material_slot);
}
