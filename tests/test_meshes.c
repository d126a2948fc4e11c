/* The procedural meshes of examples/scenes/meshes.c and the PLY reader of ply_mesh.c: counts as
 * documented, closed 2-manifolds wound outwards, unit radii and normals, refused parameters, and the
 * Stanford bunny of tests/data read back with every corrupt copy refused for the right reason. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "util_files.h"

#include "scenes/meshes.h"
#include "scenes/ply_mesh.h"

#define PI 3.14159265358979323846
#define BUNNY "tests/data/bunny.ply"

/* ---- checks shared by the meshes ------------------------------------------------------------- */

static const float *pos(const mesh *m, uint32_t v)
{
    return m->positions + 3 * (size_t)v;
}

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Each vertex's first vertex of the same position (bit for bit): seam copies become one vertex. */
static uint32_t *weld(const mesh *m)
{
    uint32_t *first = malloc(sizeof *first * m->vertex_count);
    uint64_t *keys = malloc(sizeof *keys * m->vertex_count);
    assert_true(first && keys);
    /* Sort (position hash, index) pairs, then compare positions within runs of one hash. */
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        uint32_t bits[3];
        memcpy(bits, pos(m, v), sizeof bits);
        uint32_t h = (bits[0] * 2654435761u) ^ (bits[1] * 40503u) ^ (bits[2] * 2246822519u);
        keys[v] = (uint64_t)h << 32 | v;
    }
    qsort(keys, m->vertex_count, sizeof *keys, compare_u64);
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        uint32_t v = (uint32_t)keys[i];
        first[v] = v;
        for (uint32_t j = i; j-- > 0 && keys[j] >> 32 == keys[i] >> 32;) {
            uint32_t u = (uint32_t)keys[j];
            if (memcmp(pos(m, u), pos(m, v), 3 * sizeof(float)) == 0)
                first[v] = first[u] < first[v] ? first[u] : first[v];
        }
    }
    free(keys);
    return first;
}

/* Every edge (after welding) is in exactly two triangles, run once in each direction; returns the
 * number of directed edges without a reverse (the boundary), which a closed mesh must not have. */
static uint32_t open_edges(const mesh *m, bool by_position)
{
    uint32_t *id = by_position ? weld(m) : NULL;
    size_t n = 3 * (size_t)m->triangle_count;
    uint64_t *e = malloc(sizeof *e * n);
    assert_non_null(e);
    for (uint32_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->indices[3 * t + k], b = m->indices[3 * t + (k + 1) % 3];
            assert_true(a < m->vertex_count && b < m->vertex_count);
            if (id) {
                a = id[a];
                b = id[b];
            }
            assert_int_not_equal(a, b);
            e[3 * t + k] = (uint64_t)a << 32 | b;
        }
    qsort(e, n, sizeof *e, compare_u64);
    uint32_t open = 0;
    for (size_t i = 0; i < n; i++) {
        if (i > 0 && e[i] == e[i - 1])
            fail_msg("edge %u -> %u is run twice in one direction", (unsigned)(e[i] >> 32), (unsigned)e[i]);
        uint64_t rev = (e[i] << 32) | (e[i] >> 32);
        if (!bsearch(&rev, e, n, sizeof *e, compare_u64))
            open++;
    }
    free(e);
    free(id);
    return open;
}

/* The enclosed volume by the divergence theorem: positive for a closed mesh wound outwards. */
static double signed_volume(const mesh *m)
{
    double v = 0.0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const float *a = pos(m, m->indices[3 * t]), *b = pos(m, m->indices[3 * t + 1]),
                    *c = pos(m, m->indices[3 * t + 2]);
        v += a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) - a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
             a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
    }
    return v / 6.0;
}

