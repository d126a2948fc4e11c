/* Procedural meshes (meshes.h). Every builder works in double and rounds once to the mesh's floats;
 * sizes are checked in 64 bits against MESH_MAX_TRIANGLES before anything is allocated. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshes.h"

#define PI 3.14159265358979323846
#define ICOSPHERE_MAX_LEVEL 9 /* 20 * 4^9 = 5242880 triangles; level 10 passes MESH_MAX_TRIANGLES */

void mesh_free(mesh *m)
{
    if (!m)
        return;
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

bg_status mesh_fail(char *why, size_t why_size, bg_status status, const char *format, ...)
{
    if (why && why_size > 0) {
        va_list args;
        va_start(args, format);
        vsnprintf(why, why_size, format, args);
        va_end(args);
    }
    return status;
}

/* malloc of n elements of size bytes, never asking for 0 bytes (which may give NULL). */
static void *alloc_array(size_t n, size_t size)
{
    return malloc((n ? n : 1) * size);
}

bg_status mesh_alloc(mesh *m, uint32_t vertex_count, uint32_t triangle_count, bool normals, bool uvs,
                     const char *what, char *why, size_t why_size)
{
    memset(m, 0, sizeof *m);
    m->vertex_count = vertex_count;
    m->triangle_count = triangle_count;
    m->positions = alloc_array((size_t)vertex_count * 3, sizeof(float));
    m->indices = alloc_array((size_t)triangle_count * 3, sizeof(uint32_t));
    m->normals = normals ? alloc_array((size_t)vertex_count * 3, sizeof(float)) : NULL;
    m->uvs = uvs ? alloc_array((size_t)vertex_count * 2, sizeof(float)) : NULL;
    if (!m->positions || !m->indices || (normals && !m->normals) || (uvs && !m->uvs)) {
        mesh_free(m);
        return mesh_fail(why, why_size, BG_ERR_OUT_OF_MEMORY, "%s: no memory for %u vertices and %u triangles",
                         what, (unsigned)vertex_count, (unsigned)triangle_count);
    }
    return BG_OK;
}

static void normalize3(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= len;
    v[1] /= len;
    v[2] /= len;
}

/* ---- icosphere ------------------------------------------------------------------------------- */

/* The growing icosphere in double: positions, triangles, and the midpoint of each split edge. */
typedef struct sphere_build {
    double *pos;     /* 3 per vertex, room for cap vertices */
    uint32_t count;  /* vertices so far */
    uint32_t cap;
    uint32_t *tris;  /* 3 per triangle */
    uint32_t tri_count;
    uint64_t *keys;  /* edge midpoint table: key (low << 32 | high) + 1, 0 empty */
    uint32_t *mids;
    uint64_t mask;
} sphere_build;

static uint32_t add_vertex(sphere_build *b, double x, double y, double z)
{
    double *p = b->pos + 3 * (size_t)b->count;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return b->count++;
}

/* The vertex halfway between a and b on the sphere, made once per edge (either direction). */
static uint32_t midpoint(sphere_build *b, uint32_t a, uint32_t c)
{
    uint32_t lo = a < c ? a : c, hi = a < c ? c : a;
    uint64_t key = ((uint64_t)lo << 32 | hi) + 1;
    uint64_t slot = (key * 0x9E3779B97F4A7C15ull) & b->mask;
    while (b->keys[slot] != 0) {
        if (b->keys[slot] == key)
            return b->mids[slot];
        slot = (slot + 1) & b->mask;
    }
    const double *pa = b->pos + 3 * (size_t)a, *pc = b->pos + 3 * (size_t)c;
    double m[3] = {(pa[0] + pc[0]) * 0.5, (pa[1] + pc[1]) * 0.5, (pa[2] + pc[2]) * 0.5};
    normalize3(m);
    b->keys[slot] = key;
    b->mids[slot] = add_vertex(b, m[0], m[1], m[2]);
    return b->mids[slot];
}

/* The icosahedron with its poles on the y axis: an upper ring of five vertices at height 1/sqrt(5)
 * and longitudes 72 k degrees (measured from +z towards +x, as the spherical mapping's u), and a lower
 * ring at -1/sqrt(5) turned by 36 degrees. */
static void icosahedron(sphere_build *b)
{
    double y = 1.0 / sqrt(5.0), r = 2.0 / sqrt(5.0);
    add_vertex(b, 0.0, 1.0, 0.0);
    add_vertex(b, 0.0, -1.0, 0.0);
    for (int k = 0; k < 5; k++)
        add_vertex(b, r * sin(2.0 * PI * k / 5.0), y, r * cos(2.0 * PI * k / 5.0));
    for (int k = 0; k < 5; k++)
        add_vertex(b, r * sin(2.0 * PI * (k + 0.5) / 5.0), -y, r * cos(2.0 * PI * (k + 0.5) / 5.0));
    uint32_t *t = b->tris;
    for (uint32_t k = 0; k < 5; k++) {
        uint32_t u0 = 2 + k, u1 = 2 + (k + 1) % 5, l0 = 7 + k, l1 = 7 + (k + 1) % 5;
        uint32_t rows[4][3] = {{0, u0, u1}, {u1, u0, l0}, {u1, l0, l1}, {1, l1, l0}};
        for (int i = 0; i < 4; i++, t += 3)
            memcpy(t, rows[i], sizeof rows[i]);
    }
    b->tri_count = 20;
}

/* Splits every triangle into four (the corners and the three edge midpoints), keeping the winding. */
static bool subdivide(sphere_build *b, uint32_t *scratch)
{
    uint64_t edges = (uint64_t)b->tri_count * 3 / 2, size = 1;
    while (size < 2 * edges)
        size *= 2;
    b->keys = calloc((size_t)size, sizeof *b->keys);
    b->mids = malloc((size_t)size * sizeof *b->mids);
    if (!b->keys || !b->mids)
        return false;
    b->mask = size - 1;
    uint32_t *out = scratch;
    for (uint32_t i = 0; i < b->tri_count; i++) {
        const uint32_t *t = b->tris + 3 * (size_t)i;
        uint32_t ab = midpoint(b, t[0], t[1]), bc = midpoint(b, t[1], t[2]), ca = midpoint(b, t[2], t[0]);
        uint32_t rows[4][3] = {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}};
        for (int k = 0; k < 4; k++, out += 3)
            memcpy(out, rows[k], sizeof rows[k]);
    }
    b->tri_count *= 4;
    memcpy(b->tris, scratch, (size_t)b->tri_count * 3 * sizeof *b->tris);
    free(b->keys);
    free(b->mids);
    b->keys = NULL;
    b->mids = NULL;
    return true;
}

