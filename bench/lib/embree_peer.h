/* A benchmark peer: the same Whitted ray tracer as the CPU reference (docs/shading.md) with Embree 3
 * doing every ray traversal, so the GPU path can be timed against the CPU kernel people pick today.
 * It is no part of the libraries and is built only where Embree is installed (Makefile, bench section).
 *
 * What Embree does and what the reference does:
 * - Traversal: every nearest-hit and shadow query goes through Embree's BVH (rtcIntersect4 /
 *   rtcOccluded4 packets by default, 1, 8 or 16 rays per query on request), over one user
 *   geometry whose primitives are the scene's bounded objects (robust build and traversal, boxes padded
 *   so that float rays cannot cull an object the double ray meets). Planes are unbounded, so they are
 *   not in the BVH: each ray tests them first, outside Embree, and the nearest plane hit becomes the
 *   ray's initial tfar.
 * - The callbacks intersect an object with the CPU reference's own double-precision routines
 *   (bgi_cpu_intersect_object and bgi_cpu_segment_blocked through the object's to_object transform), on
 *   the double ray kept beside Embree's float copy, with the reference's rules: the object a ray leaves
 *   is skipped, a ray inside a refracting object takes its far root, ties go to the object added first,
 *   shadow segments end BG_SHADOW_END_REL short of the light and never test the object they start on.
 * - Shading is the reference's per-hit code (bgi_cpu_hit_attributes, bgi_cpu_surface_eval, bgi_cpu_brdf,
 *   bgi_cpu_mirror_weight, bgi_cpu_fresnel, bgi_cpu_encode_channel), chosen over a float rewrite so that
 *   "the same BRDF" holds to the last bit: only the order of each pixel's sum differs (level by level
 *   instead of depth first), and the images match the reference byte for byte in every shared scene.
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
/* Milliseconds the last BVH build took (0 before any). */
double embree_peer_build_ms(const embree_peer *peer);

/* Renders the scene of the last build into an RGBA8 or RGBA32F image with the settings' max_depth,
 * min_weight, background and encoding; fails if the scene was committed again since. */
bool embree_peer_render(embree_peer *peer, const bg_render_settings *settings, bg_image *image, char *message,
                        size_t message_size);

#endif
