/* Objects: defaults, add, the sphere and plane shorthands, and moving an object. */
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

static bg_status add(bg_scene *scene, const char *where, const bg_object_desc *desc, uint32_t *out_object)
{
    bg_status st = bgi_validate_object(scene, where, desc, scene->materials.count);
    if (st == BG_OK)
        st = bgi_array_reserve(scene, &scene->objects, scene->objects.count + 1, sizeof(bg_object_desc), where);
    if (st != BG_OK)
        return st;
    ((bg_object_desc *)scene->objects.data)[scene->objects.count++] = *desc;
    *out_object = scene->objects.count;
    return BG_OK;
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
    return add(scene, where, desc, out_object);
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
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_SPHERE, material);
    d.transform = bg_mat4_mul(bg_mat4_translate(center.x, center.y, center.z),
                              bg_mat4_scale(radius, radius, radius));
    return add(scene, where, &d, out_object);
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
    double len = bgi_vec3_length(normal);
    if (!bgi_vec3_finite(normal) || len == 0.0)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: normal = (%g, %g, %g) must be finite and non-zero",
                             where, normal.x, normal.y, normal.z);
    bg_vec3 n = bg_vec3_make(normal.x / len, normal.y / len, normal.z / len);
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_PLANE, material);
    d.transform = bg_mat4_mul(bg_mat4_translate(point.x, point.y, point.z), plane_frame(n));
    return add(scene, where, &d, out_object);
}

bg_status bg_scene_set_transform(bg_scene *scene, uint32_t object, const bg_mat4 *transform)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t index;
    bg_status st = bgi_scene_handle(scene, "bg_scene_set_transform", "object", object,
                                   scene->objects.count, &index);
    if (st != BG_OK)
        return st;
    if (!transform)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "bg_scene_set_transform: transform is NULL");
    char where[64];
    snprintf(where, sizeof where, "bg_scene_set_transform: object %u", object);
    st = bgi_validate_transform(scene, where, transform);
    if (st != BG_OK)
        return st;
    ((bg_object_desc *)scene->objects.data)[index].transform = *transform;
    return BG_OK;
}