/* Normals are unit and on the front side of every triangle that uses them. */
static void check_normals(const mesh *m)
{
    assert_non_null(m->normals);
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *n = m->normals + 3 * v;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (!(fabs(len - 1.0) <= 1e-6))
            fail_msg("normal %u has length %.9g", (unsigned)v, len);
    }
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *i = m->indices + 3 * t;
        const float *a = pos(m, i[0]), *b = pos(m, i[1]), *c = pos(m, i[2]);
        double e1[3], e2[3], g[3], sum = 0.0;
        for (int k = 0; k < 3; k++) {
            e1[k] = (double)b[k] - a[k];
            e2[k] = (double)c[k] - a[k];
        }
        g[0] = e1[1] * e2[2] - e1[2] * e2[1];
        g[1] = e1[2] * e2[0] - e1[0] * e2[2];
        g[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (int k = 0; k < 3; k++)
            sum += g[k] * ((double)m->normals[3 * i[0] + k] + m->normals[3 * i[1] + k] + m->normals[3 * i[2] + k]);
        if (!(sum > 0.0))
            fail_msg("triangle %u faces away from its normals", (unsigned)t);
    }
}

static void expect_refusal(bg_status got, bg_status want, const char *why, const char *const *words)
{
    assert_int_equal(got, want);
    for (int i = 0; words[i]; i++)
        if (!strstr(why, words[i]))
            fail_msg("message \"%s\" does not say \"%s\"", why, words[i]);
}

/* ---- icosphere ------------------------------------------------------------------------------- */

static void icosphere_counts_closed_unit_outward(void **state)
{
    (void)state;
    char why[256];
    for (int level = 0; level <= 5; level++) {
        mesh m;
        mesh_icosphere_desc d = {level, 0, true, false};
        assert_int_equal(mesh_icosphere(&d, &m, why, sizeof why), BG_OK);
        assert_int_equal(m.triangle_count, 20u << (2 * level));
        assert_int_equal(m.vertex_count, 10u * (1u << (2 * level)) + 2);
        assert_null(m.uvs);
        assert_int_equal(open_edges(&m, false), 0);
        for (uint32_t v = 0; v < m.vertex_count; v++) {
            const float *p = pos(&m, v), *n = m.normals + 3 * v;
            double r = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
            if (!(fabs(r - 1.0) <= 1e-6))
                fail_msg("level %d: vertex %u at radius %.9g", level, (unsigned)v, r);
            for (int k = 0; k < 3; k++)
                assert_true(fabs(n[k] - p[k] / r) <= 1e-6);
        }
        check_normals(&m);
        /* Outwards, and approaching the ball's 4 pi / 3 from below. */
        double vol = signed_volume(&m);
        assert_true(vol > 0.0 && vol < 4.0 * PI / 3.0);
        if (level == 5)
            assert_true(vol > 0.999 * 4.0 * PI / 3.0);
        mesh_free(&m);
    }
    /* min_triangles picks the smallest level with at least that many. */
    const uint32_t asked[][2] = {{1, 20}, {20, 20}, {21, 80}, {80, 80}, {81, 320}, {5000, 5120}};
    for (size_t i = 0; i < sizeof asked / sizeof asked[0]; i++) {
        mesh m;
        mesh_icosphere_desc d = {0, asked[i][0], false, false};
        assert_int_equal(mesh_icosphere(&d, &m, why, sizeof why), BG_OK);
        assert_int_equal(m.triangle_count, asked[i][1]);
        assert_null(m.normals);
        mesh_free(&m);
    }
}

/* The spherical mapping of docs/shading.md 4. */
static double lon_u(double x, double z)
{
    return (x == 0.0 && z == 0.0) ? 0.5 : 0.5 + atan2(x, z) / (2.0 * PI);
}