/* The spherical mapping of docs/shading.md 4 (u = 0.5 on the y axis). */
static void spherical_uv(const double p[3], double uv[2])
{
    uv[0] = (p[0] == 0.0 && p[2] == 0.0) ? 0.5 : 0.5 + atan2(p[0], p[2]) / (2.0 * PI);
    double s = p[1] < -1.0 ? -1.0 : (p[1] > 1.0 ? 1.0 : p[1]);
    uv[1] = 0.5 + asin(s) / PI;
}

/* Gives each triangle uvs that do not run the long way round: on a triangle across the seam
 * (u spanning more than half a turn) the vertices with u < 0.5 are replaced by copies at u + 1, one
 * copy per vertex; a pole (u undefined) gets a copy per triangle at the mean u of the other two
 * corners (the first triangle keeps the original). uv holds 2 doubles per vertex, with room for the
 * copies, which add_vertex appends. */
static void fix_seams(sphere_build *b, double *uv, uint32_t *copy)
{
    uint32_t base = b->count;
    for (uint32_t v = 0; v < base; v++)
        copy[v] = UINT32_MAX;
    for (uint32_t i = 0; i < b->tri_count; i++) {
        uint32_t *t = b->tris + 3 * (size_t)i;
        double lo = 2.0, hi = -1.0;
        for (int k = 0; k < 3; k++) {
            if (t[k] < 2)
                continue; /* a pole */
            double u = uv[2 * t[k]];
            lo = u < lo ? u : lo;
            hi = u > hi ? u : hi;
        }
        if (hi - lo <= 0.5)
            continue;
        for (int k = 0; k < 3; k++) {
            uint32_t v = t[k];
            if (v < 2 || uv[2 * v] >= 0.5)
                continue;
            if (copy[v] == UINT32_MAX) {
                const double *p = b->pos + 3 * (size_t)v;
                copy[v] = add_vertex(b, p[0], p[1], p[2]);
                uv[2 * copy[v]] = uv[2 * v] + 1.0;
                uv[2 * copy[v] + 1] = uv[2 * v + 1];
            }
            t[k] = copy[v];
        }
    }
    bool pole_used[2] = {false, false};
    for (uint32_t i = 0; i < b->tri_count; i++) {
        uint32_t *t = b->tris + 3 * (size_t)i;
        for (int k = 0; k < 3; k++) {
            uint32_t v = t[k];
            if (v >= 2)
                continue;
            double u = 0.5 * (uv[2 * t[(k + 1) % 3]] + uv[2 * t[(k + 2) % 3]]);
            if (pole_used[v]) {
                const double *p = b->pos + 3 * (size_t)v;
                t[k] = add_vertex(b, p[0], p[1], p[2]);
            }
            pole_used[v] = true;
            uv[2 * t[k]] = u;
            uv[2 * t[k] + 1] = uv[2 * v + 1];
        }
    }
}

