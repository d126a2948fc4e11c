/* A reader of exactly one kind of PLY file, the kind tests/data/bunny.ply is: binary little-endian,
 * an element "vertex" with the properties float x, y, z (in that order, nothing else), then an
 * element "face" with the one property "list uchar uint vertex_indices" (int and vertex_index are
 * accepted too), every face a triangle; comment and obj_info lines anywhere in the header. Anything
 * else is refused rather than half read. */
#ifndef PLY_MESH_H
#define PLY_MESH_H

#include <stddef.h>

#include "meshes.h"

/* Reads the file at path into *out (positions and indices; no normals or uvs), overwritten, and
 * empty on failure. The message in why (when not NULL, truncated to why_size) names the file and the
 * reason: BG_ERR_IO when the file cannot be opened or read, or ends before the counts in its header
 * say (truncated); BG_ERR_INVALID_ARGUMENT for a header this reader does not take, a face that is
 * not a triangle, a vertex index out of range, a coordinate that is not finite, or bytes after the
 * last face; BG_ERR_LIMIT for more than MESH_MAX_TRIANGLES faces or 2^24 vertices;
 * BG_ERR_OUT_OF_MEMORY. */
bg_status ply_mesh_read(const char *path, mesh *out, char *why, size_t why_size);

#endif
