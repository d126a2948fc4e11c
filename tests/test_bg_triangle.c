/* Watertight ray/triangle intersection and its fill rule (docs/shading.md 2.9), in double on the
 * CPU (src/betelgeuse/cpu/triangle.c) and in float on the GPU (glsl110/bg_triangle.glsl in a MACS
 * pass): a ray through a shared edge or vertex of a consistently wound mesh hits exactly one triangle,
 * closed meshes have no holes, t and barycentrics match a reference, degenerate triangles are never
 * hit, and nothing becomes NaN at extreme scales. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/cpu/cpu_internal.h"
#include "betelgeuse/gpu/shared/shared.h"
#include "scenes/meshes.h"
#include "scenes/ply_mesh.h"
#include "util_gl.h"

/* ---- helpers --------------------------------------------------------------------------------- */

/* A mesh in double, the form the CPU test reads (positions from floats, as a scene's would be). */
typedef struct dmesh {
    int vertex_count, triangle_count;
    double *v;    /* 3 per vertex */
    uint32_t *t;  /* 3 per triangle */
} dmesh;

static void dmesh_free(dmesh *m)
{
    free(m->v);
    free(m->t);
    memset(m, 0, sizeof *m);
}

static dmesh dmesh_from(const mesh *m)
{
    dmesh d = {(int)m->vertex_count, (int)m->triangle_count, malloc(sizeof(double) * 3 * m->vertex_count),
               malloc(sizeof(uint32_t) * 3 * m->triangle_count)};
    assert_non_null(d.v);
    assert_non_null(d.t);
    for (uint32_t i = 0; i < 3 * m->vertex_count; i++)
        d.v[i] = m->positions[i];
    memcpy(d.t, m->indices, sizeof(uint32_t) * 3 * m->triangle_count);
    return d;
}

/* An n x n grid of quads on z = z0 at offset + scale (i, j), every coordinate rounded to float;
 * counter-clockwise seen from +z. alternate: the quads' diagonals alternate (vertices shared by 4 or
 * 8 triangles); otherwise all run from (i, j) to (i + 1, j + 1) (every interior vertex in 6). */
static dmesh grid(int n, double scale, const double offset[3], bool alternate)
{
    dmesh m = {(n + 1) * (n + 1), 2 * n * n, malloc(sizeof(double) * 3 * (n + 1) * (n + 1)),
               malloc(sizeof(uint32_t) * 6 * n * n)};
    assert_non_null(m.v);
    assert_non_null(m.t);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double *p = m.v + 3 * (j * (n + 1) + i);
            p[0] = (float)(offset[0] + scale * i);
            p[1] = (float)(offset[1] + scale * j);
            p[2] = (float)offset[2];
        }
    uint32_t *t = m.t;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 2, d = a + (uint32_t)n + 1;
            uint32_t q[6] = {a, b, c, a, c, d};
            if (alternate && (i + j) % 2) {
                uint32_t r[6] = {a, b, d, b, c, d};
                memcpy(q, r, sizeof q);
            }
            memcpy(t, q, sizeof q);
            t += 6;
        }
    return m;
}

static const double *vtx(const dmesh *m, int tri, int k)
{
    return m->v + 3 * m->t[3 * tri + k];
}

/* Every triangle of m the ray hits with t in (0, inf); the count, the nearest triangle and its hit,
 * and the number of front hits. */
typedef struct hits {
    int count, front, nearest;
    bg_cpu_triangle_hit hit;
} hits;

static hits cast(const dmesh *m, const double o[3], const double d[3])
{
    bg_cpu_triangle_ray ray;
    bgi_cpu_triangle_ray_init(o, d, &ray);
    hits h = {0, 0, -1, {0.0, {0.0, 0.0, 0.0}, false}};
    for (int i = 0; i < m->triangle_count; i++) {
        bg_cpu_triangle_hit x;
        if (bgi_cpu_triangle_intersect(&ray, vtx(m, i, 0), vtx(m, i, 1), vtx(m, i, 2), 0.0, INFINITY, &x)) {
            h.count++;
            h.front += x.front;
            if (h.nearest < 0 || x.t < h.hit.t) {
                h.nearest = i;
                h.hit = x;
            }
        }
    }
    return h;
}

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static double rnd(void) /* [0, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1p-53;
}

static void random_unit(double d[3])
{
    double len;
    do {
        for (int i = 0; i < 3; i++)
            d[i] = 2.0 * rnd() - 1.0;
        len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (len < 0.1 || len > 1.0);
    for (int i = 0; i < 3; i++)
        d[i] /= len;
}

/* The interior edges of a mesh (those in two triangles), as pairs of vertex indices. */
static int interior_edges(const dmesh *m, uint32_t (*out)[2], int cap)
{
    int n = 0;
    for (int i = 0; i < m->triangle_count; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->t[3 * i + k], b = m->t[3 * i + (k + 1) % 3];
            if (a > b)
                continue; /* each edge once, from the triangle that runs it upwards */
            for (int j = 0; j < m->triangle_count; j++)
                for (int l = 0; l < 3; l++)
                    if (m->t[3 * j + l] == b && m->t[3 * j + (l + 1) % 3] == a) {
                        assert_true(n < cap);
                        out[n][0] = a;
                        out[n][1] = b;
                        n++;
                    }
        }
    return n;
}

/* Directions towards -z that the grid tests aim along: straight, dyadic oblique ones (the sheared
 * projection is then exact, so edge functions are exactly 0 and the tie rule decides) and ones with
 * inexact shears (rounding decides). */
static const double grid_dirs[][3] = {
    {0.0, 0.0, -1.0},     {0.25, 0.5, -1.0},   {-0.375, 0.125, -1.0}, {1.0, 0.0, -1.0},
    {0.3, -0.7, -1.0},    {-0.61, 0.23, -0.4}, {2.0, 1.7, -0.5},      {0.1, 0.2, -0.3},
    {-1.3, -0.9, -0.02},  {0.0, 0.0, 1.0},     {0.7, -0.2, 0.9},
};
enum { GRID_DIRS = sizeof grid_dirs / sizeof grid_dirs[0] };

