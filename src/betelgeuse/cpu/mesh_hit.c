/* Mesh objects in the CPU reference (docs/shading.md 2.10): the object-space ray walks the mesh's
 * own tree and meets its triangles through the watertight test (triangle.c); a hit's attributes
 * come from the barycentric weights; a ray leaving a triangle skips it and starts a little off the
 * surface, by an offset that scales with the point's magnitude. */
#include <float.h>
#include <string.h>

#include "cpu_internal.h"

/* The offset of a ray leaving a mesh, in units of the point's rounding: Waechter and Binder's float
 * rule moves a coordinate by 256 of its own ulps; here every coordinate moves 256 ulps of the
 * largest term the point's world coordinates are summed from (its magnitude), along the normal. */
#define MESH_OFFSET_ULPS 256.0

static void vertex(const bg_mesh_data *m, uint32_t triangle, int corner, double v[3])
{
    const float *p = &m->positions[3 * (size_t)m->indices[3 * (size_t)triangle + corner]];
    bg_v3_set(v, p[0], p[1], p[2]);
}

/* t_max made inclusive for the triangle test, whose range is open at both ends. */
static double inclusive(double t_max)
{
    return t_max < DBL_MAX ? nextafter(t_max, DBL_MAX) : DBL_MAX;
}

typedef struct mesh_search {
    const bg_mesh_data *mesh;
    const bg_cpu_mesh_filter *filter; /* NULL: every point is there */
    bg_cpu_triangle_ray ray;
    uint32_t skip;
    double t_max;     /* nearest: inclusive limit; shadow: exclusive */
    bool shadow;
    bool found;
    uint32_t triangle;
    bg_cpu_triangle_hit hit;
} mesh_search;

static bool visit_triangle(void *user, uint32_t prim, double *t_max)
{
    mesh_search *s = user;
    if (prim == s->skip)
        return true;
    double v0[3], v1[3], v2[3];
    vertex(s->mesh, prim, 0, v0);
    vertex(s->mesh, prim, 1, v1);
    vertex(s->mesh, prim, 2, v2);
    bg_cpu_triangle_hit h;
    if (s->shadow) {
        /* Light travels the segment the other way: the side it meets is the one the light sees. */
        s->found = bgi_cpu_triangle_intersect(&s->ray, v0, v1, v2, 0.0, s->t_max, &h) &&
                   (!s->filter || bgi_cpu_mesh_filter_keeps(s->filter, s->mesh, prim, h.bary, !h.front));
        return !s->found;
    }
    double limit = s->found ? s->hit.t : s->t_max;
    if (!bgi_cpu_triangle_intersect(&s->ray, v0, v1, v2, 0.0, inclusive(limit), &h))
        return true;
    if (s->filter && !bgi_cpu_mesh_filter_keeps(s->filter, s->mesh, prim, h.bary, h.front))
        return true;
    if (!s->found || h.t < s->hit.t || (h.t == s->hit.t && prim < s->triangle)) {
        s->found = true;
        s->hit = h;
        s->triangle = prim;
        *t_max = h.t;
    }
    return true;
}

/* Offers the triangles the tree's walk reaches; every triangle when the walk is refused (never for
 * a tree bgi_bvh_build made, but the answer stays exact either way). */
static void walk(mesh_search *s, const double oo[3], const double od[3])
{
    bgi_cpu_triangle_ray_init(oo, od, &s->ray);
    if (!s->ray.valid)
        return;
    double t = s->t_max;
    if (bgi_bvh_traverse(&s->mesh->tree, oo, od, 0.0, &t, visit_triangle, s, NULL) == BG_OK)
        return;
    double unused = s->t_max;
    for (uint32_t i = 0; i < s->mesh->triangle_count; i++)
        if (!visit_triangle(s, i, &unused))
            return;
}

bool bgi_cpu_mesh_nearest(const bg_object_data *object, const bg_cpu_mesh_filter *filter, const double oo[3],
                         const double od[3], uint32_t skip_triangle, double t_max, bg_cpu_candidate *candidate)
{
    mesh_search s;
    memset(&s, 0, sizeof s);
    s.mesh = object->mesh;
    s.filter = filter;
    s.skip = skip_triangle;
    s.t_max = t_max;
    walk(&s, oo, od);
    if (!s.found)
        return false;
    candidate->t = s.hit.t;
    candidate->root = s.hit.front ? 0 : 1;
    candidate->triangle = s.triangle;
    memcpy(candidate->bary, s.hit.bary, sizeof s.hit.bary);
    for (int i = 0; i < 3; i++)
        candidate->p[i] = oo[i] + s.hit.t * od[i];
    bg_v3_set(candidate->n, 0.0, 0.0, 0.0);
    return true;
}

bool bgi_cpu_mesh_blocked(const bg_object_data *object, const bg_cpu_mesh_filter *filter, const double oo[3],
                         const double od[3], uint32_t skip_triangle, double t_limit)
{
    mesh_search s;
    memset(&s, 0, sizeof s);
    s.mesh = object->mesh;
    s.filter = filter;
    s.skip = skip_triangle;
    s.t_max = t_limit;
    s.shadow = true;
    walk(&s, oo, od);
    return s.found;
}

