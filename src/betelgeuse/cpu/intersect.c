/* Ray/prototype intersection in object space and the hit attributes (docs/shading.md sections 2-3).
 * The object-space direction is never normalised, so t is the world ray's parameter too. */
#include <float.h>
#include <string.h>

#include "../common/shapes.h"
#include "cpu_internal.h"

/* Below this share of the largest direction component a slab or cap counts as parallel: the
 * division it guards then stays below 2^1000 times the numerator scale, far from overflow. */
#define PARALLEL_REL 0x1p-1000
/* A plane whose |n.d| is below this share of |d| (max norm) is treated as parallel. */
#define PLANE_REL 0x1p-40

typedef struct interval {
    bool has_lo, has_hi; /* false: unbounded on that side */
    double lo, hi;
    double n_lo[3], n_hi[3];
} interval;

static double max_abs3(const double v[3])
{
    double m = fabs(v[0]);
    if (fabs(v[1]) > m)
        m = fabs(v[1]);
    if (fabs(v[2]) > m)
        m = fabs(v[2]);
    return m;
}

/* Intersects the interval with [lo, hi] and its normals; false when it becomes empty. */
static bool clip(interval *iv, double lo, const double n_lo[3], double hi, const double n_hi[3])
{
    if (!iv->has_lo || lo > iv->lo) {
        iv->lo = lo;
        memcpy(iv->n_lo, n_lo, sizeof iv->n_lo);
        iv->has_lo = true;
    }
    if (!iv->has_hi || hi < iv->hi) {
        iv->hi = hi;
        memcpy(iv->n_hi, n_hi, sizeof iv->n_hi);
        iv->has_hi = true;
    }
    return iv->lo <= iv->hi;
}

/* The slab -1 <= o_i + t d_i <= 1 along axis i; false when the line misses it. */
static bool slab(interval *iv, const double o[3], const double d[3], int axis, double dir_scale)
{
    double oi = o[axis], di = d[axis];
    double n_lo[3] = {0.0, 0.0, 0.0}, n_hi[3] = {0.0, 0.0, 0.0};
    if (fabs(di) <= dir_scale * PARALLEL_REL * (1.0 + fabs(oi)) || di == 0.0)
        return oi >= -1.0 && oi <= 1.0; /* parallel: inside the slab for every t, or never */
    double ta = (-1.0 - oi) / di, tb = (1.0 - oi) / di;
    if (di > 0.0) {
        n_lo[axis] = -1.0;
        n_hi[axis] = 1.0;
        return clip(iv, ta, n_lo, tb, n_hi);
    }
    n_lo[axis] = 1.0;
    n_hi[axis] = -1.0;
    return clip(iv, tb, n_lo, ta, n_hi);
}

/* Roots of a t^2 + 2 b t + c = 0 for a quadric whose discriminant is given in the stable form;
 * false for no real root or a degenerate one. */
static bool stable_roots(double a, double b, double c, double disc, double *t0, double *t1)
{
    if (!(a > 0.0) || disc < 0.0)
        return false;
    double q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
    if (q == 0.0)
        return false;
    double r0 = c / q, r1 = q / a;
    *t0 = r0 < r1 ? r0 : r1;
    *t1 = r0 < r1 ? r1 : r0;
    return true;
}

static void sphere_span(const double o[3], const double d[3], bg_cpu_span *span)
{
    double a = bg_v3_dot(d, d), b = bg_v3_dot(o, d), c = bg_v3_dot(o, o) - 1.0;
    if (!(a > 0.0))
        return;
    /* b^2 - a c = a (1 - |f - (b / a) d|^2): no cancellation between two large squares. */
    double s = b / a;
    double g[3] = {o[0] - s * d[0], o[1] - s * d[1], o[2] - s * d[2]};
    double disc = a * (1.0 - bg_v3_dot(g, g));
    double t0, t1;
    if (!stable_roots(a, b, c, disc, &t0, &t1))
        return;
    span->count = 2;
    span->t[0] = t0;
    span->t[1] = t1;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 3; i++)
            span->normal[k][i] = o[i] + span->t[k] * d[i];
}

/* A closed shape's span is the clipped interval, when both of its ends were found. */
static void store_interval(const interval *iv, bg_cpu_span *span)
{
    if (!iv->has_lo || !iv->has_hi)
        return;
    span->count = 2;
    span->t[0] = iv->lo;
    span->t[1] = iv->hi;
    memcpy(span->normal[0], iv->n_lo, sizeof iv->n_lo);
    memcpy(span->normal[1], iv->n_hi, sizeof iv->n_hi);
}

static void box_span(const double o[3], const double d[3], bg_cpu_span *span)
{
    interval iv = {false, false, 0.0, 0.0, {0, 0, 0}, {0, 0, 0}};
    double scale = max_abs3(d);
    for (int axis = 0; axis < 3; axis++)
        if (!slab(&iv, o, d, axis, scale))
            return;
    store_interval(&iv, span);
}

