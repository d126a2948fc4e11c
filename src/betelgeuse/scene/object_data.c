/* What a commit derives for one object (bg_object_data), and the one check of it. Add,
 * set_transform and commit all go through bgi_object_derive, so an object the API accepted is one
 * commit accepts: everything commit stores is computed here and checked finite here. */
#include <float.h>
#include <math.h>

#include "../common/affine.h"
#include "../common/shapes.h"
#include "scene_private.h"

/* The mapping BG_UV_DEFAULT resolves to, from each shape's row of common/shapes.h. */
static bg_uv_mapping default_uv(bg_shape shape)
{
#define DEFAULT_UV_OF(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = default_uv,
    static const bg_uv_mapping uv[BG_SHAPE_COUNT_] = {BG_SHAPES(DEFAULT_UV_OF)};
#undef DEFAULT_UV_OF
    return uv[shape];
}

/* Half extents along one world axis of the transformed prototype, from that axis's row (a b c)
 * of the linear part. For the box and rectangle this equals transforming their corners; for the
 * sphere and cylinder it is the exact (tighter) extent of the transformed surface. The squares
 * stay in range for an accepted transform: its entries are at most 1.8 BG_AFFINE_MAX_SCALE, and
 * its rows (bounded below by the scale and singularity limits) are longer than 1e-113, so an entry
 * whose square underflows changes no extent. */
static double sphere_extent(double a, double b, double c)
{
    return sqrt(a * a + b * b + c * c);
}

static double box_extent(double a, double b, double c)
{
    return fabs(a) + fabs(b) + fabs(c);
}

static double cylinder_extent(double a, double b, double c)
{
    return fabs(b) + sqrt(a * a + c * c);
}

static double rectangle_extent(double a, double b, double c)
{
    (void)b; /* the prototype is flat in y */
    return fabs(a) + fabs(c);
}

typedef double (*half_extent_fn)(double a, double b, double c);
#define HALF_EXTENT_OF(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = half_extent,
static const half_extent_fn shape_half_extent[BG_SHAPE_COUNT_] = {BG_SHAPES(HALF_EXTENT_OF)};
#undef HALF_EXTENT_OF

/* World box of a mesh object: its object-space box's 8 corners transformed in double, each
 * coordinate padded outward as world_box pads (by a few ulps of the terms it is summed from), so
 * that rounding never cuts a triangle. */
static void mesh_world_box(const bg_mesh_data *mesh, const bg_mat4 *transform, double lo[3], double hi[3])
{
    const double (*m)[4] = transform->m;
    for (int i = 0; i < 3; i++) {
        lo[i] = DBL_MAX;
        hi[i] = -DBL_MAX;
    }
    for (int c = 0; c < 8; c++) {
        const double p[3] = {(c & 1) ? mesh->box_max[0] : mesh->box_min[0],
                             (c & 2) ? mesh->box_max[1] : mesh->box_min[1],
                             (c & 4) ? mesh->box_max[2] : mesh->box_min[2]};
        for (int i = 0; i < 3; i++) {
            double v = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3];
            double mag = fabs(m[i][0] * p[0]) + fabs(m[i][1] * p[1]) + fabs(m[i][2] * p[2]) + fabs(m[i][3]);
            double pad = 8.0 * DBL_EPSILON * mag;
            if (v - pad < lo[i])
                lo[i] = v - pad;
            if (v + pad > hi[i])
                hi[i] = v + pad;
        }
    }
}

/* World box of the object: for a bounded prototype, centre the translation and half extent per
 * axis from the shape, padded by a few ulps so rounding never cuts the object; unbounded shapes
 * get the whole double range. Returns whether the shape is bounded. */
static bool world_box(const bg_object_desc *desc, double lo[3], double hi[3])
{
    half_extent_fn half_extent = shape_half_extent[desc->shape];
    const double (*m)[4] = desc->transform.m;
    for (int i = 0; i < 3; i++) {
        if (!half_extent) {
            lo[i] = -DBL_MAX;
            hi[i] = DBL_MAX;
            continue;
        }
        double e = half_extent(m[i][0], m[i][1], m[i][2]);
        double t = m[i][3];
        e += 8.0 * DBL_EPSILON * (fabs(t) + e);
        lo[i] = t - e;
        hi[i] = t + e;
    }
    return half_extent != NULL;
}

bg_status bgi_object_derive(bg_scene *scene, const char *where, const char *transform_field,
                           const bg_object_item *item, bg_object_data *o)
{
    uint32_t material;
    bg_status st = bgi_validate_object_fields(scene, where, &item->desc, item->mesh != NULL, &material);
    if (st == BG_OK)
        st = bgi_object_derive_shape(scene, where, transform_field, item, o);
    if (st == BG_OK)
        o->material = material;
    return st;
}

bg_status bgi_object_derive_shape(bg_scene *scene, const char *where, const char *transform_field,
                                  const bg_object_item *item, bg_object_data *o)
{
    const bg_object_desc *d = &item->desc;
    double scale;
    bg_affine_check c = bgi_affine_inverse(&d->transform, o->to_object, &scale);
    if (c == BG_AFFINE_SCALE)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: %s %s: it is %g", where, transform_field,
                             bgi_affine_check_string(c), scale);
    if (c != BG_AFFINE_OK)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: %s %s", where, transform_field,
                             bgi_affine_check_string(c));
    if (item->mesh) {
        mesh_world_box(item->mesh, &d->transform, o->bounds_min, o->bounds_max);
        o->bounded = true;
    } else {
        o->bounded = world_box(d, o->bounds_min, o->bounds_max);
    }
    for (int i = 0; i < 3; i++)
        if (!isfinite(o->bounds_min[i]) || !isfinite(o->bounds_max[i]))
            return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT,
                                 "%s: %s puts the world box beyond the double range (axis %d: translation %g)",
                                 where, transform_field, i, d->transform.m[i][3]);
    o->shape = d->shape;
    o->mesh = item->mesh;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            o->to_world[i][j] = d->transform.m[i][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            o->normal_to_world[i][j] = o->to_object[j][i];
    /* A mesh has its own texture coordinates; its mapping is never read. */
    o->uv_mapping = item->mesh ? BG_UV_PLANAR : d->uv_mapping == BG_UV_DEFAULT ? default_uv(d->shape) : d->uv_mapping;
    o->uv_scale[0] = d->uv_scale[0];
    o->uv_scale[1] = d->uv_scale[1];
    o->casts_shadows = d->casts_shadows;
    o->light = 0; /* the commit names the light of a visible light's own object */
    return BG_OK;
}