/* A ray along d that reaches p at t = 10 (exact when p and d are dyadic). */
static void aim(const double p[3], const double d[3], double o[3])
{
    for (int i = 0; i < 3; i++)
        o[i] = p[i] - 10.0 * d[i];
}

/* ---- the exact edge function ------------------------------------------------------------------ */

static void diff_of_products_is_exact_where_rounding_gives_zero(void **state)
{
    (void)state;
    double a = 1.0 + 0x1p-30, c = 1.0 + 0x1p-29;
    /* (1 + 2^-30)^2 - (1 + 2^-29) = 2^-60, which the plain evaluation rounds away. */
    assert_true(a * a - c * 1.0 == 0.0);
    assert_true(bgi_cpu_diff_of_products(a, a, c, 1.0) == 0x1p-60);
    assert_true(bgi_cpu_diff_of_products(c, 1.0, a, a) == -0x1p-60);
    /* Exactly equal products stay 0; nonzero plain results are returned as they are. */
    assert_true(bgi_cpu_diff_of_products(3.0, 5.0, 5.0, 3.0) == 0.0);
    assert_true(bgi_cpu_diff_of_products(0.1, 0.3, 0.2, 0.1) == 0.1 * 0.3 - 0.2 * 0.1);
    /* The same at other scales (powers of two leave the products' relations alone)... */
    assert_true(bgi_cpu_diff_of_products(a * 0x1p-400, a, c * 0x1p-400, 1.0) == 0x1p-460);
    assert_true(bgi_cpu_diff_of_products(a * 0x1p200, a * 0x1p200, c * 0x1p200, 0x1p200) == 0x1p340);
    /* ...and outside the exact range the plain value (0) is kept rather than risk an overflow. */
    assert_true(bgi_cpu_diff_of_products(a * 0x1p600, a, c * 0x1p600, 1.0) == 0.0);
}

/* Two triangles share an edge whose line passes 2^-62 from the ray; the plain edge function
 * rounds to 0, where the tie rule alone would give the edge to the wrong triangle. */
static void exact_sign_decides_before_the_tie_rule(void **state)
{
    (void)state;
    /* Along -z the sheared frame is (x', y') = (y, x). In it P' = (1 + 2^-30, 1 + 2^-29) and
     * Q' = (-1, -(1 + 2^-30)): P' x Q' = -2^-60, so the ray passes to the right of P -> Q. */
    const double p[3] = {1.0 + 0x1p-29, 1.0 + 0x1p-30, 0.0}, q[3] = {-(1.0 + 0x1p-30), -1.0, 0.0};
    const double right[3] = {2.0, -2.0, 0.0}, left[3] = {-2.0, 2.0, 0.0};
    const double o[3] = {0.0, 0.0, 1.0}, d[3] = {0.0, 0.0, -1.0};
    bg_cpu_triangle_ray ray;
    bgi_cpu_triangle_ray_init(o, d, &ray);
    bg_cpu_triangle_hit h;
    /* (p, q, right) and (q, p, left): one winding, the edge run both ways. */
    assert_true(bgi_cpu_triangle_intersect(&ray, p, q, right, 0.0, INFINITY, &h));
    assert_true(h.t == 1.0);
    assert_false(bgi_cpu_triangle_intersect(&ray, q, p, left, 0.0, INFINITY, NULL));
    /* Mirrored (x <-> y): the sides of the ray and of the tie rule both turn over, and the mirror of
     * the triangle that had the ray has it. */
    const double pm[3] = {p[1], p[0], 0.0}, qm[3] = {q[1], q[0], 0.0};
    const double rm[3] = {right[1], right[0], 0.0}, lm[3] = {left[1], left[0], 0.0};
    assert_true(bgi_cpu_triangle_intersect(&ray, pm, qm, rm, 0.0, INFINITY, NULL));
    assert_false(bgi_cpu_triangle_intersect(&ray, qm, pm, lm, 0.0, INFINITY, NULL));
}

/* ---- single triangles -------------------------------------------------------------------------- */

static void front_side_t_and_barycentrics(void **state)
{
    (void)state;
    const double v0[3] = {0, 0, 0}, v1[3] = {4, 0, 0}, v2[3] = {0, 4, 0};
    const double o[3] = {1, 2, 3}, down[3] = {0, 0, -1}, up[3] = {0, 0, 0.5};
    bg_cpu_triangle_ray ray;
    bg_cpu_triangle_hit h;
    /* Counter-clockwise seen from +z: a ray coming down meets the front. */
    bgi_cpu_triangle_ray_init(o, down, &ray);
    assert_true(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, 0.0, INFINITY, &h));
    assert_true(h.front);
    assert_true(h.t == 3.0);
    assert_true(h.bary[0] == 0.25 && h.bary[1] == 0.25 && h.bary[2] == 0.5);
    /* From below: the back, and t in units of the unnormalised direction. */
    const double ob[3] = {1, 2, -3};
    bgi_cpu_triangle_ray_init(ob, up, &ray);
    assert_true(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, 0.0, INFINITY, &h));
    assert_false(h.front);
    assert_true(h.t == 6.0);
    /* The same triangle wound the other way swaps the sides, for every dominant axis. */
    for (int axis = 0; axis < 3; axis++)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, c[3] = {0, 0, 0}, oo[3] = {0.2, 0.2, 0.2}, dd[3] = {0, 0, 0};
            int u = (axis + 1) % 3, w = (axis + 2) % 3;
            b[u] = 1.0;
            c[w] = 1.0; /* (b - a) x (c - a) = e_axis */
            oo[axis] = -sgn * 2.0;
            dd[axis] = sgn;
            dd[u] = 0.01;
            bgi_cpu_triangle_ray_init(oo, dd, &ray);
            assert_true(bgi_cpu_triangle_intersect(&ray, a, b, c, 0.0, INFINITY, &h));
            assert_int_equal(h.front, sgn < 0);
            assert_true(bgi_cpu_triangle_intersect(&ray, a, c, b, 0.0, INFINITY, &h));
            assert_int_equal(h.front, sgn > 0);
        }
}

