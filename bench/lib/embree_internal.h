/* What the two halves of the Embree peer share: embree_peer.c (device, BVH, ray queries through
 * Embree) and embree_trace.c (the Whitted tracing of tiles over threads). */
#ifndef EMBREE_INTERNAL_H
#define EMBREE_INTERNAL_H

#include <embree3/rtcore.h>

#include "embree_peer.h"
#include "betelgeuse/common/render_settings.h"
#include "betelgeuse/cpu/cpu_internal.h"

#define EMBREE_WAVE_MAX 64 /* rays traced together at one level; more are traced in further waves */
#define EMBREE_MAX_THREADS BG_MAX_THREADS

/* A ray of the Whitted tree, in double: the reference's ray with its skip/inside rule. */
typedef struct peer_ray {
    double o[3], d[3];
    double weight[3];
    uint32_t pixel;  /* index into the tile's radiance */
    uint32_t skip, inside;
} peer_ray;

/* The nearest hit found so far for a ray; object BG_CPU_NONE: none. */
typedef struct peer_hit {
    double t;
    uint32_t object;
    bg_cpu_candidate candidate;
} peer_hit;

/* A shadow segment towards one light from the hit of ray `ray` of the wave, with what that light
 * brings when nothing blocks it (the BRDF is evaluated only then, as in the reference). */
typedef struct shadow_ray {
    double o[3], l[3], t_max;
    uint32_t self, ray;
    double vl, radiance[3];
} shadow_ray;

/* One render thread's buffers (embree_trace.c). */
typedef struct peer_worker peer_worker;

struct embree_peer {
    RTCDevice device;
    int threads, packet_width;
    char device_error[256];
    /* The BVH and the committed state it was built from. */
    RTCScene bvh;
    const bg_scene_state *state;
    uint64_t commit_count;
    uint32_t *prim_object; /* Embree primitive -> object index (the bounded objects) */
    uint32_t prim_count;
    uint32_t *planes;      /* the unbounded objects, tested outside Embree */
    uint32_t plane_count;
    float box_pad;
    double build_ms;
    peer_worker *workers[EMBREE_MAX_THREADS];
};

/* Formats into the caller's message buffer (which may be absent) and returns false. */
bool embree_fail(char *message, size_t size, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---- embree_peer.c: ray queries over the last build ------------------------------------------ */

/* The nearest hit of each of count (<= EMBREE_WAVE_MAX) rays; coherent: camera rays. */
void embree_nearest_hits(const embree_peer *peer, const peer_ray *rays, peer_hit *hits, int count, bool coherent);
/* Whether each of count (<= EMBREE_WAVE_MAX) shadow segments is blocked. */
void embree_trace_shadows(const embree_peer *peer, const shadow_ray *shadows, bool *blocked, int count);

/* ---- embree_trace.c: the render threads' buffers ---------------------------------------------- */

peer_worker *embree_worker_create(void);
void embree_worker_destroy(peer_worker *worker);

#endif
