/* Watertight ray/triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle
 * Intersection", JCGT 2(1), 2013) with an exact fill rule: docs/shading.md 2.9.
 *
 * Invariant: every quantity that two triangles sharing a vertex or an edge both use is computed from
 * that vertex or edge alone, by one expression, in one canonical order, so that both get the same
 * bits (an edge's values only change sign between the two triangles). Vertices are projected into
 * the ray's sheared 2-D frame on their own; an edge's function and direction are computed from its
 * two vertices with the lexicographically smaller position first. The sign of each edge function is
 * then exact (a plain 0 is recomputed exactly), and an exact 0 is decided by the tie rule of one
 * fixed infinitesimal displacement of the ray, so a shared edge or vertex goes to exactly one
 * triangle. glsl110/bg_triangle.glsl is the float mirror (without the exact recomputation).
 *
 * The exact steps need IEEE double arithmetic with every operation rounded on its own: no fused
 * multiply-add contraction (GCC contracts nothing in the ISO modes, -std=c99) and no extended
 * precision (x86-64 uses SSE2). */
#include "cpu_internal.h"

/* 2^27 + 1: Veltkamp's splitting constant for 53-bit significands. */
#define SPLIT 134217729.0

/* The exact recomputation is exact when every factor is 0 or has a magnitude in
 * [2^-480, 2^495]: the split cannot overflow and no partial product loses bits to underflow. */
#define EXACT_MIN 0x1p-480
#define EXACT_MAX 0x1p495

static bool exact_range(double x)
{
    double a = fabs(x);
    return a == 0.0 || (a >= EXACT_MIN && a <= EXACT_MAX);
}

/* a = hi + lo exactly, each half with at most 26 significant bits (Veltkamp). */
static void split(double a, double *hi, double *lo)
{
    double c = SPLIT * a;
    *hi = c - (c - a);
    *lo = a - *hi;
}

/* The rounding error of a * b: a * b = fl(a * b) + error exactly (Dekker's TwoProduct). */
static double product_error(double a, double b, double p)
{
    double ah, al, bh, bl;
    split(a, &ah, &al);
    split(b, &bh, &bl);
    return ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

double bgi_cpu_diff_of_products(double a, double b, double c, double d)
{
    double p = a * b, q = c * d;
    double w = p - q;
    /* Rounding is monotone, so p > q implies a b > c d: a nonzero w has the exact sign. Only p == q
     * leaves it open, and then a b - c d = (p + ep) - (q + eq) = ep - eq, one rounding away. */
    if (w != 0.0 || !exact_range(a) || !exact_range(b) || !exact_range(c) || !exact_range(d))
        return w;
    return product_error(a, b, p) - product_error(c, d, q);
}

void bgi_cpu_triangle_ray_init(const double o[3], const double d[3], bg_cpu_triangle_ray *ray)
{
    for (int i = 0; i < 3; i++)
        ray->o[i] = o[i];
    /* The dominant axis, the first of equal magnitudes (as the GLSL mirror picks it). */
    int kz = 0;
    if (fabs(d[1]) > fabs(d[kz]))
        kz = 1;
    if (fabs(d[2]) > fabs(d[kz]))
        kz = 2;
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    /* A negative d[kz] makes the shear mirror the plane; swapping kx and ky mirrors it back, so the
     * sign of a projected triangle's area is always the sign of d.n. */
    if (d[kz] < 0.0) {
        int k = kx;
        kx = ky;
        ky = k;
    }
    ray->kx = kx;
    ray->ky = ky;
    ray->kz = kz;
    ray->valid = d[kz] != 0.0 && isfinite(d[0]) && isfinite(d[1]) && isfinite(d[2]);
    ray->sx = ray->valid ? d[kx] / d[kz] : 0.0;
    ray->sy = ray->valid ? d[ky] / d[kz] : 0.0;
    ray->sz = ray->valid ? 1.0 / d[kz] : 0.0;
}

/* A vertex in the ray's frame: (x, y) across the ray (the ray passes through (0, 0)) and z, the t of
 * the plane through the vertex across axis kz. */
static void project(const bg_cpu_triangle_ray *r, const double v[3], double p[3])
{
    double ax = v[r->kx] - r->o[r->kx], ay = v[r->ky] - r->o[r->ky], az = v[r->kz] - r->o[r->kz];
    p[0] = ax - r->sx * az;
    p[1] = ay - r->sy * az;
    p[2] = r->sz * az;
}

/* The canonical order of an edge's two vertices: lexicographic on the positions. By position rather
 * than by index, so that vertices duplicated for a UV or normal seam (one position, two indices)
 * still give their triangles the same edge. */
static bool before(const double a[3], const double b[3])
{
    if (a[0] != b[0])
        return a[0] < b[0];
    if (a[1] != b[1])
        return a[1] < b[1];
    return a[2] < b[2];
}

/* The edge function w of the directed edge a -> b, twice the signed area of (ray, a, b) in the
 * sheared plane, and the edge's 2-D direction e = pb - pa. */
static double edge(const double a[3], const double b[3], const double pa[3], const double pb[3], double e[2])
{
    bool flip = before(b, a);
    const double *p = flip ? pb : pa, *q = flip ? pa : pb;
    double w = bgi_cpu_diff_of_products(p[0], q[1], p[1], q[0]);
    double ex = q[0] - p[0], ey = q[1] - p[1];
    e[0] = flip ? -ex : ex;
    e[1] = flip ? -ey : ey;
    return flip ? -w : w;
}

/* The sign an exactly zero edge function takes when the ray moves by (eps, eps^2) in the sheared
 * plane, eps -> 0+: the sign of e x (eps, eps^2) = e.x eps^2 - e.y eps. Odd in e, so the two
 * triangles of an edge, which see -e of each other, get opposite signs. */
static double tie(const double e[2])
{
    if (e[1] != 0.0)
        return e[1] < 0.0 ? 1.0 : -1.0;
    return e[0] > 0.0 ? 1.0 : (e[0] < 0.0 ? -1.0 : 0.0);
}

/* The cross product of the edge vectors is zero: products compared rather than subtracted, so the
 * GLSL mirror decides alike even where a compiler fuses a subtraction into an fma. */
static bool degenerate(const double v0[3], const double v1[3], const double v2[3])
{
    double a[3] = {v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]};
    double b[3] = {v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]};
    return a[1] * b[2] == a[2] * b[1] && a[2] * b[0] == a[0] * b[2] && a[0] * b[1] == a[1] * b[0];
}