static void t_range_is_open_and_zero_directions_miss(void **state)
{
    (void)state;
    const double v0[3] = {0, 0, 0}, v1[3] = {4, 0, 0}, v2[3] = {0, 4, 0};
    const double o[3] = {1, 1, 2}, d[3] = {0, 0, -1}, zero[3] = {0, 0, 0}, bad[3] = {NAN, 0, -1};
    bg_cpu_triangle_ray ray;
    bgi_cpu_triangle_ray_init(o, d, &ray);
    assert_true(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, 1.0, 3.0, NULL));
    assert_false(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, 2.0, 3.0, NULL));
    assert_false(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, 0.0, 2.0, NULL));
    assert_true(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, -INFINITY, INFINITY, NULL));
    bgi_cpu_triangle_ray_init(o, zero, &ray);
    assert_false(ray.valid);
    assert_false(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, -INFINITY, INFINITY, NULL));
    bgi_cpu_triangle_ray_init(o, bad, &ray);
    assert_false(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, -INFINITY, INFINITY, NULL));
}

/* ---- shared edges and vertices --------------------------------------------------------------- */

/* Every interior edge's midpoint and every interior vertex of the grid, along every test direction,
 * hits exactly one triangle, at the right place. */
static void check_grid_exactly_one(const dmesh *m, const char *what)
{
    uint32_t(*edges)[2] = malloc(sizeof *edges * 3 * (size_t)m->triangle_count);
    assert_non_null(edges);
    int ne = interior_edges(m, edges, 3 * m->triangle_count);
    int checked = 0;
    for (int k = 0; k < GRID_DIRS; k++) {
        const double *d = grid_dirs[k];
        for (int e = 0; e < ne + m->vertex_count; e++) {
            double p[3], o[3];
            if (e < ne) {
                const double *a = m->v + 3 * edges[e][0], *b = m->v + 3 * edges[e][1];
                for (int i = 0; i < 3; i++)
                    p[i] = 0.5 * (a[i] + b[i]);
            } else {
                /* Only vertices away from the boundary have a full fan around them. */
                const double *v = m->v + 3 * (e - ne);
                const double *lo = m->v, *hi = m->v + 3 * (m->vertex_count - 1);
                if (v[0] == lo[0] || v[1] == lo[1] || v[0] == hi[0] || v[1] == hi[1])
                    continue;
                memcpy(p, v, sizeof p);
            }
            aim(p, d, o);
            hits h = cast(m, o, d);
            if (h.count != 1)
                fail_msg("%s: direction %d, %s %d at (%.17g, %.17g, %.17g): %d hits", what, k,
                         e < ne ? "edge" : "vertex", e < ne ? e : e - ne, p[0], p[1], p[2], h.count);
            assert_true(fabs(h.hit.t - 10.0) <= 1e-12 * 10.0);
            checked++;
        }
    }
    assert_true(checked > 100);
    free(edges);
}

static void grid_edges_and_vertices_hit_exactly_one_triangle(void **state)
{
    (void)state;
    const double origin[3] = {0, 0, 0}, moved[3] = {0.3, -0.7, 5.1}, far[3] = {1234.5678, -987.321, 0.0123};
    for (int alt = 0; alt < 2; alt++) {
        dmesh m = grid(8, 1.0, origin, alt);
        assert_int_equal(m.triangle_count, 128);
        check_grid_exactly_one(&m, alt ? "integer grid, alternating" : "integer grid");
        dmesh_free(&m);
        /* Coordinates no float or double holds exactly: 0.1 steps, translated. */
        m = grid(8, 0.1, moved, alt);
        check_grid_exactly_one(&m, alt ? "0.1 grid, alternating" : "0.1 grid");
        dmesh_free(&m);
        m = grid(8, 0.37, far, alt);
        check_grid_exactly_one(&m, alt ? "far grid, alternating" : "far grid");
        dmesh_free(&m);
    }
}

/* Random rays through the grid's inside, and rays a hair from its edges and vertices. */
static void grid_random_rays_hit_exactly_one_triangle(void **state)
{
    (void)state;
    const double moved[3] = {0.3, -0.7, 5.1};
    dmesh m = grid(8, 0.1, moved, false);
    int n = util_quick() ? 2000 : 20000;
    for (int i = 0; i < n; i++) {
        double p[3] = {moved[0] + 0.8 * (0.01 + 0.98 * rnd()), moved[1] + 0.8 * (0.01 + 0.98 * rnd()), moved[2]};
        if (i % 2) {
            /* Snap to a grid line or node, then move by a few units in the last place. */
            int gx = (int)floor((p[0] - moved[0]) / 0.1 + 0.5), gy = (int)floor((p[1] - moved[1]) / 0.1 + 0.5);
            const double *v = m.v + 3 * (gy * 9 + gx);
            if (i % 4 == 1)
                p[0] = v[0];
            else
                memcpy(p, v, sizeof p);
            p[0] += (double)((int)(rnd() * 7) - 3) * 0x1p-50;
            p[1] += (double)((int)(rnd() * 7) - 3) * 0x1p-50;
            /* A boundary edge has one triangle, which the tie rule (or rounding) may turn away. */
            const double *lo = m.v, *hi = m.v + 3 * (m.vertex_count - 1);
            if (p[0] <= lo[0] + 1e-9 || p[1] <= lo[1] + 1e-9 || p[0] >= hi[0] - 1e-9 || p[1] >= hi[1] - 1e-9)
                continue;
        }
        double d[3];
        random_unit(d);
        if (fabs(d[2]) < 0.05)
            continue;
        double o[3];
        aim(p, d, o);
        hits h = cast(&m, o, d);
        if (h.count != 1)
            fail_msg("ray %d at (%.17g, %.17g): %d hits", i, p[0], p[1], h.count);
    }
    dmesh_free(&m);
}

