/* Normals computed for a mesh whose file has none, creased above an angle.
 *
 * Invariant: each corner of a triangle gets the area-weighted sum of the normals of the faces around
 * its vertex that differ from its own face's normal by at most the crease angle; corners of one
 * vertex whose sums are equal (bit for bit) share one output vertex, and each other sum gets a copy
 * of the vertex (position and texture coordinates). So a vertex on a smooth surface stays one
 * vertex, and a vertex on a crease (a cube's corner under a 60-degree angle) becomes one vertex per
 * side, each with its side's normal: the crease stays sharp. The first sum of a vertex keeps its
 * index and copies are appended, so a mesh without creases keeps its layout.
 *
 * The sums are taken in one order for every corner of a vertex (its corners in triangle order), so
 * that equal sets of faces give equal bits. A corner's sum visits every face of its vertex, which is
 * quadratic in a vertex's valence; at 180 degrees every face counts for every corner, so the sum is
 * taken once per vertex and a fan of any size stays linear. */
#include "scenefile_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct crease {
    size_t nv, nt;
    size_t *start;  /* per vertex (nv + 1): where its corners begin in corners[] */
    uint32_t *corners; /* 3 nt corner numbers (3 t + k), grouped by vertex, in triangle order */
    double *face;   /* 3 nt: each face's normal scaled by twice its area */
    double *unit;   /* 3 nt: the same normalised, zero for a face without area */
    float *sum;     /* 9 nt: each corner's normal */
    uint32_t *out;  /* 3 nt: each corner's output vertex */
} crease;

static void crease_free(crease *c)
{
    free(c->start);
    free(c->corners);
    free(c->face);
    free(c->unit);
    free(c->sum);
    free(c->out);
}

