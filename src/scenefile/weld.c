/* Welding a mesh's vertices before its normals are computed (normals.c averages over the faces that
 * share a vertex, so a mesh whose faces share none, as every STL file and some exporters' OBJ and
 * PLY files are, would come out flat-faceted whatever the crease angle).
 *
 * Invariant: two vertices become one exactly when their positions, and their texture coordinates
 * where the mesh has them, are equal bit for bit (with -0 taken as +0). No tolerance: exporters
 * write a shared corner as the same numbers each time it appears, and a tolerance would join
 * distinct vertices of fine meshes and depend on the model's scale. A texture seam (equal position,
 * other coordinates) stays two vertices. The first vertex of each group keeps its place in the
 * order, so a mesh with nothing to weld is left exactly as it was. */
#include "scenefile_internal.h"

#include <stdlib.h>
#include <string.h>

typedef struct weld_key {
    float value[5]; /* position, then uv (zero without) */
    uint32_t vertex;
} weld_key;

static int compare_keys(const void *a, const void *b)
{
    const weld_key *x = a, *y = b;
    int c = memcmp(x->value, y->value, sizeof x->value);
    if (c != 0)
        return c;
    return x->vertex < y->vertex ? -1 : x->vertex > y->vertex;
}

bg_status bgi_sf_weld_vertices(float *p, float *uv, size_t *nv, uint32_t *idx, size_t nt)
{
    size_t n = *nv;
    weld_key *keys = malloc((n ? n : 1) * sizeof *keys);
    uint32_t *first = malloc((n ? n : 1) * sizeof *first);
    if (!keys || !first) {
        free(keys);
        free(first);
        return BG_ERR_OUT_OF_MEMORY;
    }
    for (size_t v = 0; v < n; v++) {
        memset(keys[v].value, 0, sizeof keys[v].value);
        for (int k = 0; k < 3; k++)
            keys[v].value[k] = p[3 * v + k] + 0.0f; /* -0 + 0 is +0 */
        for (int k = 0; uv && k < 2; k++)
            keys[v].value[3 + k] = uv[2 * v + k] + 0.0f;
        keys[v].vertex = (uint32_t)v;
    }
    qsort(keys, n, sizeof *keys, compare_keys);
    /* Within a group the lowest index comes first (the comparison's tie-break): it represents all. */
    for (size_t i = 0; i < n; i++)
        first[keys[i].vertex] = i > 0 && memcmp(keys[i].value, keys[i - 1].value, sizeof keys[i].value) == 0
                                    ? first[keys[i - 1].vertex]
                                    : keys[i].vertex;
    free(keys);
    /* Compact: every representative moves down to the next free place, in its original order. */
    uint32_t *place = first; /* reused: a representative's new index, written over in order */
    size_t kept = 0;
    for (size_t v = 0; v < n; v++) {
        if (first[v] != v) {
            place[v] = place[first[v]]; /* first[v] < v: already placed */
            continue;
        }
        memmove(&p[3 * kept], &p[3 * v], 3 * sizeof *p);
        if (uv)
            memmove(&uv[2 * kept], &uv[2 * v], 2 * sizeof *uv);
        place[v] = (uint32_t)kept++;
    }
    for (size_t i = 0; i < 3 * nt; i++)
        idx[i] = place[idx[i]];
    free(first);
    *nv = kept;
    return BG_OK;
}
