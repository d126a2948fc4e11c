/* Objects: defaults, add, the sphere and plane shorthands, moving and removing an object. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../common/affine.h"
#include "scene_private.h"

bg_object_desc bg_object_desc_init(bg_shape shape, uint32_t material)
{
    bg_object_desc d;
    memset(&d, 0, sizeof d);
    d.shape = shape;
    d.transform = bg_mat4_identity();
    d.material = material;
    d.uv_mapping = BG_UV_DEFAULT;
    d.uv_scale[0] = d.uv_scale[1] = 1.0;
    d.casts_shadows = true;
    return d;
}

/* The one check commit runs too (bgi_object_derive), so an added object never blocks a commit. */
static bg_status add(bg_scene *scene, const char *where, const char *transform_field, const bg_object_desc *desc,
                     uint32_t *out_object)
{
    bg_object_item item = {*desc, NULL};
    bg_object_data derived;
    bg_status st = bgi_object_derive(scene, where, transform_field, &item, &derived);
    if (st != BG_OK)
        return st;
    return bgi_pool_add(scene, &scene->objects, where, &item, out_object);
}

bg_status bg_scene_add_object(bg_scene *scene, const bg_object_desc *desc, uint32_t *out_object)
{
    static const char where[] = "bg_scene_add_object";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!desc)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: desc is NULL", where);
    if (!out_object)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_object is NULL", where);
    return add(scene, where, "transform", desc, out_object);
}

bg_status bg_scene_add_sphere(bg_scene *scene, bg_vec3 center, double radius, uint32_t material,
                              uint32_t *out_object)
{
    static const char where[] = "bg_scene_add_sphere";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!out_object)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_object is NULL", where);
    if (!bgi_vec3_finite(center))
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: center = (%g, %g, %g) is not finite",
                             where, center.x, center.y, center.z);
    if (!isfinite(radius) || radius <= 0.0)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: radius = %g must be finite and > 0",
                             where, radius);
    /* The radius is the transform's overall scale: name it rather than a transform the caller never saw. */
    if (radius < BG_AFFINE_MIN_SCALE || radius > BG_AFFINE_MAX_SCALE)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT,
                             "%s: radius = %g is outside " BG_AFFINE_SCALE_RANGE
                             ", the overall scale an object may have",
                             where, radius);
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_SPHERE, material);
    d.transform = bg_mat4_mul(bg_mat4_translate(center.x, center.y, center.z),
                              bg_mat4_scale(radius, radius, radius));
    return add(scene, where, "transform (from center and radius)", &d, out_object);
}

/* The plane's prototype axes in world space: y becomes the normal n; x (the planar u axis) is
 * world x projected onto the plane, or world z when n is within about 25 degrees of the x axis;
 * z (the planar v axis) is x cross n, keeping the frame right-handed. A floor (n = +y) thus gets
 * the identity, so u runs along world x and v along world z. */
static bg_mat4 plane_frame(bg_vec3 n)
{
    bg_vec3 r = fabs(n.x) < 0.9 ? bg_vec3_make(1, 0, 0) : bg_vec3_make(0, 0, 1);
    double d = r.x * n.x + r.y * n.y + r.z * n.z;
    bg_vec3 u = bg_vec3_make(r.x - d * n.x, r.y - d * n.y, r.z - d * n.z);
    double ul = bgi_vec3_length(u);
    u.x /= ul; u.y /= ul; u.z /= ul;
    bg_vec3 w = bg_vec3_make(u.y * n.z - u.z * n.y, u.z * n.x - u.x * n.z, u.x * n.y - u.y * n.x);
    bg_mat4 m = bg_mat4_identity();
    double cols[3][3] = {{u.x, u.y, u.z}, {n.x, n.y, n.z}, {w.x, w.y, w.z}};
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++)
            m.m[row][c] = cols[c][row];
    return m;
}

bg_status bg_scene_add_plane(bg_scene *scene, bg_vec3 point, bg_vec3 normal, uint32_t material,
                             uint32_t *out_object)
{
    static const char where[] = "bg_scene_add_plane";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!out_object)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_object is NULL", where);
    if (!bgi_vec3_finite(point))
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: point = (%g, %g, %g) is not finite",
                             where, point.x, point.y, point.z);
    if (!bgi_vec3_finite(normal) || bgi_vec3_length(normal) == 0.0)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: normal = (%g, %g, %g) must be finite and non-zero",
                             where, normal.x, normal.y, normal.z);
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_PLANE, material);
    d.transform = bg_mat4_mul(bg_mat4_translate(point.x, point.y, point.z), plane_frame(bgi_vec3_normalize(normal)));
    return add(scene, where, "transform (from point and normal)", &d, out_object);
}

bg_status bg_scene_set_transform(bg_scene *scene, uint32_t object, const bg_mat4 *transform)
{
    static const char call[] = "bg_scene_set_transform";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->objects, call, "object", object, &slot);
    if (st != BG_OK)
        return st;
    if (!transform)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: transform is NULL", call);
    char where[64], text[BG_HANDLE_TEXT_SIZE];
    snprintf(where, sizeof where, "%s: object %s", call, bgi_handle_text(object, text));
    bg_object_item *item = bgi_pool_item(&scene->objects, slot);
    bg_object_item moved = *item;
    moved.desc.transform = *transform;
    bg_object_data derived;
    st = bgi_object_derive(scene, where, "transform", &moved, &derived);
    if (st != BG_OK)
        return st;
    item->desc.transform = *transform;
    return BG_OK;
}

bg_status bg_scene_remove_object(bg_scene *scene, uint32_t object)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->objects, "bg_scene_remove_object", "object", object, &slot);
    if (st != BG_OK)
        return st;
    /* The committed state may still show the mesh: unref retires it until the next commit. */
    bgi_mesh_unref(scene, ((bg_object_item *)bgi_pool_item(&scene->objects, slot))->mesh);
    bgi_pool_remove(&scene->objects, slot);
    return BG_OK;
}