static void cylinder_span(const double o[3], const double d[3], bg_cpu_span *span)
{
    interval iv = {false, false, 0.0, 0.0, {0, 0, 0}, {0, 0, 0}};
    double scale = max_abs3(d);
    double a = d[0] * d[0] + d[2] * d[2];
    double b = o[0] * d[0] + o[2] * d[2];
    double c = o[0] * o[0] + o[2] * o[2] - 1.0;
    if (a <= scale * scale * PARALLEL_REL) {
        if (c > 0.0)
            return; /* parallel to the axis and outside the side */
    } else {
        double s = b / a;
        double gx = o[0] - s * d[0], gz = o[2] - s * d[2];
        double disc = a * (1.0 - (gx * gx + gz * gz));
        double t0, t1;
        if (!stable_roots(a, b, c, disc, &t0, &t1))
            return;
        double n0[3] = {o[0] + t0 * d[0], 0.0, o[2] + t0 * d[2]};
        double n1[3] = {o[0] + t1 * d[0], 0.0, o[2] + t1 * d[2]};
        clip(&iv, t0, n0, t1, n1);
    }
    if (!slab(&iv, o, d, 1, scale))
        return;
    store_interval(&iv, span);
}

static void thin(const double o[3], const double d[3], bool bounded, bg_cpu_span *span)
{
    if (fabs(d[1]) <= max_abs3(d) * PLANE_REL)
        return; /* parallel (or too grazing to resolve) */
    double t = -o[1] / d[1];
    if (bounded) {
        double x = o[0] + t * d[0], z = o[2] + t * d[2];
        if (!(x >= -1.0 && x <= 1.0 && z >= -1.0 && z <= 1.0))
            return;
    }
    span->count = 1;
    span->t[0] = span->t[1] = t;
    bg_v3_set(span->normal[0], 0.0, 1.0, 0.0);
    bg_v3_set(span->normal[1], 0.0, 1.0, 0.0);
}

static void plane_span(const double o[3], const double d[3], bg_cpu_span *span)
{
    thin(o, d, false, span);
}

static void rectangle_span(const double o[3], const double d[3], bg_cpu_span *span)
{
    thin(o, d, true, span);
}

/* Each shape's intersector, from its row of common/shapes.h. */
#define SPAN_OF(shape, name, glsl, is_thin, default_uv, cpu_span, half_extent) [shape] = cpu_span,
static void (*const shape_span[BG_SHAPE_COUNT_])(const double o[3], const double d[3], bg_cpu_span *span) = {
    BG_SHAPES(SPAN_OF)};
#undef SPAN_OF

void bgi_cpu_intersect_prototype(bg_shape shape, const double o[3], const double d[3], bg_cpu_span *span)
{
    memset(span, 0, sizeof *span);
    if ((unsigned)shape < BG_SHAPE_COUNT_)
        shape_span[shape](o, d, span);
}

void bgi_cpu_object_ray(const bg_object_data *object, const double o[3], const double d[3], double oo[3],
                       double od[3])
{
    const double (*m)[4] = object->to_object;
    for (int i = 0; i < 3; i++) {
        oo[i] = m[i][0] * o[0] + m[i][1] * o[1] + m[i][2] * o[2] + m[i][3];
        od[i] = m[i][0] * d[0] + m[i][1] * d[1] + m[i][2] * d[2];
    }
}

bool bgi_cpu_intersect_object(const bg_object_data *object, const double o[3], const double d[3], bool far_root,
                             double t_max, bg_cpu_candidate *candidate)
{
    return bgi_cpu_intersect_object_except(object, o, d, far_root, BG_CPU_NONE, NULL, t_max, candidate);
}

bool bgi_cpu_intersect_object_except(const bg_object_data *object, const double o[3], const double d[3],
                                    bool far_root, uint32_t skip_triangle, const bg_cpu_mesh_filter *filter,
                                    double t_max, bg_cpu_candidate *candidate)
{
    double oo[3], od[3];
    bg_cpu_span span;
    bgi_cpu_object_ray(object, o, d, oo, od);
    /* A mesh has no far root: the side of the triangle says inside or outside. */
    if (object->mesh)
        return bgi_cpu_mesh_nearest(object, filter, oo, od, skip_triangle, t_max, candidate);
    bgi_cpu_intersect_prototype(object->shape, oo, od, &span);
    if (span.count == 0)
        return false;
    int root = -1;
    if (far_root) {
        if (span.count == 2 && span.t[1] > 0.0 && span.t[1] <= t_max)
            root = 1;
    } else if (span.t[0] > 0.0 && span.t[0] <= t_max) {
        root = 0;
    } else if (span.count == 2 && span.t[1] > 0.0 && span.t[1] <= t_max) {
        root = 1;
    }
    if (root < 0)
        return false;
    candidate->t = span.t[root];
    candidate->root = root;
    candidate->triangle = BG_CPU_NONE;
    for (int i = 0; i < 3; i++) {
        candidate->p[i] = oo[i] + candidate->t * od[i];
        candidate->n[i] = span.normal[root][i];
    }
    return true;
}