/* The face normals, and the corners listed by vertex (a counting sort on the vertex index). */
static void list_faces(crease *c, const float *p, const uint32_t *idx)
{
    for (size_t t = 0; t < c->nt; t++) {
        const float *a = &p[3 * idx[3 * t]], *b = &p[3 * idx[3 * t + 1]], *d = &p[3 * idx[3 * t + 2]];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        double *f = &c->face[3 * t], *u = &c->unit[3 * t];
        f[0] = e1[1] * e2[2] - e1[2] * e2[1];
        f[1] = e1[2] * e2[0] - e1[0] * e2[2];
        f[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        for (int k = 0; k < 3; k++)
            u[k] = len > 0 ? f[k] / len : 0.0;
    }
    for (size_t i = 0; i < 3 * c->nt; i++)
        c->start[idx[i] + 1]++;
    for (size_t v = 0; v < c->nv; v++)
        c->start[v + 1] += c->start[v];
    size_t *fill = c->start; /* advanced per vertex below, then restored */
    for (size_t i = 0; i < 3 * c->nt; i++)
        c->corners[fill[idx[i]]++] = (uint32_t)i;
    for (size_t v = c->nv; v > 0; v--)
        fill[v] = fill[v - 1];
    fill[0] = 0;
}

/* Each corner's normal: the faces of its vertex within the angle of its own face. A face without
 * area has no direction to compare: it neither limits nor adds (its normal is zero). */
static void sum_corners(crease *c, double cos_limit, bool all)
{
    for (size_t v = 0; v < c->nv; v++) {
        size_t lo = c->start[v], hi = c->start[v + 1];
        for (size_t i = lo; i < hi; i++) {
            size_t own = c->corners[i] / 3;
            float *s = &c->sum[3 * (size_t)c->corners[i]];
            if (all && i > lo) {
                memcpy(s, &c->sum[3 * (size_t)c->corners[lo]], 3 * sizeof *s);
                continue;
            }
            /* Each face's term rounded to float and summed in float, in triangle order: the sums
             * the scene builders make (examples/scenes/bunny_scene.c), bit for bit. */
            float n[3] = {0, 0, 0};
            for (size_t j = lo; j < hi; j++) {
                size_t g = c->corners[j] / 3;
                const double *uo = &c->unit[3 * own], *ug = &c->unit[3 * g];
                if (!all && uo[0] * ug[0] + uo[1] * ug[1] + uo[2] * ug[2] < cos_limit)
                    continue;
                for (int k = 0; k < 3; k++)
                    n[k] += (float)c->face[3 * g + k];
            }
            memcpy(s, n, sizeof n);
        }
    }
}

/* Output vertices: per vertex, one per distinct corner normal; the count of copies is returned. */
static size_t assign_vertices(crease *c)
{
    size_t next = c->nv;
    for (size_t v = 0; v < c->nv; v++) {
        size_t lo = c->start[v], hi = c->start[v + 1];
        for (size_t i = lo; i < hi; i++) {
            const float *s = &c->sum[3 * (size_t)c->corners[i]];
            size_t j = lo;
            while (j < i && memcmp(&c->sum[3 * (size_t)c->corners[j]], s, 3 * sizeof *s) != 0)
                j++;
            c->out[c->corners[i]] = j < i ? c->out[c->corners[j]] : i == lo ? (uint32_t)v : (uint32_t)next++;
        }
    }
    return next - c->nv;
}

bg_status bgi_sf_crease_normals(float **p, float **uv, size_t *nv, uint32_t *idx, size_t nt, double angle_degrees,
                                float **n)
{
    crease c = {*nv, nt, NULL, NULL, NULL, NULL, NULL, NULL};
    *n = NULL;
    if (nt > SIZE_MAX / (9 * sizeof(double)) || *nv >= SIZE_MAX / (3 * sizeof(float)))
        return BG_ERR_OUT_OF_MEMORY;
    c.start = calloc(*nv + 1, sizeof *c.start);
    c.corners = malloc(3 * nt * sizeof *c.corners + 1);
    c.face = malloc(3 * nt * sizeof *c.face + 1);
    c.unit = malloc(3 * nt * sizeof *c.unit + 1);
    c.sum = malloc(9 * nt * sizeof *c.sum + 1);
    c.out = malloc(3 * nt * sizeof *c.out + 1);
    bg_status st = BG_ERR_OUT_OF_MEMORY;
    if (!c.start || !c.corners || !c.face || !c.unit || !c.sum || !c.out)
        goto done;
    list_faces(&c, *p, idx);
    bool all = angle_degrees >= 180.0;
    sum_corners(&c, cos(angle_degrees * 3.14159265358979323846 / 180.0), all);
    size_t copies = assign_vertices(&c);
    size_t total = *nv + copies;
    if (total > UINT32_MAX) {
        st = BG_ERR_LIMIT;
        goto done;
    }
    /* The normals of vertices no triangle uses stay zero, as they would with no creases at all. */
    float *np = copies ? malloc(3 * total * sizeof *np) : *p, *nuv = copies && *uv ? malloc(2 * total * sizeof *nuv) : *uv;
    float *nn = calloc(3 * total, sizeof *nn);
    if (!np || (*uv && !nuv) || !nn) {
        if (np != *p)
            free(np);
        if (nuv != *uv)
            free(nuv);
        free(nn);
        goto done;
    }
    if (copies) {
        memcpy(np, *p, 3 * *nv * sizeof *np);
        if (*uv)
            memcpy(nuv, *uv, 2 * *nv * sizeof *nuv);
    }
    for (size_t i = 0; i < 3 * nt; i++) {
        uint32_t o = c.out[i], from = idx[i];
        memcpy(&nn[3 * (size_t)o], &c.sum[3 * i], 3 * sizeof *nn);
        if (o >= *nv) {
            memcpy(&np[3 * (size_t)o], &(*p)[3 * (size_t)from], 3 * sizeof *np);
            if (*uv)
                memcpy(&nuv[2 * (size_t)o], &(*uv)[2 * (size_t)from], 2 * sizeof *nuv);
        }
        idx[i] = o;
    }
    if (np != *p) {
        free(*p);
        *p = np;
    }
    if (nuv != *uv) {
        free(*uv);
        *uv = nuv;
    }
    *n = nn;
    *nv = total;
    st = BG_OK;
done:
    crease_free(&c);
    return st;
}