bool bgi_cpu_triangle_intersect(const bg_cpu_triangle_ray *ray, const double v0[3], const double v1[3],
                                const double v2[3], double t_min, double t_max, bg_cpu_triangle_hit *hit)
{
    if (!ray->valid)
        return false;
    double p0[3], p1[3], p2[3];
    project(ray, v0, p0);
    project(ray, v1, p1);
    project(ray, v2, p2);
    double e0[2], e1[2], e2[2];
    /* w_i belongs to the edge opposite vertex i: its barycentric weight times det. */
    double w0 = edge(v1, v2, p1, p2, e0);
    double w1 = edge(v2, v0, p2, p0, e1);
    double w2 = edge(v0, v1, p0, p1, e2);
    bool neg = w0 < 0.0 || w1 < 0.0 || w2 < 0.0;
    bool pos = w0 > 0.0 || w1 > 0.0 || w2 > 0.0;
    if (neg == pos)
        return false; /* the ray passes outside an edge, or the projection has no area */
    /* The orientation of the projected triangle, and of every nonzero edge function. */
    double s = pos ? 1.0 : -1.0;
    if ((w0 == 0.0 && tie(e0) != s) || (w1 == 0.0 && tie(e1) != s) || (w2 == 0.0 && tie(e2) != s))
        return false;
    /* Terms of one sign: no cancellation, and det != 0. */
    double det = w0 + w1 + w2;
    double t = (w0 * p0[2] + w1 * p1[2] + w2 * p2[2]) / det;
    /* Written so that a NaN (an overflowing product) is a miss. */
    if (!(t > t_min && t < t_max) || !isfinite(det))
        return false;
    if (degenerate(v0, v1, v2))
        return false;
    if (hit) {
        hit->t = t;
        hit->bary[0] = w0 / det;
        hit->bary[1] = w1 / det;
        hit->bary[2] = w2 / det;
        hit->front = det < 0.0;
    }
    return true;
}