static void sphere_build_free(sphere_build *b, double *uv, uint32_t *scratch)
{
    free(b->pos);
    free(b->tris);
    free(b->keys);
    free(b->mids);
    free(uv);
    free(scratch);
}

bg_status mesh_icosphere(const mesh_icosphere_desc *desc, mesh *out, char *why, size_t why_size)
{
    static const char *what = "mesh_icosphere";
    if (!out)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: out is NULL", what);
    memset(out, 0, sizeof *out);
    mesh_icosphere_desc d = {0, 0, false, false};
    if (desc)
        d = *desc;
    if (d.level < 0)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: desc.level is %d; it must be 0 .. %d", what,
                         d.level, ICOSPHERE_MAX_LEVEL);
    if (d.min_triangles > 0) {
        if (d.level != 0)
            return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                             "%s: desc.level (%d) and desc.min_triangles (%u) are both set; give one", what, d.level,
                             (unsigned)d.min_triangles);
        while (d.level <= ICOSPHERE_MAX_LEVEL && (20ull << (2 * d.level)) < d.min_triangles)
            d.level++;
        if (d.level > ICOSPHERE_MAX_LEVEL)
            return mesh_fail(why, why_size, BG_ERR_LIMIT,
                             "%s: desc.min_triangles is %u; the largest icosphere (level %d) has %u triangles", what,
                             (unsigned)d.min_triangles, ICOSPHERE_MAX_LEVEL, 20u << (2 * ICOSPHERE_MAX_LEVEL));
    }
    if (d.level > ICOSPHERE_MAX_LEVEL)
        return mesh_fail(why, why_size, BG_ERR_LIMIT,
                         "%s: desc.level is %d; it must be 0 .. %d (20 * 4^level triangles: level %d would give "
                         "%u, more than MESH_MAX_TRIANGLES, %u)",
                         what, d.level, ICOSPHERE_MAX_LEVEL, ICOSPHERE_MAX_LEVEL + 1,
                         20u << (2 * (ICOSPHERE_MAX_LEVEL + 1)), (unsigned)MESH_MAX_TRIANGLES);

    uint32_t tris = 20u << (2 * d.level), verts = 10u * (1u << (2 * d.level)) + 2;
    /* With uvs every vertex may get one seam copy, and each pole four more. */
    uint32_t room = d.uvs ? 2 * verts + 8 : verts;
    sphere_build b = {NULL, 0, room, NULL, 0, NULL, NULL, 0};
    b.pos = malloc((size_t)room * 3 * sizeof *b.pos);
    b.tris = malloc((size_t)tris * 3 * sizeof *b.tris);
    uint32_t *scratch = malloc((size_t)tris * 3 * sizeof *scratch);
    double *uv = d.uvs ? malloc((size_t)room * 2 * sizeof *uv) : NULL;
    bool ok = b.pos && b.tris && scratch && (!d.uvs || uv);
    if (ok) {
        icosahedron(&b);
        for (int l = 0; l < d.level && ok; l++)
            ok = subdivide(&b, scratch);
    }
    if (ok && d.uvs) {
        for (uint32_t v = 0; v < b.count; v++)
            spherical_uv(b.pos + 3 * (size_t)v, uv + 2 * (size_t)v);
        fix_seams(&b, uv, scratch); /* scratch (3 per triangle) has room for one index per vertex */
    }
    bg_status st = ok ? mesh_alloc(out, b.count, b.tri_count, d.normals, d.uvs, what, why, why_size)
                      : mesh_fail(why, why_size, BG_ERR_OUT_OF_MEMORY, "%s: no memory for level %d", what, d.level);
    if (st == BG_OK) {
        for (uint32_t v = 0; v < b.count; v++) {
            double p[3] = {b.pos[3 * v], b.pos[3 * v + 1], b.pos[3 * v + 2]};
            for (int i = 0; i < 3; i++)
                out->positions[3 * v + i] = (float)p[i];
            if (d.normals) {
                normalize3(p);
                for (int i = 0; i < 3; i++)
                    out->normals[3 * v + i] = (float)p[i];
            }
            if (d.uvs) {
                out->uvs[2 * v] = (float)uv[2 * v];
                out->uvs[2 * v + 1] = (float)uv[2 * v + 1];
            }
        }
        memcpy(out->indices, b.tris, (size_t)b.tri_count * 3 * sizeof *b.tris);
    }
    sphere_build_free(&b, uv, scratch);
    return st;
}