/* An octahedron with its vertices on the axes, counter-clockwise seen from outside. */
static dmesh octahedron(void)
{
    static const double v[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    dmesh m = {6, 8, malloc(sizeof v), malloc(sizeof(uint32_t) * 24)};
    assert_non_null(m.v);
    assert_non_null(m.t);
    memcpy(m.v, v, sizeof v);
    int n = 0;
    for (int sx = 0; sx < 2; sx++)
        for (int sy = 0; sy < 2; sy++)
            for (int sz = 0; sz < 2; sz++) {
                uint32_t a = (uint32_t)sx, b = 2 + (uint32_t)sy, c = 4 + (uint32_t)sz;
                bool flip = (sx + sy + sz) % 2 == 1; /* an odd number of negative axes mirrors it */
                m.t[n++] = a;
                m.t[n++] = flip ? c : b;
                m.t[n++] = flip ? b : c;
            }
    return m;
}

/* Rays from inside a closed convex mesh: through every vertex, every edge midpoint, every centroid
 * and random directions, each meets exactly one triangle (and it faces the ray's back side). */
static void check_closed_from(const dmesh *m, const double o[3], const char *what)
{
    int n = m->vertex_count + 3 * m->triangle_count + m->triangle_count + (util_quick() ? 200 : 2000);
    for (int r = 0; r < n; r++) {
        double p[3];
        if (r < m->vertex_count) {
            memcpy(p, m->v + 3 * r, sizeof p);
        } else if (r < m->vertex_count + 3 * m->triangle_count) {
            int e = r - m->vertex_count;
            const double *a = vtx(m, e / 3, e % 3), *b = vtx(m, e / 3, (e + 1) % 3);
            for (int i = 0; i < 3; i++)
                p[i] = 0.5 * (a[i] + b[i]);
        } else if (r < m->vertex_count + 4 * m->triangle_count) {
            int t = r - m->vertex_count - 3 * m->triangle_count;
            for (int i = 0; i < 3; i++)
                p[i] = (vtx(m, t, 0)[i] + vtx(m, t, 1)[i] + vtx(m, t, 2)[i]) / 3.0;
        } else {
            random_unit(p);
        }
        double d[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
        hits h = cast(m, o, d);
        if (h.count != 1)
            fail_msg("%s: ray %d towards (%.17g, %.17g, %.17g): %d hits", what, r, p[0], p[1], p[2], h.count);
        assert_false(h.hit.front);
    }
}

static void closed_meshes_have_no_holes_from_inside(void **state)
{
    (void)state;
    const double centre[3] = {0, 0, 0}, off[3] = {0.1, -0.2, 0.05};
    dmesh oct = octahedron();
    check_closed_from(&oct, centre, "octahedron");
    check_closed_from(&oct, off, "octahedron, off centre");
    dmesh_free(&oct);
    char why[256];
    for (int uvs = 0; uvs < 2; uvs++) {
        /* With uvs the seam's vertices are duplicated: the canonical order by position keeps the
         * triangles on both sides of the seam sharing their edges. */
        mesh_icosphere_desc desc = {2, 0, false, uvs == 1};
        mesh ico;
        assert_int_equal(mesh_icosphere(&desc, &ico, why, sizeof why), BG_OK);
        dmesh m = dmesh_from(&ico);
        check_closed_from(&m, centre, uvs ? "icosphere with seams" : "icosphere");
        check_closed_from(&m, off, uvs ? "icosphere with seams, off centre" : "icosphere, off centre");
        dmesh_free(&m);
        mesh_free(&ico);
    }
}

/* Lines from outside a closed mesh: every one enters as often as it leaves (each crossing is found
 * once: a hole would drop one, a doubled edge add one). Aimed at every vertex, at edge midpoints, and
 * at random points. */
static void check_parity(const dmesh *m, double radius, const char *what)
{
    int n = m->vertex_count + m->triangle_count + (util_quick() ? 200 : 2000);
    int crossings = 0;
    for (int r = 0; r < n; r++) {
        double p[3], o[3], d[3];
        if (r < m->vertex_count) {
            memcpy(p, m->v + 3 * r, sizeof p);
        } else if (r < m->vertex_count + m->triangle_count) {
            int t = r - m->vertex_count;
            const double *a = vtx(m, t, r % 3), *b = vtx(m, t, (r + 1) % 3);
            for (int i = 0; i < 3; i++)
                p[i] = 0.5 * (a[i] + b[i]);
        } else {
            random_unit(p);
            for (int i = 0; i < 3; i++)
                p[i] *= 0.5 * radius * rnd();
        }
        random_unit(d);
        for (int i = 0; i < 3; i++)
            o[i] = p[i] - 3.0 * radius * d[i];
        hits h = cast(m, o, d);
        if (h.count % 2 != 0 || 2 * h.front != h.count)
            fail_msg("%s: line %d through (%.17g, %.17g, %.17g): %d hits, %d of them front", what, r, p[0], p[1],
                     p[2], h.count, h.front);
        crossings += h.count;
    }
    assert_true(crossings >= n); /* most lines meet the mesh */
}

static void closed_meshes_are_entered_as_often_as_left(void **state)
{
    (void)state;
    char why[256];
    mesh knot;
    mesh_torus_knot_desc kd = {0, 0, 64, 8, false, false};
    assert_int_equal(mesh_torus_knot(&kd, &knot, why, sizeof why), BG_OK);
    dmesh m = dmesh_from(&knot);
    check_parity(&m, 1.6, "torus knot");
    dmesh_free(&m);
    mesh_free(&knot);

    mesh ico;
    mesh_icosphere_desc id = {3, 0, false, true};
    assert_int_equal(mesh_icosphere(&id, &ico, why, sizeof why), BG_OK);
    m = dmesh_from(&ico);
    check_parity(&m, 1.0, "icosphere with seams");
    dmesh_free(&m);
    mesh_free(&ico);

    mesh bunny;
    if (ply_mesh_read("tests/data/bunny.ply", &bunny, why, sizeof why) != BG_OK)
        fail_msg("%s (the tests run from the repository root)", why);
    m = dmesh_from(&bunny);
    /* Around the bunny's middle: its bounds are about [-5, 5] x [0, 9.7] x [-3.7, 3.8]. */
    for (int i = 0; i < m.vertex_count; i++)
        m.v[3 * i + 1] -= 4.8;
    check_parity(&m, 6.0, "bunny");
    dmesh_free(&m);
    mesh_free(&bunny);
}

/* ---- agreement with a reference -------------------------------------------------------------- */

static void t_and_barycentrics_match_a_reference(void **state)
{
    (void)state;
    int n = util_quick() ? 2000 : 20000, hits_seen = 0, misses_seen = 0;
    double worst_t = 0.0, worst_b = 0.0;
    for (int i = 0; i < n; i++) {
        double v[3][3], o[3], d[3], target[3];
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 3; c++)
                v[k][c] = 4.0 * rnd() - 2.0;
        /* A point of the triangle's plane at random barycentrics, some outside. */
        double b1 = 1.4 * rnd() - 0.2, b2 = 1.4 * rnd() - 0.2, b0 = 1.0 - b1 - b2;
        for (int c = 0; c < 3; c++)
            target[c] = b0 * v[0][c] + b1 * v[1][c] + b2 * v[2][c];
        random_unit(d);
        double dist = 1.0 + 9.0 * rnd();
        for (int c = 0; c < 3; c++)
            o[c] = target[c] - dist * d[c];
        /* The reference: the plane and the sub-triangle areas, in long double. */
        long double e1[3], e2[3], nrm[3], w[3], p[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = (long double)v[1][c] - v[0][c];
            e2[c] = (long double)v[2][c] - v[0][c];
        }
        nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
        nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
        nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
        long double nn = nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2];
        long double nd = nrm[0] * d[0] + nrm[1] * d[1] + nrm[2] * d[2];
        /* Grazing rays and slivers are ill-conditioned for any method; the fill-rule tests cover them. */
        if (fabsl(nd) < 0.2L * sqrtl(nn) || nn < 0.01L)
            continue;
        long double t_ref = (nrm[0] * (v[0][0] - (long double)o[0]) + nrm[1] * (v[0][1] - (long double)o[1]) +
                             nrm[2] * (v[0][2] - (long double)o[2])) /
                            nd;
        for (int c = 0; c < 3; c++)
            p[c] = o[c] + t_ref * d[c];
        for (int k = 0; k < 3; k++) {
            const double *a = v[(k + 1) % 3], *b = v[(k + 2) % 3];
            long double pa[3], pb[3];
            for (int c = 0; c < 3; c++) {
                pa[c] = a[c] - p[c];
                pb[c] = b[c] - p[c];
            }
            w[k] = (nrm[0] * (pa[1] * pb[2] - pa[2] * pb[1]) + nrm[1] * (pa[2] * pb[0] - pa[0] * pb[2]) +
                    nrm[2] * (pa[0] * pb[1] - pa[1] * pb[0])) /
                   nn;
        }
        bool inside = w[0] > 1e-9L && w[1] > 1e-9L && w[2] > 1e-9L;
        bool outside = w[0] < -1e-9L || w[1] < -1e-9L || w[2] < -1e-9L;
        bg_cpu_triangle_ray ray;
        bg_cpu_triangle_hit h;
        bgi_cpu_triangle_ray_init(o, d, &ray);
        bool hit = bgi_cpu_triangle_intersect(&ray, v[0], v[1], v[2], 0.0, INFINITY, &h);
        if (outside) {
            assert_false(hit);
            misses_seen++;
            continue;
        }
        if (!inside)
            continue;
        assert_true(hit);
        hits_seen++;
        assert_int_equal(h.front, nd < 0);
        double et = fabs(h.t - (double)t_ref) / (double)t_ref;
        worst_t = et > worst_t ? et : worst_t;
        for (int k = 0; k < 3; k++) {
            double eb = fabs(h.bary[k] - (double)w[k]);
            worst_b = eb > worst_b ? eb : worst_b;
        }
    }
    /* Measured: 4.9e-16 for t (relative), 8.3e-15 for the barycentrics; a margin of 12 or more. */
    if (!(worst_t < 1e-14 && worst_b < 1e-13))
        fail_msg("worst relative t error %g, worst barycentric error %g", worst_t, worst_b);
    assert_true(hits_seen > n / 10 && misses_seen > n / 20);
}

