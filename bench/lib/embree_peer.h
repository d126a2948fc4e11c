/* A benchmark peer: the same Whitted ray tracer as the CPU reference (docs/shading.md) with Embree
 * (3 or 4: embree_internal.h) doing every ray traversal, so the GPU path can be timed against the CPU
 * kernel people pick today.
 * It is no part of the libraries and is built only where Embree is installed (Makefile, bench section).
 *
 * What Embree does and what the reference does:
 * - Traversal: every nearest-hit and shadow query goes through Embree's BVH (rtcIntersect4 /
 *   rtcOccluded4 packets by default, 1, 8 or 16 rays per query on request), over one user
 *   geometry whose primitives are the scene's bounded analytic objects (boxes padded so that float
 *   rays cannot cull an object the double ray meets) and over the meshes' triangles. Planes are unbounded, so
 *   they are not in the BVH: each ray tests them first, outside Embree, and the nearest plane hit
 *   becomes the ray's initial tfar.
 * - The callbacks intersect an analytic object with the CPU reference's own double-precision routines
 *   (bgi_cpu_intersect_object and bgi_cpu_segment_blocked through the object's to_object transform), on
 *   the double ray kept beside Embree's float copy, with the reference's rules: the object a ray leaves
 *   is skipped, a ray inside a refracting object takes its far root, ties go to the object added first,
 *   shadow segments end BG_SHADOW_END_REL short of the light and never test the object they start on.
 * - Meshes are Embree's own: each mesh (bg_mesh_data, shared by its instances) is one
 *   RTC_GEOMETRY_TYPE_TRIANGLE in a scene of its own, shown in the BVH by an RTC_GEOMETRY_TYPE_INSTANCE
 *   per object with the object's transform in float, or, when a single object shows a mesh with the
 *   identity transform, by the triangle geometry itself (no instance level to pay). The index buffer is
 *   the scene's own array (rtcSetSharedGeometryBuffer); the vertices are copied once per mesh into a
 *   buffer of Embree's, because Embree reads the last vertex with a 16-byte load and the scene's float
 *   array has no padding behind it. Embree finds the hit in float (robust mode), and the
 *   hit's attributes are the reference's, in double, from Embree's triangle and barycentric weights
 *   (bgi_cpu_mesh_attributes: interpolated normals kept on the seen side, face normals otherwise, uv,
 *   tangent); which side is met (front: entering) is decided in double as the reference does. A ray
 *   leaving a mesh skips its triangle (the query's filter) and starts off the surface along the
 *   geometric normal by docs/shading.md 2.10's rule taken in float units, 4 * 2^-23 of the point's
 *   magnitude (the reference's 256 double ulps would vanish when Embree rounds the origin to float;
 *   embree_trace.c gives the measurements behind 4); mesh objects that cast no shadow are dropped by
 *   the same filter on shadow rays.
 * - Build: every scene ROBUST (no accuracy-reducing optimisations: no triangle or box lost to float
 *   rounding at edges; the user geometry needs it for the padded boxes), RTC_BUILD_QUALITY_MEDIUM (Embree's default, binned SAH like the
 *   reference's mesh trees; HIGH adds spatial splits), the filter flag where there are
 *   meshes (the triangle skip: CONTEXT_FILTER_FUNCTION in Embree 3, FILTER_FUNCTION_IN_ARGUMENTS in
 *   4). Timed: the whole build (embree_peer_build_ms) and its rtcCommitScene calls alone
 *   (embree_peer_commit_ms); Embree's memory through its device memory monitor.
 * - Shading is the reference's per-hit code (bgi_cpu_hit_attributes, bgi_cpu_surface_eval, bgi_cpu_brdf,
 *   bgi_cpu_mirror_weight, bgi_cpu_fresnel, bgi_encode_channel), chosen over a float rewrite so that
 *   "the same BRDF" holds to the last bit: only the order of each pixel's sum differs (level by level
 *   instead of depth first), and the images match the reference byte for byte in every analytic scene
 *   of bench_embree. Mesh scenes differ in the few pixels where Embree's float hit or shadow test
 *   parts from the reference's double one (bench_mesh gives the error).
 *   The price: scalar double shading is most of a frame, so on scenes of one or two objects the peer
 *   costs about 1.1-1.2x the reference's CPU time (Embree's calls, the packets); its BVH pays as the
 *   object count grows (bench_embree prints the reference's time beside the peer's).
 * - Threads: pthreads take 8x8 tiles from a shared counter; each tile traces its rays level by level
 *   (the level's nearest hits, then one batch of shadow segments per light, then the next level's
 *   rays), which keeps the packets full. */
#ifndef EMBREE_PEER_H
#define EMBREE_PEER_H

#include <stdbool.h>
#include <stddef.h>

#include "betelgeuse.h"

typedef struct embree_peer embree_peer;

typedef struct embree_peer_desc {
    int threads;      /* render and BVH build threads; 0: the online cores */
    int packet_width; /* rays per Embree query: 1, 4, 8 or 16; 0: 4 (measured in CPU time on a 2-core
                         AVX-512 machine: 4 and 8 tie, 1 is 5-10 % slower, 16 10-60 %) */
} embree_peer_desc;

/* Creates the peer and its Embree device (desc may be NULL for defaults). NULL and a message on failure. */
embree_peer *embree_peer_create(const embree_peer_desc *desc, char *message, size_t message_size);
void embree_peer_destroy(embree_peer *peer);
/* "rtcIntersect4/rtcOccluded4 packets, 2 threads": how the peer traces, for a benchmark's header. */
const char *embree_peer_describe(const embree_peer *peer, char *buffer, size_t size);

/* Builds the BVH of a committed scene (timed: embree_peer_build_ms). The scene must stay alive and
 * uncommitted while the peer renders it; build again after a new commit. */
bool embree_peer_build(embree_peer *peer, const bg_scene *scene, char *message, size_t message_size);
/* Milliseconds the last BVH build took (0 before any): all of it, and its rtcCommitScene calls alone
 * (the BVH builds proper, without copying the vertices and creating the geometries). */
double embree_peer_build_ms(const embree_peer *peer);
double embree_peer_commit_ms(const embree_peer *peer);
/* Bytes Embree's device holds now (its memory monitor): the BVHs and the vertex copies of the last
 * build, not the index arrays it shares with the scene. */
size_t embree_peer_bytes(embree_peer *peer);
/* Mesh objects of the last build shown through an Embree instance (the others are its triangles). */
unsigned embree_peer_instanced_objects(const embree_peer *peer);

/* Renders the scene of the last build into an RGBA8 or RGBA32F image with the settings' max_depth,
 * min_weight, background and encoding; fails if the scene was committed again since. */
bool embree_peer_render(embree_peer *peer, const bg_render_settings *settings, bg_image *image, char *message,
                        size_t message_size);

/* The peer as a contestant of bench_measure.h's rounds: embree_peer_frame's job. */
typedef struct embree_peer_job {
    embree_peer *peer;
    bg_render_settings settings;
} embree_peer_job;

/* A bench_frame_fn: one frame of the job's peer into image; prints the reason on failure. */
bool embree_peer_frame(void *job, bg_image *image);

#endif