/* ---- torus knot ------------------------------------------------------------------------------ */

#define KNOT_R 1.0     /* the torus the knot lies on: major radius... */
#define KNOT_A 0.4     /* ...and minor radius */
#define KNOT_TUBE 0.15 /* the tube around the knot */

static int gcd(int a, int b)
{
    while (b != 0) {
        int r = a % b;
        a = b;
        b = r;
    }
    return a;
}

/* The point and unit tangent of the (p, q) knot at s. */
static void knot_curve(int p, int q, double s, double c[3], double t[3])
{
    double ps = p * s, qs = q * s, r = KNOT_R + KNOT_A * cos(qs);
    c[0] = r * cos(ps);
    c[1] = r * sin(ps);
    c[2] = KNOT_A * sin(qs);
    double dr = -KNOT_A * q * sin(qs);
    t[0] = dr * cos(ps) - r * p * sin(ps);
    t[1] = dr * sin(ps) + r * p * cos(ps);
    t[2] = KNOT_A * q * cos(qs);
    normalize3(t);
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

bg_status mesh_torus_knot(const mesh_torus_knot_desc *desc, mesh *out, char *why, size_t why_size)
{
    static const char *what = "mesh_torus_knot";
    if (!out)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: out is NULL", what);
    memset(out, 0, sizeof *out);
    mesh_torus_knot_desc d = {0, 0, 0, 0, false, false};
    if (desc)
        d = *desc;
    d.p = d.p ? d.p : 2;
    d.q = d.q ? d.q : 3;
    d.segments = d.segments ? d.segments : 128;
    d.sides = d.sides ? d.sides : 12;
    if (d.p < 1 || d.p > 64 || d.q < 1 || d.q > 64)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: desc.p (%d) and desc.q (%d) must be 1 .. 64",
                         what, d.p, d.q);
    if (gcd(d.p, d.q) != 1)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT,
                         "%s: desc.p (%d) and desc.q (%d) share the factor %d: the curve would run over itself", what,
                         d.p, d.q, gcd(d.p, d.q));
    if (d.segments < 3 || d.sides < 3)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: desc.segments (%d) and desc.sides (%d) must be >= 3",
                         what, d.segments, d.sides);
    uint64_t tris = 2ull * (uint64_t)d.segments * (uint64_t)d.sides;
    if (tris > MESH_MAX_TRIANGLES)
        return mesh_fail(why, why_size, BG_ERR_LIMIT,
                         "%s: desc.segments %d x desc.sides %d gives %llu triangles, more than MESH_MAX_TRIANGLES (%u)",
                         what, d.segments, d.sides, (unsigned long long)tris, (unsigned)MESH_MAX_TRIANGLES);
    /* With uvs the first ring and the first side repeat at the end (u = 1, v = 1). */
    uint32_t rows = (uint32_t)d.segments + (d.uvs ? 1 : 0), cols = (uint32_t)d.sides + (d.uvs ? 1 : 0);
    bg_status st = mesh_alloc(out, rows * cols, (uint32_t)tris, d.normals, d.uvs, what, why, why_size);
    if (st != BG_OK)
        return st;
    for (uint32_t i = 0; i < rows; i++) {
        double s = 2.0 * PI * (double)(i % (uint32_t)d.segments) / d.segments;
        double c[3], t[3], b[3], n[3];
        knot_curve(d.p, d.q, s, c, t);
        /* A frame from the curve alone (periodic in s): b across the tangent and the position, which
         * are never parallel on this torus; n = b x t. */
        cross3(t, c, b);
        normalize3(b);
        cross3(b, t, n);
        for (uint32_t j = 0; j < cols; j++) {
            double a = 2.0 * PI * (double)(j % (uint32_t)d.sides) / d.sides;
            double out_dir[3];
            for (int k = 0; k < 3; k++)
                out_dir[k] = cos(a) * n[k] + sin(a) * b[k];
            uint32_t v = i * cols + j;
            for (int k = 0; k < 3; k++)
                out->positions[3 * v + k] = (float)(c[k] + KNOT_TUBE * out_dir[k]);
            if (d.normals) {
                normalize3(out_dir);
                for (int k = 0; k < 3; k++)
                    out->normals[3 * v + k] = (float)out_dir[k];
            }
            if (d.uvs) {
                out->uvs[2 * v] = (float)((double)i / d.segments);
                out->uvs[2 * v + 1] = (float)((double)j / d.sides);
            }
        }
    }
    /* Around the tube (v) then along the knot (u) is counter-clockwise seen from outside. */
    uint32_t *idx = out->indices;
    for (uint32_t i = 0; i < (uint32_t)d.segments; i++)
        for (uint32_t j = 0; j < (uint32_t)d.sides; j++) {
            uint32_t i1 = d.uvs ? i + 1 : (i + 1) % rows, j1 = d.uvs ? j + 1 : (j + 1) % cols;
            uint32_t a = i * cols + j, bb = i * cols + j1, c = i1 * cols + j, dd = i1 * cols + j1;
            uint32_t quad[6] = {a, bb, c, c, bb, dd};
            memcpy(idx, quad, sizeof quad);
            idx += 6;
        }
    return BG_OK;
}