/* ---- degenerate triangles and extreme scales ------------------------------------------------- */

static void degenerate_triangles_are_never_hit(void **state)
{
    (void)state;
    /* Exactly collinear points (dyadic steps, so the differences are exact), repeated vertices, a
     * point: aimed at along many directions, and at random. */
    const double a[3] = {0.5, -0.25, 1.0}, e[3] = {0.375, 0.125, -0.0625};
    double b[3], c[3], c3[3];
    for (int i = 0; i < 3; i++) {
        b[i] = a[i] + e[i];
        c[i] = a[i] + 2.0 * e[i];
        c3[i] = a[i] + 3.0 * e[i];
    }
    const double *tris[][3] = {{a, b, c}, {a, c3, b}, {b, a, c3}, {a, a, c}, {a, c, c}, {c, a, c}, {a, a, a}};
    int n = util_quick() ? 300 : 3000;
    for (size_t k = 0; k < sizeof tris / sizeof tris[0]; k++)
        for (int r = 0; r < n; r++) {
            double p[3], d[3], o[3];
            /* Points on the segment (some exactly at a vertex), or near it. */
            double s = r % 3 == 0 ? (double)(r % 4) : 3.0 * rnd();
            for (int i = 0; i < 3; i++)
                p[i] = a[i] + s * e[i] + (r % 5 == 0 ? 1e-3 * (rnd() - 0.5) : 0.0);
            random_unit(d);
            aim(p, d, o);
            bg_cpu_triangle_ray ray;
            bgi_cpu_triangle_ray_init(o, d, &ray);
            if (bgi_cpu_triangle_intersect(&ray, tris[k][0], tris[k][1], tris[k][2], -INFINITY, INFINITY, NULL))
                fail_msg("degenerate triangle %zu hit by ray %d", k, r);
        }
}