bool bgi_cpu_segment_blocked(const bg_object_data *object, const double o[3], const double l[3], double t_max)
{
    return bgi_cpu_segment_blocked_except(object, o, l, BG_CPU_NONE, NULL, t_max);
}

bool bgi_cpu_segment_blocked_except(const bg_object_data *object, const double o[3], const double l[3],
                                   uint32_t skip_triangle, const bg_cpu_mesh_filter *filter, double t_max)
{
    double oo[3], od[3];
    bg_cpu_span span;
    bgi_cpu_object_ray(object, o, l, oo, od);
    if (object->mesh)
        return bgi_cpu_mesh_blocked(object, filter, oo, od, skip_triangle, t_max * (1.0 - BG_SHADOW_END_REL));
    bgi_cpu_intersect_prototype(object->shape, oo, od, &span);
    if (span.count == 0)
        return false;
    double exit_t = span.t[span.count - 1];
    /* Open at the light's end by BG_SHADOW_END_REL of its length (cpu_internal.h). */
    return exit_t > 0.0 && span.t[0] < t_max * (1.0 - BG_SHADOW_END_REL);
}

/* Any unit vector perpendicular to n: the coordinate axis least aligned with it, orthogonalised. */
static void fallback_tangent(const double n[3], double t[3])
{
    double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
    double e[3] = {0.0, 0.0, 0.0};
    if (ax <= ay && ax <= az)
        e[0] = 1.0;
    else if (ay <= az)
        e[1] = 1.0;
    else
        e[2] = 1.0;
    double k = bg_v3_dot(e, n);
    bg_v3_set(t, e[0] - k * n[0], e[1] - k * n[1], e[2] - k * n[2]);
    bg_v3_normalize(t);
}

void bgi_cpu_finish_tangent(const double t0[3], const double n[3], double t[3])
{
    double len0 = sqrt(bg_v3_dot(t0, t0));
    double k = bg_v3_dot(t0, n);
    for (int i = 0; i < 3; i++)
        t[i] = t0[i] - k * n[i];
    /* Degenerate when dP/du vanishes (poles) or lies along the normal. */
    if (!(len0 > 0.0) || !(sqrt(bg_v3_dot(t, t)) > len0 * 1e-9) || !bg_v3_normalize(t))
        fallback_tangent(n, t);
}

void bgi_cpu_hit_attributes(const bg_object_data *object, uint32_t index, const double o[3], const double d[3],
                           const bg_cpu_candidate *candidate, bg_cpu_hit *hit)
{
    if (object->mesh) {
        bgi_cpu_mesh_attributes(object, index, d, candidate, hit);
        return;
    }
    hit->object = index;
    hit->triangle = BG_CPU_NONE;
    hit->offset = 0.0;
    hit->t = candidate->t;
    for (int i = 0; i < 3; i++)
        hit->position[i] = o[i] + candidate->t * d[i];

    const double (*nw)[3] = object->normal_to_world;
    const double *n = candidate->n;
    for (int i = 0; i < 3; i++)
        hit->normal[i] = nw[i][0] * n[0] + nw[i][1] * n[1] + nw[i][2] * n[2];
    if (!bg_v3_normalize(hit->normal))
        bg_v3_set(hit->normal, -d[0], -d[1], -d[2]);

    if (bg_shape_thin(object->shape)) {
        hit->entering = bg_v3_dot(hit->normal, d) <= 0.0;
    } else {
        hit->entering = candidate->root == 0;
    }
    /* The outward normal faces the ray at an entry; at an exit (or the back of a thin shape) flip it. */
    if (!hit->entering)
        bg_v3_set(hit->normal, -hit->normal[0], -hit->normal[1], -hit->normal[2]);

    double dpdu[3];
    bgi_cpu_uv_map(object->uv_mapping, candidate->p, hit->uv, dpdu);
    hit->uv[0] *= object->uv_scale[0];
    hit->uv[1] *= object->uv_scale[1];

    const double (*m)[4] = object->to_world;
    double t[3];
    for (int i = 0; i < 3; i++)
        t[i] = m[i][0] * dpdu[0] + m[i][1] * dpdu[1] + m[i][2] * dpdu[2];
    bgi_cpu_finish_tangent(t, hit->normal, hit->tangent);
    memcpy(hit->geometric_normal, hit->normal, sizeof hit->normal);
}