static void icosphere_uvs_do_not_wrap_and_keep_it_closed(void **state)
{
    (void)state;
    char why[256];
    mesh m;
    mesh_icosphere_desc d = {3, 0, true, true};
    assert_int_equal(mesh_icosphere(&d, &m, why, sizeof why), BG_OK);
    assert_int_equal(m.triangle_count, 1280);
    /* The seam and the poles add copies: closed by position, open by index. */
    assert_int_equal(m.vertex_count, 10 * 64 + 3 * 8 + 9);
    assert_int_equal(open_edges(&m, true), 0);
    assert_true(open_edges(&m, false) > 0);
    assert_true(signed_volume(&m) > 0.0);
    check_normals(&m);
    for (uint32_t t = 0; t < m.triangle_count; t++) {
        float lo = 2.0f, hi = -1.0f;
        for (int k = 0; k < 3; k++) {
            float u = m.uvs[2 * m.indices[3 * t + k]];
            lo = u < lo ? u : lo;
            hi = u > hi ? u : hi;
        }
        if (!(hi - lo < 0.5f))
            fail_msg("triangle %u spans u %g .. %g", (unsigned)t, lo, hi);
    }
    for (uint32_t v = 0; v < m.vertex_count; v++) {
        const float *p = pos(&m, v), *uv = m.uvs + 2 * v;
        assert_true(uv[0] >= 0.0f && uv[0] <= 1.5f && uv[1] >= 0.0f && uv[1] <= 1.0f);
        assert_true(fabs(uv[1] - (0.5 + asin(fmax(-1.0, fmin(1.0, p[1]))) / PI)) <= 1e-6);
        if (p[0] == 0.0f && p[2] == 0.0f)
            continue; /* a pole: u is its triangle's */
        /* u is the mapping's, or one turn more on the seam's small side. */
        double du = uv[0] - lon_u(p[0], p[2]);
        assert_true(fabs(du - floor(du + 0.5)) <= 1e-6);
    }
    mesh_free(&m);
    for (int level = 0; level <= 4; level++) {
        mesh_icosphere_desc e = {level, 0, false, true};
        assert_int_equal(mesh_icosphere(&e, &m, why, sizeof why), BG_OK);
        assert_int_equal(m.vertex_count, 10u * (1u << (2 * level)) + 3u * (1u << level) + 9);
        assert_int_equal(open_edges(&m, true), 0);
        mesh_free(&m);
    }
}