static void to_world_linear(const bg_object_data *o, const double v[3], double out[3])
{
    const double (*m)[4] = o->to_world;
    for (int i = 0; i < 3; i++)
        out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

static void normal_to_world(const bg_object_data *o, const double n[3], double out[3])
{
    const double (*m)[3] = o->normal_to_world;
    for (int i = 0; i < 3; i++)
        out[i] = m[i][0] * n[0] + m[i][1] * n[1] + m[i][2] * n[2];
}

/* The world point of the barycentric weights, and its magnitude: per axis the sum of the absolute
 * terms it is made of (the largest vertex coordinates, the transform's entries), the largest over
 * the axes. Rounding errors of the point, and of the next ray's tests near it, are a few ulps of it. */
static double world_point(const bg_object_data *o, double v[3][3], const double b[3], double p[3])
{
    double q[3], big[3];
    for (int j = 0; j < 3; j++) {
        q[j] = b[0] * v[0][j] + b[1] * v[1][j] + b[2] * v[2][j];
        big[j] = fmax(fabs(v[0][j]), fmax(fabs(v[1][j]), fabs(v[2][j])));
    }
    const double (*m)[4] = o->to_world;
    double magnitude = 0.0;
    for (int i = 0; i < 3; i++) {
        p[i] = m[i][0] * q[0] + m[i][1] * q[1] + m[i][2] * q[2] + m[i][3];
        double mag = fabs(m[i][0]) * big[0] + fabs(m[i][1]) * big[1] + fabs(m[i][2]) * big[2] + fabs(m[i][3]);
        magnitude = fmax(magnitude, mag);
    }
    return magnitude;
}

/* dP/du of the triangle from its texture coordinates (object space); false when they are missing
 * or give the triangle no u direction (a zero or non-finite uv area). */
static bool uv_tangent(const bg_mesh_data *m, uint32_t triangle, double v[3][3], double dpdu[3])
{
    if (!m->uvs)
        return false;
    double uv[3][2];
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 2; k++)
            uv[c][k] = m->uvs[2 * (size_t)m->indices[3 * (size_t)triangle + c] + k];
    double du1 = uv[1][0] - uv[0][0], dv1 = uv[1][1] - uv[0][1];
    double du2 = uv[2][0] - uv[0][0], dv2 = uv[2][1] - uv[0][1];
    double det = du1 * dv2 - du2 * dv1;
    if (!(det != 0.0) || !isfinite(det))
        return false;
    for (int i = 0; i < 3; i++)
        dpdu[i] = (dv2 * (v[1][i] - v[0][i]) - dv1 * (v[2][i] - v[0][i])) / det;
    return true;
}

void bgi_cpu_mesh_attributes(const bg_object_data *object, uint32_t index, const double d[3],
                            const bg_cpu_candidate *candidate, bg_cpu_hit *hit)
{
    const bg_mesh_data *m = object->mesh;
    uint32_t tri = candidate->triangle;
    const double *b = candidate->bary;
    double v[3][3];
    for (int c = 0; c < 3; c++)
        vertex(m, tri, c, v[c]);
    hit->object = index;
    hit->triangle = tri;
    hit->t = candidate->t;
    hit->offset = MESH_OFFSET_ULPS * DBL_EPSILON * world_point(object, v, b, hit->position);
    hit->entering = candidate->root == 0;

    /* The geometric normal, turned to the side the ray arrives from. */
    double e1[3], e2[3], ng[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = v[1][i] - v[0][i];
        e2[i] = v[2][i] - v[0][i];
    }
    bg_v3_cross(e1, e2, ng);
    normal_to_world(object, ng, hit->geometric_normal);
    double *g = hit->geometric_normal;
    if (!bg_v3_normalize(g))
        bg_v3_set(g, -d[0], -d[1], -d[2]);
    else if (!hit->entering)
        bg_v3_set(g, -g[0], -g[1], -g[2]);

    /* The shading normal: interpolated and turned like the geometric one, then kept on the side of
     * the geometric normal that the ray sees. */
    memcpy(hit->normal, g, sizeof hit->normal);
    if (m->normals) {
        double ns[3] = {0.0, 0.0, 0.0}, w[3];
        for (int c = 0; c < 3; c++) {
            const float *n = &m->normals[3 * (size_t)m->indices[3 * (size_t)tri + c]];
            for (int i = 0; i < 3; i++)
                ns[i] += b[c] * n[i];
        }
        normal_to_world(object, ns, w);
        if (bg_v3_normalize(w)) {
            double s = hit->entering ? 1.0 : -1.0;
            if (s * bg_v3_dot(w, g) < 0.0)
                s = -s;
            bg_v3_set(hit->normal, s * w[0], s * w[1], s * w[2]);
        }
    }

    hit->uv[0] = hit->uv[1] = 0.0;
    if (m->uvs)
        for (int k = 0; k < 2; k++) {
            double u = 0.0;
            for (int c = 0; c < 3; c++)
                u += b[c] * m->uvs[2 * (size_t)m->indices[3 * (size_t)tri + c] + k];
            hit->uv[k] = u * object->uv_scale[k];
        }
    double dpdu[3] = {0.0, 0.0, 0.0}, t0[3] = {0.0, 0.0, 0.0};
    if (uv_tangent(m, tri, v, dpdu))
        to_world_linear(object, dpdu, t0);
    bgi_cpu_finish_tangent(t0, hit->normal, hit->tangent);
}

void bgi_cpu_leave_origin(const bg_cpu_hit *hit, const double dir[3], double origin[3])
{
    if (hit->offset == 0.0) { /* the analytic shapes: exactly the hit point, signed zeros included */
        memcpy(origin, hit->position, 3 * sizeof origin[0]);
        return;
    }
    double side = bg_v3_dot(dir, hit->geometric_normal) >= 0.0 ? hit->offset : -hit->offset;
    for (int i = 0; i < 3; i++)
        origin[i] = hit->position[i] + side * hit->geometric_normal[i];
}