/* The grid at scales from 1e-30 to 1e30 (and placed away from the origin by as much): rays at its
 * edges hit exactly one triangle with finite t and barycentrics; nothing anywhere is NaN. */
static void extreme_scales_stay_finite(void **state)
{
    (void)state;
    for (int e = -30; e <= 30; e += 10) {
        double s = pow(10.0, e);
        const double offset[3] = {0.3 * s, -0.2 * s, 1.7 * s};
        dmesh m = grid(4, s, offset, false);
        uint32_t edges[64][2];
        int ne = interior_edges(&m, edges, 64);
        for (int k = 0; k < GRID_DIRS; k++)
            for (int i = 0; i < ne; i++) {
                double p[3], d[3], o[3];
                for (int c = 0; c < 3; c++) {
                    p[c] = 0.5 * (m.v[3 * edges[i][0] + c] + m.v[3 * edges[i][1] + c]);
                    d[c] = grid_dirs[k][c] * s; /* directions of the scene's size too */
                }
                aim(p, d, o);
                hits h = cast(&m, o, d);
                if (h.count != 1)
                    fail_msg("scale 1e%d, direction %d, edge %d: %d hits", e, k, i, h.count);
                assert_true(isfinite(h.hit.t) && fabs(h.hit.t - 10.0) < 1e-9);
                double sum = 0.0;
                for (int c = 0; c < 3; c++) {
                    assert_true(h.hit.bary[c] >= 0.0 && h.hit.bary[c] <= 1.0);
                    sum += h.hit.bary[c];
                }
                assert_true(fabs(sum - 1.0) < 1e-12);
            }
        /* A unit ray at the tiny or huge grid from the origin: a hit or a miss, never a NaN. */
        for (int r = 0; r < 200; r++) {
            double o[3] = {0, 0, 0}, d[3];
            random_unit(d);
            bg_cpu_triangle_ray ray;
            bg_cpu_triangle_hit hit;
            bgi_cpu_triangle_ray_init(o, d, &ray);
            for (int t = 0; t < m.triangle_count; t++)
                if (bgi_cpu_triangle_intersect(&ray, vtx(&m, t, 0), vtx(&m, t, 1), vtx(&m, t, 2), 0.0, INFINITY, &hit))
                    assert_true(isfinite(hit.t) && isfinite(hit.bary[0]) && isfinite(hit.bary[1]) &&
                                isfinite(hit.bary[2]));
        }
        dmesh_free(&m);
    }
    /* A triangle of size 1e-30 at distance 1: its vertices differ below the origin's rounding, so the
     * projection collapses; the answer is a miss, not a NaN. */
    const double v0[3] = {1.0, 1.0, 1.0}, v1[3] = {1.0 + 1e-30, 1.0, 1.0}, v2[3] = {1.0, 1.0 + 1e-30, 1.0};
    const double o[3] = {0.1, 0.2, 0.3}, d[3] = {0.9, 0.8, 0.7};
    bg_cpu_triangle_ray ray;
    bgi_cpu_triangle_ray_init(o, d, &ray);
    assert_false(bgi_cpu_triangle_intersect(&ray, v0, v1, v2, -INFINITY, INFINITY, NULL));
}

/* ---- the GLSL mirror ------------------------------------------------------------------------- */

#define GPU_TRIS 128
#define GPU_RAY_WIDTH 64

/* Runs bg_triangle.glsl over rays (origin, direction as floats) against the 128 triangles of m:
 * per ray the hit count, the nearest t and triangle, and whether it is a front hit. */
typedef struct gpu_rays {
    int count, height;
    float *o, *d;  /* RGBA texels, count rounded up to whole rows */
    float *result; /* count, t, triangle, front */
} gpu_rays;

static const char *const gpu_main =
    "vec3 o = texture2D(rays_o, macs_uv).xyz;\n"
    "vec3 d = texture2D(rays_d, macs_uv).xyz;\n"
    "mat3 perm;\n"
    "vec3 shear;\n"
    "float count = 0.0, best = 0.0, best_id = -1.0, best_front = 0.0;\n"
    "if (bg_triangle_setup(d, perm, shear)) {\n"
    "    for (int k = 0; k < 128; k++) {\n"
    "        float y = (float(k) + 0.5) / 128.0;\n"
    "        vec3 v0 = texture2D(tris, vec2(0.5 / 3.0, y)).xyz;\n"
    "        vec3 v1 = texture2D(tris, vec2(1.5 / 3.0, y)).xyz;\n"
    "        vec3 v2 = texture2D(tris, vec2(2.5 / 3.0, y)).xyz;\n"
    "        float t;\n"
    "        vec3 b;\n"
    "        bool front;\n"
    "        if (bg_triangle_intersect(o, perm, shear, v0, v1, v2, 0.0, 1e30, t, b, front)) {\n"
    "            count += 1.0;\n"
    "            if (best_id < 0.0 || t < best) {\n"
    "                best = t;\n"
    "                best_id = float(k);\n"
    "                best_front = front ? 1.0 : 0.0;\n"
    "            }\n"
    "        }\n"
    "    }\n"
    "}\n";

