/* What the two halves of the Embree peer share: embree_peer.c (device, BVH, ray queries through
 * Embree) and embree_trace.c (the Whitted tracing of tiles over threads). */
#ifndef EMBREE_INTERNAL_H
#define EMBREE_INTERNAL_H

/* Embree 4 where the Makefile found it (BENCH_EMBREE_VERSION=4), else Embree 3. */
#if defined(BENCH_EMBREE_VERSION) && BENCH_EMBREE_VERSION >= 4
#include <embree4/rtcore.h>
#else
#include <embree3/rtcore.h>
#endif
#include <pthread.h>

#include "embree_peer.h"
#include "betelgeuse/common/render_settings.h"
#include "betelgeuse/cpu/cpu_internal.h"

/* ---- where Embree 3 and 4 differ (everything else is written once, for both) ------------------
 * A query's state, which Embree hands to the callbacks as a pointer to its first member, context:
 * - Embree 3: the context (struct RTCIntersectContext) holds the coherence flag and the filter, and
 *   rtcIntersect1/4/8/16 and rtcOccluded1/4/8/16 take (scene, context, rays);
 * - Embree 4: the context (struct RTCRayQueryContext) holds only the instance stack; flag, filter and
 *   a pointer to the context go in per-call arguments (struct RTCIntersectArguments for
 *   rtcIntersect*, struct RTCOccludedArguments for rtcOccluded*), taken as (scene, rays, arguments).
 *   The arguments' filter runs only in scenes flagged RTC_SCENE_FLAG_FILTER_FUNCTION_IN_ARGUMENTS
 *   (the instanced ones too), only with RTC_FEATURE_FLAG_FILTER_FUNCTION_IN_ARGUMENTS in the feature
 *   mask (rtcInit*Arguments sets every feature), and only on geometries that enable it
 *   (rtcSetGeometryEnableFilterFunctionFromArguments) unless the query sets
 *   RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER, as peer_query_init does.
 * In both, the filter runs on the triangles' hits: a user geometry reports its hits without one
 * (it would call rtcFilterIntersection in Embree 3, rtcInvokeIntersectFilterFromGeometry in 4). */
#if RTC_VERSION_MAJOR >= 4
typedef struct peer_query {
    struct RTCRayQueryContext context;
    struct RTCIntersectArguments intersect;
    struct RTCOccludedArguments occluded;
} peer_query;

#define PEER_SCENE_FLAG_FILTER RTC_SCENE_FLAG_FILTER_FUNCTION_IN_ARGUMENTS

/* Initialises q for a query whose triangle hits go through filter (NULL: no filter). */
static inline void peer_query_init(peer_query *q, bool coherent, RTCFilterFunctionN filter)
{
    rtcInitRayQueryContext(&q->context);
    rtcInitIntersectArguments(&q->intersect);
    rtcInitOccludedArguments(&q->occluded);
    enum RTCRayQueryFlags flags = coherent ? RTC_RAY_QUERY_FLAG_COHERENT : RTC_RAY_QUERY_FLAG_INCOHERENT;
    if (filter)
        flags = (enum RTCRayQueryFlags)(flags | RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER);
    q->intersect.flags = q->occluded.flags = flags;
    q->intersect.context = q->occluded.context = &q->context;
    q->intersect.filter = q->occluded.filter = filter;
}

#define PEER_INTERSECT1(scene, q, rayhit) rtcIntersect1(scene, rayhit, &(q)->intersect)
#define PEER_INTERSECT(n, valid, scene, q, rayhit) rtcIntersect##n(valid, scene, rayhit, &(q)->intersect)
#define PEER_OCCLUDED1(scene, q, ray) rtcOccluded1(scene, ray, &(q)->occluded)
#define PEER_OCCLUDED(n, valid, scene, q, ray) rtcOccluded##n(valid, scene, ray, &(q)->occluded)
#else
typedef struct peer_query {
    struct RTCIntersectContext context;
} peer_query;

#define PEER_SCENE_FLAG_FILTER RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION

static inline void peer_query_init(peer_query *q, bool coherent, RTCFilterFunctionN filter)
{
    rtcInitIntersectContext(&q->context);
    q->context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    q->context.filter = filter;
}

#define PEER_INTERSECT1(scene, q, rayhit) rtcIntersect1(scene, &(q)->context, rayhit)
#define PEER_INTERSECT(n, valid, scene, q, rayhit) rtcIntersect##n(valid, scene, &(q)->context, rayhit)
#define PEER_OCCLUDED1(scene, q, ray) rtcOccluded1(scene, &(q)->context, ray)
#define PEER_OCCLUDED(n, valid, scene, q, ray) rtcOccluded##n(valid, scene, &(q)->context, ray)
#endif

#define EMBREE_WAVE_MAX 64 /* rays traced together at one level; more are traced in further waves */
#define EMBREE_MAX_THREADS BG_MAX_THREADS

/* A ray of the Whitted tree, in double: the reference's ray with its skip/inside rule. A ray leaving
 * a mesh skips only its triangle skip_triangle of object skip (BG_CPU_NONE: the whole object skip). */
typedef struct peer_ray {
    double o[3], d[3];
    double weight[3];
    uint32_t pixel;  /* index into the tile's radiance */
    uint32_t skip, skip_triangle, inside;
} peer_ray;

/* The nearest hit found so far for a ray; object BG_CPU_NONE: none. */
typedef struct peer_hit {
    double t;
    uint32_t object;
    bg_cpu_candidate candidate;
} peer_hit;

/* A shadow segment towards one light from the hit of ray `ray` of the wave, with what that light
 * brings when nothing blocks it (the BRDF is evaluated only then, as in the reference). It never
 * tests the analytic object self it starts on; from a mesh it skips only triangle self_triangle. */
typedef struct shadow_ray {
    double o[3], l[3], t_max;
    uint32_t self, self_triangle, ray;
    double vl, radiance[3];
} shadow_ray;

/* One render thread's buffers (embree_trace.c). */
typedef struct peer_worker peer_worker;

/* Bytes Embree holds, from its memory monitor (called on its build threads, hence the lock). */
typedef struct peer_memory {
    pthread_mutex_t lock;
    long long live;
} peer_memory;

struct embree_peer {
    RTCDevice device;
    int threads, packet_width;
    char device_error[256];
    peer_memory memory;
    /* The BVH and the committed state it was built from. */
    RTCScene bvh;
    const bg_scene_state *state;
    uint64_t commit_count;
    uint32_t *prim_object; /* user primitive -> object index (the bounded analytic objects) */
    uint32_t prim_count;
    uint32_t *planes;      /* the unbounded objects, tested outside Embree */
    uint32_t plane_count;
    /* Mesh objects: one Embree scene of triangles per mesh (instances share it), shown in the BVH by an
     * instance, or directly by its triangles when one object shows it untransformed. */
    RTCScene *mesh_scenes;
    uint32_t mesh_scene_count;
    uint32_t *geom_object; /* geomID in the BVH -> object index; BG_CPU_NONE for the user geometry */
    uint32_t geom_count;
    uint32_t instanced_objects; /* mesh objects shown through an instance */
    float box_pad;
    double build_ms, commit_ms;
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
