#version 110
// requires:
// Watertight ray/triangle intersection with its fill rule (docs/shading.md 2.9), the float mirror of
// bgi_cpu_triangle_ray_init and bgi_cpu_triangle_intersect in src/betelgeuse/cpu/triangle.c, step
// for step, less the exact recomputation of a zero edge function (GLSL 1.10 has neither double nor a
// way to keep a compiler from fusing the steps it needs).
//
// GLSL 1.10 has no "precise": a compiler may fuse p.x * q.y - p.y * q.x into an fma, and would then
// round the edge function of a -> b differently from that of b -> a. So nothing a neighbour shares
// is computed in the triangle's own vertex order: each vertex is projected on its own, and each
// edge from its two vertices in the canonical order (the lexicographically smaller position first),
// with the triangle's direction applied afterwards as an exact negation. Both triangles of an edge
// then run one expression on the same inputs and see the same bits, whether or not it is fused.

// The per-ray setup: perm holds the unit axes kx, ky, kz as columns, so (v - o) * perm is
// (v[kx], v[ky], v[kz]) - o exactly (products with 0 and 1); shear is (d[kx], d[ky], 1) / d[kz].
// False for a zero direction, which no triangle can be hit by.
bool bg_triangle_setup(vec3 d, out mat3 perm, out vec3 shear)
{
    vec3 a = abs(d);
    // The dominant axis, the first of equal magnitudes, then the two after it in cyclic order.
    vec3 ez = vec3(1.0, 0.0, 0.0);
    vec3 ex = vec3(0.0, 1.0, 0.0);
    vec3 ey = vec3(0.0, 0.0, 1.0);
    if (a.y > a.x && a.y >= a.z) {
        ez = vec3(0.0, 1.0, 0.0);
        ex = vec3(0.0, 0.0, 1.0);
        ey = vec3(1.0, 0.0, 0.0);
    } else if (a.z > a.x && a.z > a.y) {
        ez = vec3(0.0, 0.0, 1.0);
        ex = vec3(1.0, 0.0, 0.0);
        ey = vec3(0.0, 1.0, 0.0);
    }
    float dz = dot(d, ez);
    // A negative d[kz] would mirror the sheared plane; swapping kx and ky mirrors it back.
    if (dz < 0.0) {
        vec3 k = ex;
        ex = ey;
        ey = k;
    }
    perm = mat3(ex, ey, ez);
    shear = vec3(0.0);
    if (dz == 0.0)
        return false;
    shear = vec3(dot(d, ex), dot(d, ey), 1.0) / dz;
    return true;
}

// A vertex in the ray's frame: xy across the ray (which passes through (0, 0)), z the t of the plane
// through the vertex across axis kz. One function for all three vertices, so a vertex shared by two
// triangles is projected by the same code to the same bits.
vec3 bg_triangle_project(vec3 v, vec3 o, mat3 perm, vec3 shear)
{
    vec3 q = (v - o) * perm;
    return vec3(q.xy - shear.xy * q.z, shear.z * q.z);
}

// The canonical order of an edge's vertices: lexicographic on the positions (by position, not index,
// so vertices duplicated for a seam still share their edges).
bool bg_triangle_before(vec3 a, vec3 b)
{
    if (a.x != b.x)
        return a.x < b.x;
    if (a.y != b.y)
        return a.y < b.y;
    return a.z < b.z;
}

// The edge function of a -> b (twice the signed area of (ray, a, b) in the sheared plane) and its
// 2-D direction e = pb - pa, both computed in the canonical order.
float bg_triangle_edge(vec3 a, vec3 b, vec2 pa, vec2 pb, out vec2 e)
{
    bool flip = bg_triangle_before(b, a);
    vec2 p = flip ? pb : pa;
    vec2 q = flip ? pa : pb;
    float w = p.x * q.y - p.y * q.x;
    vec2 k = q - p;
    e = flip ? -k : k;
    return flip ? -w : w;
}

// The sign a zero edge function takes when the ray moves by (eps, eps^2), eps -> 0+: the sign of
// e.x eps^2 - e.y eps. Odd in e, so the two triangles of an edge get opposite signs.
float bg_triangle_tie(vec2 e)
{
    return e.y != 0.0 ? -sign(e.y) : sign(e.x);
}

// The ray o + t d (perm and shear from bg_triangle_setup of d) against triangle v0 v1 v2: true for a
// hit with t in (tmin, tmax) on either side; bary holds the weights of v0, v1, v2 and front tells
// whether the ray meets the side (v1 - v0) x (v2 - v0) points to.
bool bg_triangle_intersect(vec3 o, mat3 perm, vec3 shear, vec3 v0, vec3 v1, vec3 v2, float tmin, float tmax,
                           out float t, out vec3 bary, out bool front)
{
    t = 0.0;
    bary = vec3(0.0);
    front = false;
    vec3 p0 = bg_triangle_project(v0, o, perm, shear);
    vec3 p1 = bg_triangle_project(v1, o, perm, shear);
    vec3 p2 = bg_triangle_project(v2, o, perm, shear);
    vec2 e0, e1, e2;
    float w0 = bg_triangle_edge(v1, v2, p1.xy, p2.xy, e0);
    float w1 = bg_triangle_edge(v2, v0, p2.xy, p0.xy, e1);
    float w2 = bg_triangle_edge(v0, v1, p0.xy, p1.xy, e2);
    bool neg = w0 < 0.0 || w1 < 0.0 || w2 < 0.0;
    bool pos = w0 > 0.0 || w1 > 0.0 || w2 > 0.0;
    if (neg == pos)
        return false;
    float s = pos ? 1.0 : -1.0;
    if ((w0 == 0.0 && bg_triangle_tie(e0) != s) || (w1 == 0.0 && bg_triangle_tie(e1) != s) ||
        (w2 == 0.0 && bg_triangle_tie(e2) != s))
        return false;
    float det = w0 + w1 + w2;
    float tt = (w0 * p0.z + w1 * p1.z + w2 * p2.z) / det;
    if (!(tt > tmin && tt < tmax))
        return false;
    // Degenerate in 3-D (repeated or collinear vertices): products compared, never subtracted.
    vec3 a = v1 - v0;
    vec3 b = v2 - v0;
    if (a.y * b.z == a.z * b.y && a.z * b.x == a.x * b.z && a.x * b.y == a.y * b.x)
        return false;
    t = tt;
    bary = vec3(w0, w1, w2) / det;
    front = det < 0.0;
    return true;
}