static void gpu_run(macs_context *ctx, const dmesh *m, gpu_rays *r)
{
    assert_int_equal(m->triangle_count, GPU_TRIS);
    float tri[GPU_TRIS * 3 * 4];
    for (int t = 0; t < GPU_TRIS; t++)
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 4; c++)
                tri[(t * 3 + k) * 4 + c] = c < 3 ? (float)vtx(m, t, k)[c] : 1.0f;
    macs_texture_desc td = {3, GPU_TRIS, 0, 0, 0, tri, 0};
    macs_texture_desc od = {GPU_RAY_WIDTH, r->height, 0, 0, 0, r->o, 0};
    macs_texture_desc dd = {GPU_RAY_WIDTH, r->height, 0, 0, 0, r->d, 0};
    macs_texture *in[3], *out = util_texture(ctx, GPU_RAY_WIDTH, r->height, MACS_FORMAT_RGBA32F);
    assert_int_equal(macs_texture_create(ctx, &od, &in[0]), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &dd, &in[1]), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &td, &in[2]), MACS_OK);

    bg_allocator none = {0};
    gpu_text functions;
    bgi_gpu_text_init(&functions, &none);
    const char *seen[8];
    int seen_count = 0;
    assert_true(bgi_gpu_text_snippet(&functions, "bg_triangle.glsl", seen, &seen_count, 8));
    assert_false(functions.failed);

    macs_input_desc inputs[3] = {{"rays_o"}, {"rays_d"}, {"tris"}};
    macs_output_desc output = {"hits", "vec4(count, best, best_id, best_front)"};
    macs_pass_desc pd = {0};
    pd.functions = functions.s;
    pd.main = gpu_main;
    pd.inputs = inputs;
    pd.input_count = 3;
    pd.input_textures = in;
    pd.outputs = &output;
    pd.output_count = 1;
    pd.output_textures = &out;
    macs_pass *pass = NULL;
    if (macs_pass_create(ctx, &pd, &pass) != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(out, r->result, 0), MACS_OK);
    macs_pass_destroy(pass);
    bgi_gpu_text_free(&functions);
    for (int i = 0; i < 3; i++)
        macs_texture_destroy(in[i]);
    macs_texture_destroy(out);
}

static void gpu_rays_alloc(gpu_rays *r, int count)
{
    r->count = count;
    r->height = (count + GPU_RAY_WIDTH - 1) / GPU_RAY_WIDTH;
    size_t n = (size_t)GPU_RAY_WIDTH * (size_t)r->height * 4;
    r->o = calloc(n, sizeof(float));
    r->d = calloc(n, sizeof(float)); /* unused texels keep d = 0: no triangle can be hit */
    r->result = calloc(n, sizeof(float));
    assert_true(r->o && r->d && r->result);
}

static void gpu_rays_free(gpu_rays *r)
{
    free(r->o);
    free(r->d);
    free(r->result);
}

/* The largest relative difference of the GPU's t from the CPU's (both on the same float rays and
 * vertices) over the grids, printed and asserted below GPU_T_REL. */
static double gpu_worst_t = 0.0;

/* Measured on llvmpipe: 2.7e-7 (two float steps) over every grid and direction; 2^-18 = 3.8e-6
 * leaves a margin of 14 for GPUs whose division or fused steps round less exactly. */
#define GPU_T_REL 0x1p-18

static void check_gpu_grid(macs_context *ctx, const dmesh *m, const char *what)
{
    uint32_t(*edges)[2] = malloc(sizeof *edges * 3 * (size_t)m->triangle_count);
    assert_non_null(edges);
    int ne = interior_edges(m, edges, 3 * m->triangle_count);
    const double *lo = m->v, *hi = m->v + 3 * (m->vertex_count - 1);
    /* Every interior edge midpoint and interior vertex along every direction, as float rays. */
    gpu_rays r;
    gpu_rays_alloc(&r, GRID_DIRS * (ne + m->vertex_count));
    int n = 0;
    for (int k = 0; k < GRID_DIRS; k++)
        for (int e = 0; e < ne + m->vertex_count; e++) {
            double p[3], o[3];
            if (e < ne) {
                for (int i = 0; i < 3; i++)
                    p[i] = 0.5 * (m->v[3 * edges[e][0] + i] + m->v[3 * edges[e][1] + i]);
            } else {
                const double *v = m->v + 3 * (e - ne);
                if (v[0] == lo[0] || v[1] == lo[1] || v[0] == hi[0] || v[1] == hi[1])
                    continue;
                memcpy(p, v, sizeof p);
            }
            aim(p, grid_dirs[k], o);
            for (int i = 0; i < 3; i++) {
                r.o[4 * n + i] = (float)o[i];
                r.d[4 * n + i] = (float)grid_dirs[k][i];
            }
            n++;
        }
    gpu_run(ctx, m, &r);
    for (int i = 0; i < n; i++) {
        const float *g = r.result + 4 * i;
        double o[3] = {r.o[4 * i], r.o[4 * i + 1], r.o[4 * i + 2]}, d[3] = {r.d[4 * i], r.d[4 * i + 1], r.d[4 * i + 2]};
        hits h = cast(m, o, d);
        if (g[0] != 1.0f || h.count != 1)
            fail_msg("%s: ray %d from (%.9g, %.9g, %.9g) along (%g, %g, %g): %g GPU hits, %d CPU hits", what, i, o[0],
                     o[1], o[2], d[0], d[1], d[2], g[0], h.count);
        double rel = fabs(g[1] - h.hit.t) / h.hit.t;
        gpu_worst_t = rel > gpu_worst_t ? rel : gpu_worst_t;
        if (!(rel <= GPU_T_REL))
            fail_msg("%s: ray %d: GPU t %.9g, CPU t %.17g", what, i, g[1], h.hit.t);
        assert_true(g[3] == (h.hit.front ? 1.0f : 0.0f));
    }
    gpu_rays_free(&r);
    free(edges);
}