static void icosphere_refuses_absurd_levels(void **state)
{
    (void)state;
    char why[256];
    mesh m;
    mesh_icosphere_desc d = {-1, 0, false, false};
    const char *level[] = {"mesh_icosphere", "desc.level", NULL};
    expect_refusal(mesh_icosphere(&d, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, level);
    assert_null(m.positions);
    d.level = 10;
    const char *limit[] = {"desc.level is 10", "20971520", "MESH_MAX_TRIANGLES", NULL};
    expect_refusal(mesh_icosphere(&d, &m, why, sizeof why), BG_ERR_LIMIT, why, limit);
    d.level = 1000000;
    expect_refusal(mesh_icosphere(&d, &m, why, sizeof why), BG_ERR_LIMIT, why, level);
    mesh_icosphere_desc many = {0, 1000000000u, false, false};
    const char *min[] = {"desc.min_triangles", "5242880", NULL};
    expect_refusal(mesh_icosphere(&many, &m, why, sizeof why), BG_ERR_LIMIT, why, min);
    mesh_icosphere_desc both = {2, 100, false, false};
    const char *two[] = {"desc.level", "desc.min_triangles", NULL};
    expect_refusal(mesh_icosphere(&both, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, two);
    assert_int_equal(mesh_icosphere(NULL, NULL, NULL, 0), BG_ERR_INVALID_ARGUMENT);
    /* NULL desc: the defaults (the icosahedron). */
    assert_int_equal(mesh_icosphere(NULL, &m, NULL, 0), BG_OK);
    assert_int_equal(m.triangle_count, 20);
    mesh_free(&m);
    mesh_free(&m); /* an empty mesh frees to nothing */
    mesh_free(NULL);
}

/* ---- torus knot ------------------------------------------------------------------------------ */

/* The length of the (p, q) knot of meshes.h, summed over fine chords. */
static double knot_length(int p, int q)
{
    double len = 0.0, prev[3] = {0, 0, 0};
    for (int i = 0; i <= 100000; i++) {
        double s = 2.0 * PI * i / 100000.0, r = 1.0 + 0.4 * cos(q * s);
        double c[3] = {r * cos(p * s), r * sin(p * s), 0.4 * sin(q * s)};
        if (i > 0)
            len += sqrt((c[0] - prev[0]) * (c[0] - prev[0]) + (c[1] - prev[1]) * (c[1] - prev[1]) +
                        (c[2] - prev[2]) * (c[2] - prev[2]));
        memcpy(prev, c, sizeof c);
    }
    return len;
}

static void torus_knot_counts_closed_outward(void **state)
{
    (void)state;
    char why[256];
    const int pq[][4] = {{2, 3, 128, 12}, {3, 2, 100, 8}, {3, 5, 300, 10}, {1, 1, 3, 3}};
    for (size_t i = 0; i < sizeof pq / sizeof pq[0]; i++) {
        for (int uvs = 0; uvs < 2; uvs++) {
            mesh m;
            mesh_torus_knot_desc d = {pq[i][0], pq[i][1], pq[i][2], pq[i][3], true, uvs == 1};
            assert_int_equal(mesh_torus_knot(&d, &m, why, sizeof why), BG_OK);
            uint32_t seg = (uint32_t)pq[i][2], sides = (uint32_t)pq[i][3];
            assert_int_equal(m.triangle_count, 2 * seg * sides);
            assert_int_equal(m.vertex_count, uvs ? (seg + 1) * (sides + 1) : seg * sides);
            assert_int_equal(open_edges(&m, uvs == 1), 0);
            check_normals(&m);
            if (i < 3) {
                /* About a prism's volume: the cross-section (a regular polygon of `sides` corners on
                 * the radius 0.15) times the knot's length. */
                double section = 0.5 * sides * sin(2.0 * PI / sides) * 0.15 * 0.15;
                double want = section * knot_length(pq[i][0], pq[i][1]), vol = signed_volume(&m);
                if (!(vol > 0.97 * want && vol < 1.01 * want))
                    fail_msg("(%d, %d) knot: volume %g, a tube's %g", pq[i][0], pq[i][1], vol, want);
            }
            if (uvs)
                for (uint32_t v = 0; v < m.vertex_count; v++)
                    assert_true(m.uvs[2 * v] >= 0.0f && m.uvs[2 * v] <= 1.0f && m.uvs[2 * v + 1] >= 0.0f &&
                                m.uvs[2 * v + 1] <= 1.0f);
            mesh_free(&m);
        }
    }
    /* Defaults: the trefoil, 128 x 12. */
    mesh m;
    assert_int_equal(mesh_torus_knot(NULL, &m, why, sizeof why), BG_OK);
    assert_int_equal(m.triangle_count, 3072);
    assert_null(m.normals);
    assert_null(m.uvs);
    mesh_free(&m);
}

static void torus_knot_refuses_absurd_parameters(void **state)
{
    (void)state;
    char why[256];
    mesh m;
    mesh_torus_knot_desc d = {2, 4, 0, 0, false, false};
    const char *shared[] = {"desc.p (2)", "desc.q (4)", "factor 2", NULL};
    expect_refusal(mesh_torus_knot(&d, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, shared);
    d.p = 65;
    d.q = 3;
    const char *range[] = {"desc.p (65)", "1 .. 64", NULL};
    expect_refusal(mesh_torus_knot(&d, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, range);
    mesh_torus_knot_desc few = {2, 3, 2, 8, false, false};
    const char *segments[] = {"desc.segments (2)", ">= 3", NULL};
    expect_refusal(mesh_torus_knot(&few, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, segments);
    mesh_torus_knot_desc huge = {2, 3, 1 << 20, 1 << 10, false, false};
    const char *limit[] = {"2147483648 triangles", "MESH_MAX_TRIANGLES", NULL};
    expect_refusal(mesh_torus_knot(&huge, &m, why, sizeof why), BG_ERR_LIMIT, why, limit);
    mesh_torus_knot_desc widest = {2, 3, 2147483647, 2147483647, false, false};
    const char *widest_words[] = {"MESH_MAX_TRIANGLES", NULL};
    expect_refusal(mesh_torus_knot(&widest, &m, why, sizeof why), BG_ERR_LIMIT, why, widest_words);
    assert_null(m.positions);
}

/* ---- heightfield ----------------------------------------------------------------------------- */

static void heightfield_counts_edges_and_facing(void **state)
{
    (void)state;
    char why[256];
    mesh m, again;
    mesh_heightfield_desc d = {16, 0.0, true, true};
    assert_int_equal(mesh_heightfield(&d, &m, why, sizeof why), BG_OK);
    assert_int_equal(m.vertex_count, 17 * 17);
    assert_int_equal(m.triangle_count, 2 * 16 * 16);
    /* An open sheet: only its 4 n border edges lack a twin. */
    assert_int_equal(open_edges(&m, false), 4 * 16);
    check_normals(&m);
    for (uint32_t t = 0; t < m.triangle_count; t++) {
        const uint32_t *i = m.indices + 3 * t;
        const float *a = pos(&m, i[0]), *b = pos(&m, i[1]), *c = pos(&m, i[2]);
        /* Front up: the y of (b - a) x (c - a) is positive. */
        double gy = ((double)b[2] - a[2]) * ((double)c[0] - a[0]) - ((double)b[0] - a[0]) * ((double)c[2] - a[2]);
        assert_true(gy > 0.0);
    }
    bool hilly = false;
    for (uint32_t v = 0; v < m.vertex_count; v++) {
        const float *p = pos(&m, v);
        assert_true(m.normals[3 * v + 1] > 0.0f);
        assert_true(m.uvs[2 * v] == (float)((p[0] + 1.0) / 2.0) && m.uvs[2 * v + 1] == (float)((1.0 - p[2]) / 2.0));
        assert_true(fabs(p[1]) <= 0.25f);
        hilly |= fabs(p[1]) > 0.1f;
    }
    assert_true(hilly);
    /* Deterministic, and a negative amplitude mirrors the heights exactly. */
    assert_int_equal(mesh_heightfield(&d, &again, why, sizeof why), BG_OK);
    assert_memory_equal(m.positions, again.positions, sizeof(float) * 3 * m.vertex_count);
    mesh_free(&again);
    mesh_heightfield_desc mirrored = {16, -0.25, false, false};
    assert_int_equal(mesh_heightfield(&mirrored, &again, why, sizeof why), BG_OK);
    for (uint32_t v = 0; v < m.vertex_count; v++)
        assert_true(again.positions[3 * v + 1] == -m.positions[3 * v + 1]);
    mesh_free(&again);
    mesh_free(&m);
}

static void heightfield_refuses_absurd_parameters(void **state)
{
    (void)state;
    char why[256];
    mesh m;
    mesh_heightfield_desc d = {-1, 0.0, false, false};
    const char *n[] = {"desc.n is -1", NULL};
    expect_refusal(mesh_heightfield(&d, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, n);
    d.n = 2049;
    const char *limit[] = {"desc.n 2049", "8396802 triangles", "MESH_MAX_TRIANGLES", NULL};
    expect_refusal(mesh_heightfield(&d, &m, why, sizeof why), BG_ERR_LIMIT, why, limit);
    d.n = 4;
    d.amplitude = NAN;
    const char *amp[] = {"desc.amplitude", NULL};
    expect_refusal(mesh_heightfield(&d, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, amp);
    d.amplitude = INFINITY;
    expect_refusal(mesh_heightfield(&d, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT, why, amp);
    assert_null(m.positions);
}

/* ---- the bunny and the PLY reader ------------------------------------------------------------ */

static void bunny_reads_as_packaged(void **state)
{
    (void)state;
    char why[256];
    mesh m;
    if (ply_mesh_read(BUNNY, &m, why, sizeof why) != BG_OK)
        fail_msg("%s (the tests run from the repository root)", why);
    /* The counts of the npm package bunny 1.0.1 (tests/data/README.md). */
    assert_int_equal(m.vertex_count, 1839);
    assert_int_equal(m.triangle_count, 3674);
    assert_null(m.normals);
    assert_null(m.uvs);
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < m.vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], pos(&m, v)[k]);
            hi[k] = fmaxf(hi[k], pos(&m, v)[k]);
        }
    const float want_lo[3] = {-4.95847511f, -0.003149f, -3.72983289f}, want_hi[3] = {4.94885015f, 9.65474796f, 3.8106389f};
    for (int k = 0; k < 3; k++)
        assert_true(lo[k] == want_lo[k] && hi[k] == want_hi[k]);
    /* The package's first and last entries, rounded to float. */
    assert_true(pos(&m, 0)[0] == 1.301895f && pos(&m, 0)[1] == 0.122622f && pos(&m, 0)[2] == 2.550061f);
    assert_true(pos(&m, 1838)[0] == -2.505459f && pos(&m, 1838)[1] == 1.492266f && pos(&m, 1838)[2] == 1.19295f);
    const uint32_t first[3] = {2, 1661, 3}, last[3] = {816, 589, 1838};
    assert_memory_equal(m.indices, first, sizeof first);
    assert_memory_equal(m.indices + 3 * 3673, last, sizeof last);
    /* Every index in range (open_edges asserts it), and this bunny is closed and wound outwards. */
    assert_int_equal(open_edges(&m, false), 0);
    assert_true(fabs(signed_volume(&m) - 1165.7302 / 6.0) < 0.01);
    mesh_free(&m);
}

typedef struct corrupt_case {
    const char *name;
    bg_status status;
    const char *words[3];
} corrupt_case;

static void write_bytes(const char *path, const void *a, size_t na, const void *b, size_t nb)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(a, 1, na, f), na);
    if (nb)
        assert_int_equal(fwrite(b, 1, nb, f), nb);
    assert_int_equal(fclose(f), 0);
}

/* Writes one corrupt copy of the bunny (bytes, header end at body) as dir/name, reads it, and
 * checks the status and that the message names the file and the reason. */
static void expect_corrupt(const char *dir, const corrupt_case *c, const unsigned char *bytes, size_t size)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.ply", dir, c->name);
    write_bytes(path, bytes, size, NULL, 0);
    char why[512] = "";
    mesh m;
    bg_status st = ply_mesh_read(path, &m, why, sizeof why);
    if (st != c->status)
        fail_msg("%s: status %d, want %d (%s)", c->name, (int)st, (int)c->status, why);
    assert_null(m.positions);
    assert_null(m.indices);
    if (!strstr(why, path))
        fail_msg("%s: the message \"%s\" does not name the file", c->name, why);
    for (int i = 0; i < 3 && c->words[i]; i++)
        if (!strstr(why, c->words[i]))
            fail_msg("%s: the message \"%s\" does not say \"%s\"", c->name, why, c->words[i]);
    assert_int_equal(unlink(path), 0);
}

/* A copy of the bunny with its header replaced by header (the data kept). */
static unsigned char *with_header(const unsigned char *bunny, size_t size, size_t body, const char *header,
                                  size_t *out_size)
{
    size_t h = strlen(header);
    unsigned char *b = malloc(h + size - body);
    assert_non_null(b);
    memcpy(b, header, h);
    memcpy(b + h, bunny + body, size - body);
    *out_size = h + size - body;
    return b;
}

static void corrupt_ply_files_are_refused_with_the_reason(void **state)
{
    (void)state;
    size_t size;
    unsigned char *bunny = util_read_file(BUNNY, &size);
    const char *end = "end_header\n";
    unsigned char *at = NULL;
    for (size_t i = 0; i + strlen(end) <= size && !at; i++)
        if (memcmp(bunny + i, end, strlen(end)) == 0)
            at = bunny + i;
    assert_non_null(at);
    size_t body = (size_t)(at - bunny) + strlen(end);
    assert_int_equal(size - body, 1839 * 12 + 3674 * 13);
    char dir[] = "/tmp/bg_mesh_test_XXXXXX";
    assert_non_null(mkdtemp(dir));
    unsigned char *copy = malloc(size + 1);
    assert_non_null(copy);

    /* Cut short: inside the header, the vertices, the faces; and empty. */
    const corrupt_case in_header = {"cut_header", BG_ERR_IO, {"truncated", "header", NULL}};
    expect_corrupt(dir, &in_header, bunny, 40);
    const corrupt_case empty = {"empty", BG_ERR_IO, {"truncated", "header (line 1)", NULL}};
    expect_corrupt(dir, &empty, bunny, 0);
    const corrupt_case in_vertices = {"cut_vertices", BG_ERR_IO, {"truncated", "after 8 of 1839 vertices", NULL}};
    expect_corrupt(dir, &in_vertices, bunny, body + 8 * 12 + 5);
    const corrupt_case in_faces = {"cut_faces", BG_ERR_IO, {"truncated", "after 3673 of 3674 triangles", NULL}};
    expect_corrupt(dir, &in_faces, bunny, size - 5);

    /* Headers this reader does not take. */
    static const struct {
        corrupt_case c;
        const char *header;
    } headers[] = {
        {{"not_ply", BG_ERR_INVALID_ARGUMENT, {"bad header", "not a PLY file", NULL}}, "plz\n"},
        {{"ascii", BG_ERR_INVALID_ARGUMENT, {"bad header", "only format binary_little_endian 1.0", NULL}},
         "ply\nformat ascii 1.0\nelement vertex 1839\n"},
        {{"big_endian", BG_ERR_INVALID_ARGUMENT, {"line 3", "binary_big_endian", NULL}},
         "ply\ncomment x\nformat binary_big_endian 1.0\n"},
        {{"double", BG_ERR_INVALID_ARGUMENT, {"line 4 is \"property double x\"", "expected \"property float x\"", NULL}},
         "ply\nformat binary_little_endian 1.0\nelement vertex 1839\nproperty double x\n"},
        {{"normals", BG_ERR_INVALID_ARGUMENT, {"line 7 is \"property float nx\"", "element face", NULL}},
         "ply\nformat binary_little_endian 1.0\nelement vertex 1839\nproperty float x\nproperty float y\n"
         "property float z\nproperty float nx\n"},
        {{"no_count", BG_ERR_INVALID_ARGUMENT, {"\"element vertex\"", "element vertex <count>", NULL}},
         "ply\nformat binary_little_endian 1.0\nelement vertex\n"},
        {{"ushort_list", BG_ERR_INVALID_ARGUMENT, {"property list uchar ushort", "expected", NULL}},
         "ply\nformat binary_little_endian 1.0\nelement vertex 1839\nproperty float x\nproperty float y\n"
         "property float z\nelement face 3674\nproperty list uchar ushort vertex_indices\n"},
        {{"huge_counts", BG_ERR_LIMIT, {"99999999 vertices", "at most", NULL}},
         "ply\nformat binary_little_endian 1.0\nelement vertex 99999999\nproperty float x\nproperty float y\n"
         "property float z\nelement face 3674\nproperty list uchar uint vertex_indices\nend_header\n"},
        {{"more_faces", BG_ERR_IO, {"truncated", "after 3674 of 3675 triangles", NULL}},
         "ply\nformat binary_little_endian 1.0\nelement vertex 1839\nproperty float x\nproperty float y\n"
         "property float z\nelement face 3675\nproperty list uchar uint vertex_indices\nend_header\n"},
    };
    for (size_t i = 0; i < sizeof headers / sizeof headers[0]; i++) {
        size_t n;
        unsigned char *b = with_header(bunny, size, body, headers[i].header, &n);
        expect_corrupt(dir, &headers[i].c, b, n);
        free(b);
    }
    /* A header with comments, obj_info, CRLF line ends and int indices is read like the original. */
    size_t n;
    unsigned char *b = with_header(bunny, size, body,
                                   "ply\r\nformat binary_little_endian 1.0\r\ncomment a\r\nelement vertex 1839\r\n"
                                   "obj_info b\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
                                   "element face 3674\r\nproperty list uchar int vertex_index\r\nend_header\n",
                                   &n);
    char path[512], why[256];
    snprintf(path, sizeof path, "%s/variant.ply", dir);
    write_bytes(path, b, n, NULL, 0);
    mesh m;
    assert_int_equal(ply_mesh_read(path, &m, why, sizeof why), BG_OK);
    assert_int_equal(m.triangle_count, 3674);
    mesh_free(&m);
    assert_int_equal(unlink(path), 0);
    free(b);

    /* Bad data after a good header. */
    size_t face10 = body + 1839 * 12 + 10 * 13;
    memcpy(copy, bunny, size);
    copy[face10 + 1 + 4] = 0x2f; /* 1839 = 0x072f, little-endian */
    copy[face10 + 1 + 5] = 0x07;
    copy[face10 + 1 + 6] = 0;
    copy[face10 + 1 + 7] = 0;
    const corrupt_case range = {"index_range", BG_ERR_INVALID_ARGUMENT,
                                {"face 10", "vertex index 1839 is out of range", "(1839 vertices)"}};
    expect_corrupt(dir, &range, copy, size);
    memcpy(copy, bunny, size);
    memset(copy + face10 + 1, 0xff, 4); /* -1 as an int */
    const corrupt_case negative = {"index_negative", BG_ERR_INVALID_ARGUMENT, {"face 10", "4294967295", NULL}};
    expect_corrupt(dir, &negative, copy, size);
    memcpy(copy, bunny, size);
    copy[body + 1839 * 12] = 4;
    const corrupt_case quad = {"quad", BG_ERR_INVALID_ARGUMENT, {"face 0 has 4 vertices", "only triangles", NULL}};
    expect_corrupt(dir, &quad, copy, size);
    memcpy(copy, bunny, size);
    const unsigned char nan_bits[4] = {0x00, 0x00, 0xc0, 0x7f};
    memcpy(copy + body + 5 * 12 + 4, nan_bits, 4);
    const corrupt_case nan = {"nan", BG_ERR_INVALID_ARGUMENT, {"vertex 5", "not finite", NULL}};
    expect_corrupt(dir, &nan, copy, size);
    memcpy(copy, bunny, size);
    copy[size] = 0;
    const corrupt_case trailing = {"trailing", BG_ERR_INVALID_ARGUMENT, {"unexpected data after the last face", NULL}};
    expect_corrupt(dir, &trailing, copy, size + 1);

    /* No file at all. */
    snprintf(path, sizeof path, "%s/missing.ply", dir);
    const char *missing[] = {"cannot open", "missing.ply", NULL};
    expect_refusal(ply_mesh_read(path, &m, why, sizeof why), BG_ERR_IO, why, missing);
    assert_int_equal(ply_mesh_read(NULL, &m, why, sizeof why), BG_ERR_INVALID_ARGUMENT);

    assert_int_equal(rmdir(dir), 0);
    free(copy);
    free(bunny);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(icosphere_counts_closed_unit_outward),
        cmocka_unit_test(icosphere_uvs_do_not_wrap_and_keep_it_closed),
        cmocka_unit_test(icosphere_refuses_absurd_levels),
        cmocka_unit_test(torus_knot_counts_closed_outward),
        cmocka_unit_test(torus_knot_refuses_absurd_parameters),
        cmocka_unit_test(heightfield_counts_edges_and_facing),
        cmocka_unit_test(heightfield_refuses_absurd_parameters),
        cmocka_unit_test(bunny_reads_as_packaged),
        cmocka_unit_test(corrupt_ply_files_are_refused_with_the_reason),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
