/* Procedural triangle meshes for tests and benchmarks: a subdivided icosphere, a torus knot and a
 * heightfield terrain, all deterministic (the same parameters give the same bits everywhere).
 *
 * Every mesh is an indexed triangle list wound counter-clockwise seen from its front: from outside
 * for the closed ones (icosphere, knot), from above (+y) for the terrain. A closed mesh without UVs is
 * a 2-manifold by index (each edge in exactly two triangles, once in each direction); with UVs the
 * vertices on a seam are duplicated (the same position, another uv), so it is closed by position.
 * Texture coordinates follow docs/shading.md 4: the icosphere's are the spherical mapping (seam at
 * x = 0, z < 0, where u jumps from 1 to 0; a triangle crossing it gets u + 1 on its small side, which
 * REPEAT makes the same texels), the terrain's the planar one. */
#ifndef MESHES_H
#define MESHES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "betelgeuse.h"

/* The most triangles a mesh may have: as many primitives as one BVH takes (BG_BVH_MAX_PRIMS), so a
 * per-mesh tree can always be built over it. */
#define MESH_MAX_TRIANGLES (1u << 23)

/* An indexed triangle mesh; all zero is the empty mesh. */
typedef struct mesh {
    uint32_t vertex_count;
    uint32_t triangle_count;
    float *positions;  /* 3 floats per vertex */
    float *normals;    /* 3 floats per vertex, unit length; NULL unless asked for */
    float *uvs;        /* 2 floats per vertex; NULL unless asked for */
    uint32_t *indices; /* 3 per triangle, counter-clockwise seen from the front */
} mesh;

/* Frees the mesh's arrays and leaves it empty (NULL ok). */
void mesh_free(mesh *m);

/* Writes "<format ...>" into why (when not NULL, truncated to why_size) and returns status: the one
 * way the builders and readers of meshes say what went wrong. */
bg_status mesh_fail(char *why, size_t why_size, bg_status status, const char *format, ...);

/* Allocates m's arrays for the counts (normals and uvs only when asked for), contents undefined;
 * BG_ERR_OUT_OF_MEMORY, m left empty and why naming `what`, when memory is refused. */
bg_status mesh_alloc(mesh *m, uint32_t vertex_count, uint32_t triangle_count, bool normals, bool uvs,
                     const char *what, char *why, size_t why_size);

/* The unit icosphere: an icosahedron with vertices at the poles (0, +-1, 0), each triangle split
 * into four `level` times, the new vertices pushed onto the unit sphere. 20 * 4^level triangles and
 * 10 * 4^level + 2 vertices; with uvs 10 * 4^level + 3 * 2^level + 9 (3 * 2^level - 1 seam copies,
 * and each pole once per triangle around it, 5). Normals are the positions (smooth). Defaults: level 0 (the icosahedron); min_triangles 0 (use level); no
 * normals, no uvs. */
typedef struct mesh_icosphere_desc {
    int level;              /* 0 .. 9 */
    uint32_t min_triangles; /* > 0: the smallest level with at least this many triangles (level must be 0) */
    bool normals;
    bool uvs;
} mesh_icosphere_desc;

/* Builds the icosphere into *out (overwritten; empty on failure). BG_ERR_INVALID_ARGUMENT for a bad
 * field, BG_ERR_LIMIT past MESH_MAX_TRIANGLES, BG_ERR_OUT_OF_MEMORY; why says which and why. */
bg_status mesh_icosphere(const mesh_icosphere_desc *desc, mesh *out, char *why, size_t why_size);

/* A tube of radius 0.15 around the (p, q) torus knot
 *   c(s) = ((1 + 0.4 cos(q s)) cos(p s), (1 + 0.4 cos(q s)) sin(p s), 0.4 sin(q s)),  s in [0, 2 pi),
 * which winds p times around the z axis and q times through the hole; segments rings along it of
 * sides vertices each, 2 * segments * sides triangles and segments * sides vertices ((segments + 1)
 * * (sides + 1) with uvs: u = along the knot, v = around the tube, both 0 .. 1). Normals point away
 * from the curve (exact for a tube). Defaults: p 2, q 3 (the trefoil); segments 128, sides 12; no
 * normals, no uvs. For large p and q the tube may cross itself (it still is a closed mesh). */
typedef struct mesh_torus_knot_desc {
    int p, q;      /* 1 .. 64 each, coprime (else the curve runs over itself) */
    int segments;  /* >= 3 */
    int sides;     /* >= 3 */
    bool normals;
    bool uvs;
} mesh_torus_knot_desc;

/* Builds the torus knot into *out, with the errors of mesh_icosphere. */
bg_status mesh_torus_knot(const mesh_torus_knot_desc *desc, mesh *out, char *why, size_t why_size);

/* A terrain over the square x, z in [-1, 1]: an n x n grid of quads ((n + 1)^2 vertices, 2 n^2
 * triangles, every quad cut along the diagonal from (x0, z0) to (x1, z1)) at heights
 *   y = amplitude * (0.5 sin(3 x + 1) cos(2.5 z) + 0.3 sin(7 x - 4 z + 0.5) + 0.2 cos(5 x + 11 z)),
 * front side up. uvs are the planar mapping u = (x + 1) / 2, v = (1 - z) / 2; normals the height
 * function's own. Defaults: n 64; amplitude 0.25 (0 means that default; a negative amplitude
 * mirrors the heights); no normals, no uvs. */
typedef struct mesh_heightfield_desc {
    int n;            /* 1 .. 2048 */
    double amplitude; /* finite */
    bool normals;
    bool uvs;
} mesh_heightfield_desc;

/* Builds the terrain into *out, with the errors of mesh_icosphere. */
bg_status mesh_heightfield(const mesh_heightfield_desc *desc, mesh *out, char *why, size_t why_size);

#endif