static void gpu_grid_edges_and_vertices_hit_exactly_one_triangle(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    const double origin[3] = {0, 0, 0}, moved[3] = {0.3, -0.7, 5.1}, far[3] = {123.45, -98.7, 0.0123};
    for (int alt = 0; alt < 2; alt++) {
        dmesh m = grid(8, 1.0, origin, alt);
        check_gpu_grid(ctx, &m, alt ? "integer grid, alternating" : "integer grid");
        dmesh_free(&m);
        m = grid(8, 0.1, moved, alt);
        check_gpu_grid(ctx, &m, alt ? "0.1 grid, alternating" : "0.1 grid");
        dmesh_free(&m);
        m = grid(8, 0.37, far, alt);
        check_gpu_grid(ctx, &m, alt ? "far grid, alternating" : "far grid");
        dmesh_free(&m);
    }
    print_message("GPU vs CPU t: worst relative difference %.3g (asserted <= %.3g)\n", gpu_worst_t, GPU_T_REL);
    macs_context_destroy(ctx);
}

/* The invariant behind the fill rule on the GPU, at the function itself: the edge function of b -> a is
 * exactly minus that of a -> b. The coordinates are chosen so that a compiler fusing the naive
 * p.x q.y - p.y q.x into an fma would break it: (1 + 2^-12)^2 - (1 + 2^-11) is 2^-24 fused and 0
 * unfused, and the fused form rounds the other product in the other order. Whether this GL fuses is
 * printed (the naive pair then differs); the canonical pair must agree either way. */
static void gpu_edge_function_is_negated_exactly(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_allocator none = {0};
    gpu_text functions;
    bgi_gpu_text_init(&functions, &none);
    const char *seen[8];
    int seen_count = 0;
    assert_true(bgi_gpu_text_snippet(&functions, "bg_triangle.glsl", seen, &seen_count, 8));
    macs_uniform_desc u[] = {{"pa", MACS_UNIFORM_VEC2, 0}, {"pb", MACS_UNIFORM_VEC2, 0}};
    macs_output_desc o[] = {{"canonical", "vec4(wab, wba, e.x + f.x, e.y + f.y)"},
                            {"naive", "vec4(pa.x * pb.y - pa.y * pb.x, pb.x * pa.y - pb.y * pa.x, 0.0, 0.0)"}};
    macs_texture *out[2] = {util_texture(ctx, 1, 1, MACS_FORMAT_RGBA32F), util_texture(ctx, 1, 1, MACS_FORMAT_RGBA32F)};
    macs_pass_desc pd = {0};
    pd.functions = functions.s;
    pd.main = "vec2 e, f;\n"
              "float wab = bg_triangle_edge(vec3(0.0), vec3(1.0, 0.0, 0.0), pa, pb, e);\n"
              "float wba = bg_triangle_edge(vec3(1.0, 0.0, 0.0), vec3(0.0), pb, pa, f);\n";
    pd.uniforms = u;
    pd.uniform_count = 2;
    pd.outputs = o;
    pd.output_count = 2;
    pd.output_textures = out;
    macs_pass *pass = NULL;
    if (macs_pass_create(ctx, &pd, &pass) != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
    const float pa[2] = {1.0f + 0x1p-12f, 1.0f + 0x1p-11f}, pb[2] = {1.0f, 1.0f + 0x1p-12f};
    assert_int_equal(macs_pass_set_uniform(pass, "pa", pa), MACS_OK);
    assert_int_equal(macs_pass_set_uniform(pass, "pb", pb), MACS_OK);
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    float c[4], n[4];
    assert_int_equal(macs_texture_read(out[0], c, 0), MACS_OK);
    assert_int_equal(macs_texture_read(out[1], n, 0), MACS_OK);
    print_message("naive edge functions a->b %g, b->a %g (%s); canonical %g, %g\n", n[0], n[1],
                  n[0] == -n[1] ? "this GL does not fuse them" : "this GL fuses them", c[0], c[1]);
    assert_true(c[0] == -c[1]);
    assert_true(c[2] == 0.0f && c[3] == 0.0f); /* the directions too */
    macs_pass_destroy(pass);
    bgi_gpu_text_free(&functions);
    macs_context_destroy(ctx);
}

int main(void)
{
    /* One group (one summary line for tests/run_suites.sh); only the GLSL test uses the context. */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(diff_of_products_is_exact_where_rounding_gives_zero),
        cmocka_unit_test(exact_sign_decides_before_the_tie_rule),
        cmocka_unit_test(front_side_t_and_barycentrics),
        cmocka_unit_test(t_range_is_open_and_zero_directions_miss),
        cmocka_unit_test(grid_edges_and_vertices_hit_exactly_one_triangle),
        cmocka_unit_test(grid_random_rays_hit_exactly_one_triangle),
        cmocka_unit_test(closed_meshes_have_no_holes_from_inside),
        cmocka_unit_test(closed_meshes_are_entered_as_often_as_left),
        cmocka_unit_test(t_and_barycentrics_match_a_reference),
        cmocka_unit_test(degenerate_triangles_are_never_hit),
        cmocka_unit_test(extreme_scales_stay_finite),
        cmocka_unit_test(gpu_edge_function_is_negated_exactly),
        cmocka_unit_test(gpu_grid_edges_and_vertices_hit_exactly_one_triangle),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