/* ---- heightfield ----------------------------------------------------------------------------- */

/* The terrain's height and its partial derivatives. */
static double height(double amp, double x, double z, double *hx, double *hz)
{
    double s1 = sin(3.0 * x + 1.0), c1 = cos(3.0 * x + 1.0), s2 = sin(2.5 * z), c2 = cos(2.5 * z);
    double s3 = sin(7.0 * x - 4.0 * z + 0.5), c3 = cos(7.0 * x - 4.0 * z + 0.5);
    double s4 = sin(5.0 * x + 11.0 * z), c4 = cos(5.0 * x + 11.0 * z);
    *hx = amp * (1.5 * c1 * c2 + 2.1 * c3 - 1.0 * s4);
    *hz = amp * (-1.25 * s1 * s2 - 1.2 * c3 - 2.2 * s4);
    return amp * (0.5 * s1 * c2 + 0.3 * s3 + 0.2 * c4);
}

bg_status mesh_heightfield(const mesh_heightfield_desc *desc, mesh *out, char *why, size_t why_size)
{
    static const char *what = "mesh_heightfield";
    if (!out)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: out is NULL", what);
    memset(out, 0, sizeof *out);
    mesh_heightfield_desc d = {0, 0.0, false, false};
    if (desc)
        d = *desc;
    d.n = d.n ? d.n : 64;
    d.amplitude = d.amplitude != 0.0 ? d.amplitude : 0.25;
    if (!isfinite(d.amplitude))
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: desc.amplitude is not finite", what);
    if (d.n < 1)
        return mesh_fail(why, why_size, BG_ERR_INVALID_ARGUMENT, "%s: desc.n is %d; it must be 1 .. 2048", what, d.n);
    uint64_t tris = 2ull * (uint64_t)d.n * (uint64_t)d.n;
    if (tris > MESH_MAX_TRIANGLES)
        return mesh_fail(why, why_size, BG_ERR_LIMIT,
                         "%s: desc.n %d gives %llu triangles, more than MESH_MAX_TRIANGLES (%u); n goes up to 2048",
                         what, d.n, (unsigned long long)tris, (unsigned)MESH_MAX_TRIANGLES);
    uint32_t side = (uint32_t)d.n + 1;
    bg_status st = mesh_alloc(out, side * side, (uint32_t)tris, d.normals, d.uvs, what, why, why_size);
    if (st != BG_OK)
        return st;
    for (uint32_t j = 0; j < side; j++)
        for (uint32_t i = 0; i < side; i++) {
            double x = -1.0 + 2.0 * i / d.n, z = -1.0 + 2.0 * j / d.n, hx, hz;
            double y = height(d.amplitude, x, z, &hx, &hz);
            uint32_t v = j * side + i;
            out->positions[3 * v] = (float)x;
            out->positions[3 * v + 1] = (float)y;
            out->positions[3 * v + 2] = (float)z;
            if (d.normals) {
                double n[3] = {-hx, 1.0, -hz};
                normalize3(n);
                for (int k = 0; k < 3; k++)
                    out->normals[3 * v + k] = (float)n[k];
            }
            if (d.uvs) {
                out->uvs[2 * v] = (float)((x + 1.0) / 2.0);
                out->uvs[2 * v + 1] = (float)((1.0 - z) / 2.0);
            }
        }
    /* Seen from above (+y, x to the right, z towards the viewer), (x0 z0), (x0 z1), (x1 z1) turns
     * counter-clockwise. */
    uint32_t *idx = out->indices;
    for (uint32_t j = 0; j < (uint32_t)d.n; j++)
        for (uint32_t i = 0; i < (uint32_t)d.n; i++) {
            uint32_t a = j * side + i, b = a + 1, c = a + side + 1, dd = a + side;
            uint32_t quad[6] = {a, dd, c, a, c, b};
            memcpy(idx, quad, sizeof quad);
            idx += 6;
        }
    return BG_OK;
}
