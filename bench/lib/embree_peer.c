/* The Embree side of the benchmark peer (embree_peer.h): the device, the BVH over the committed
 * scene's bounded analytic objects as one user geometry and its meshes as triangle geometries, the
 * callbacks, and the packet queries. */
#include "embree_internal.h" /* same directory: bench/lib objects are built without -Ibench */

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define MAX_PACKET 16

/* Object boxes are widened by this share of the scene's magnitude. Embree traverses with a float copy
 * of each double ray, whose origin and direction are off by up to 2^-24 of their magnitude, so along
 * the ray the float line can stray by about 2^-24 (|o| + t) from the double one. Rays start at the
 * camera or on objects, so 2^-16 of the largest coordinate in the scene covers that with a margin of
 * 2^8 (also for rays starting on a plane up to 2^8 times farther out); a box that is too wide only
 * costs a callback that the double test then rejects. */
#define BOX_PAD_REL 0x1p-16

/* A packet and its valid mask. Embree loads the mask with aligned vector loads, so it gets the
 * packet's own alignment (64 bytes): it follows a packet whose size is a multiple of that. */
typedef struct hit_packet {
    struct RTCRayHit16 rays;
    int valid[MAX_PACKET];
} hit_packet;

typedef struct shadow_packet {
    struct RTCRay16 rays;
    int valid[MAX_PACKET];
} shadow_packet;

/* What Embree hands back to the callbacks: the context comes first so a pointer to it is one to this. */
typedef struct query_context {
    peer_query base; /* its context first (embree_internal.h) */
    const embree_peer *peer;
    const peer_ray *rays;       /* nearest-hit queries, indexed by the Embree ray's id */
    peer_hit *hits;
    const shadow_ray *shadows;  /* occlusion queries */
} query_context;

bool embree_fail(char *message, size_t size, const char *format, ...)
{
    if (message && size > 0) {
        va_list args;
        va_start(args, format);
        vsnprintf(message, size, format, args);
        va_end(args);
    }
    return false;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* The smallest float >= x (+inf past the float range): a tfar that never cuts the double hit off. */
static float float_at_or_above(double x)
{
    if (!(x < FLT_MAX))
        return INFINITY;
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* The largest float <= x. */
static float float_at_or_below(double x)
{
    return -float_at_or_above(-x);
}

/* ---- Embree's SOA packets, addressed as in rtcore_ray.h's C++ helpers (a packet of N rays holds
 * field k of lane i at float k N + i; the hit follows the 12 ray fields) ---------------------- */

enum { RAY_ORG_X, RAY_ORG_Y, RAY_ORG_Z, RAY_TNEAR, RAY_DIR_X, RAY_DIR_Y, RAY_DIR_Z, RAY_TIME, RAY_TFAR, RAY_MASK,
       RAY_ID, RAY_FLAGS, RAY_FIELDS };
enum { HIT_NG_X, HIT_NG_Y, HIT_NG_Z, HIT_U, HIT_V, HIT_PRIM_ID, HIT_GEOM_ID, HIT_INST_ID };

static float *lane_float(void *soa, unsigned n, unsigned field, unsigned i)
{
    return (float *)soa + field * n + i;
}

static unsigned *lane_uint(void *soa, unsigned n, unsigned field, unsigned i)
{
    return (unsigned *)soa + field * n + i;
}

static void *hit_part(void *rayhit, unsigned n)
{
    return (float *)rayhit + RAY_FIELDS * n;
}

/* Writes a double ray into lane i as Embree's float ray over (0, tfar]; id names its record. */
static void fill_lane(void *ray, unsigned n, unsigned i, const double o[3], const double d[3], float tfar,
                      unsigned id)
{
    for (unsigned k = 0; k < 3; k++) {
        *lane_float(ray, n, RAY_ORG_X + k, i) = (float)o[k];
        *lane_float(ray, n, RAY_DIR_X + k, i) = (float)d[k];
    }
    *lane_float(ray, n, RAY_TNEAR, i) = 0.0f;
    *lane_float(ray, n, RAY_TIME, i) = 0.0f;
    *lane_float(ray, n, RAY_TFAR, i) = tfar;
    *lane_uint(ray, n, RAY_MASK, i) = ~0u;
    *lane_uint(ray, n, RAY_ID, i) = id;
    *lane_uint(ray, n, RAY_FLAGS, i) = 0;
}

/* ---- the user geometry: one primitive per bounded object ----------------------------------- */

static void object_bounds(const struct RTCBoundsFunctionArguments *args)
{
    const embree_peer *peer = args->geometryUserPtr;
    const bg_object_data *object = &peer->state->objects[peer->prim_object[args->primID]];
    struct RTCBounds *b = args->bounds_o;
    b->lower_x = float_at_or_below(object->bounds_min[0]) - peer->box_pad;
    b->lower_y = float_at_or_below(object->bounds_min[1]) - peer->box_pad;
    b->lower_z = float_at_or_below(object->bounds_min[2]) - peer->box_pad;
    b->upper_x = float_at_or_above(object->bounds_max[0]) + peer->box_pad;
    b->upper_y = float_at_or_above(object->bounds_max[1]) + peer->box_pad;
    b->upper_z = float_at_or_above(object->bounds_max[2]) + peer->box_pad;
}

/* Keeps a candidate up to t_max (the ray's best, or nearer where Embree met a mesh first) when it is
 * nearer than the ray's best, or as near and added earlier (the reference's tie rule); the nearest
 * root, or the far root for the object the ray travels inside. */
static bool offer_object(const bg_scene_state *state, uint32_t index, const peer_ray *ray, double t_max,
                         peer_hit *best)
{
    if (index == ray->skip)
        return false;
    bg_cpu_candidate c;
    if (!bgi_cpu_intersect_object(&state->objects[index], ray->o, ray->d, index == ray->inside, t_max, &c))
        return false;
    if (c.t == best->t && index > best->object)
        return false;
    best->t = c.t;
    best->object = index;
    best->candidate = c;
    return true;
}

static void object_intersect(const struct RTCIntersectFunctionNArguments *args)
{
    const embree_peer *peer = args->geometryUserPtr;
    const query_context *q = (const query_context *)args->context;
    uint32_t index = peer->prim_object[args->primID];
    unsigned n = args->N;
    void *hit = hit_part(args->rayhit, n);
    for (unsigned i = 0; i < n; i++) {
        if (!args->valid[i])
            continue;
        unsigned id = *lane_uint(args->rayhit, n, RAY_ID, i);
        double tfar = *lane_float(args->rayhit, n, RAY_TFAR, i);
        peer_hit *best = &q->hits[id];
        if (!offer_object(peer->state, index, &q->rays[id], tfar < best->t ? tfar : best->t, best))
            continue;
        *lane_float(args->rayhit, n, RAY_TFAR, i) = float_at_or_above(q->hits[id].t);
        *lane_uint(hit, n, HIT_PRIM_ID, i) = args->primID;
        *lane_uint(hit, n, HIT_GEOM_ID, i) = args->geomID;
        *lane_uint(hit, n, HIT_INST_ID, i) = args->context->instID[0];
    }
}

/* The reference's shadow rule: shadow casters only, never the object the segment starts on. */
static bool blocks(const bg_scene_state *state, uint32_t index, const shadow_ray *s)
{
    const bg_object_data *object = &state->objects[index];
    return index != s->self && object->casts_shadows && bgi_cpu_segment_blocked(object, s->o, s->l, s->t_max);
}

static void object_occluded(const struct RTCOccludedFunctionNArguments *args)
{
    const embree_peer *peer = args->geometryUserPtr;
    const query_context *q = (const query_context *)args->context;
    uint32_t index = peer->prim_object[args->primID];
    unsigned n = args->N;
    for (unsigned i = 0; i < n; i++) {
        if (!args->valid[i])
            continue;
        unsigned id = *lane_uint(args->ray, n, RAY_ID, i);
        if (blocks(peer->state, index, &q->shadows[id]))
            *lane_float(args->ray, n, RAY_TFAR, i) = -INFINITY; /* Embree's mark for "occluded" */
    }
}

/* ---- meshes: Embree's triangles under the reference's skip and shadow rules ------------------- */

/* The object of a triangle hit: the instance's, or the triangle geometry's own at the top level. */
static uint32_t mesh_object_of(const embree_peer *peer, unsigned geom, unsigned inst)
{
    unsigned top = inst != RTC_INVALID_GEOMETRY_ID ? inst : geom;
    return top < peer->geom_count ? peer->geom_object[top] : BG_CPU_NONE;
}

/* The filter of queries whose rays may start on a mesh: drops the triangle a ray leaves
 * and, on shadow rays, the meshes that cast no shadow (Embree calls it for triangle hits only: the
 * user geometry reports its hits without it). */
static void mesh_filter(const struct RTCFilterFunctionNArguments *args)
{
    const query_context *q = (const query_context *)args->context;
    const embree_peer *peer = q->peer;
    unsigned n = args->N;
    for (unsigned i = 0; i < n; i++) {
        if (!args->valid[i])
            continue;
        unsigned id = *lane_uint(args->ray, n, RAY_ID, i);
        uint32_t prim = *lane_uint(args->hit, n, HIT_PRIM_ID, i);
        uint32_t object = mesh_object_of(peer, *lane_uint(args->hit, n, HIT_GEOM_ID, i),
                                         *lane_uint(args->hit, n, HIT_INST_ID, i));
        if (object == BG_CPU_NONE)
            continue;
        bool drop;
        if (q->shadows) {
            const shadow_ray *s = &q->shadows[id];
            drop = !peer->state->objects[object].casts_shadows || (object == s->self && prim == s->self_triangle);
        } else {
            const peer_ray *r = &q->rays[id];
            drop = object == r->skip && prim == r->skip_triangle;
        }
        if (drop)
            args->valid[i] = 0;
    }
}

/* The candidate of Embree's triangle hit on a mesh object, as bgi_cpu_mesh_nearest would give it:
 * weights (1 - u - v, u, v) of the vertices, and the side met, decided in double in object space. */
static void mesh_candidate(const bg_object_data *object, const peer_ray *ray, float t, uint32_t triangle, float u,
                           float v, bg_cpu_candidate *c)
{
    const bg_mesh_data *m = object->mesh;
    double oo[3], od[3], p[3][3], e1[3], e2[3], ng[3];
    bgi_cpu_object_ray(object, ray->o, ray->d, oo, od);
    for (int k = 0; k < 3; k++) {
        const float *x = &m->positions[3 * (size_t)m->indices[3 * (size_t)triangle + (size_t)k]];
        bg_v3_set(p[k], x[0], x[1], x[2]);
    }
    for (int i = 0; i < 3; i++) {
        e1[i] = p[1][i] - p[0][i];
        e2[i] = p[2][i] - p[0][i];
    }
    bg_v3_cross(e1, e2, ng);
    c->t = t;
    c->root = bg_v3_dot(od, ng) < 0.0 ? 0 : 1;
    c->triangle = triangle;
    c->bary[1] = u;
    c->bary[2] = v;
    c->bary[0] = 1.0 - c->bary[1] - c->bary[2];
    for (int i = 0; i < 3; i++)
        c->p[i] = oo[i] + c->t * od[i];
    bg_v3_set(c->n, 0.0, 0.0, 0.0);
}

/* ---- building the BVH ------------------------------------------------------------------------ */

static void device_error(void *user, enum RTCError code, const char *text)
{
    embree_peer *peer = user;
    if (!peer->device_error[0])
        snprintf(peer->device_error, sizeof peer->device_error, "Embree error %d: %s", (int)code, text ? text : "");
}

/* Counts Embree's allocations (bytes > 0) and frees (bytes < 0); never refuses one. */
static bool memory_monitor(void *user, ssize_t bytes, bool post)
{
    (void)post;
    peer_memory *m = user;
    pthread_mutex_lock(&m->lock);
    m->live += (long long)bytes;
    pthread_mutex_unlock(&m->lock);
    return true;
}

static void release_bvh(embree_peer *peer)
{
    if (peer->bvh)
        rtcReleaseScene(peer->bvh);
    for (uint32_t i = 0; i < peer->mesh_scene_count; i++)
        rtcReleaseScene(peer->mesh_scenes[i]);
    free(peer->mesh_scenes);
    free(peer->geom_object);
    free(peer->prim_object);
    free(peer->planes);
    peer->bvh = NULL;
    peer->mesh_scenes = NULL;
    peer->geom_object = peer->prim_object = peer->planes = NULL;
    peer->prim_count = peer->plane_count = peer->mesh_scene_count = peer->geom_count = 0;
    peer->instanced_objects = 0;
    peer->state = NULL;
}

/* Splits the objects into user primitives (bounded analytic), planes (unbounded) and meshes (left to
 * build_meshes), and sizes the box padding. */
static bool sort_objects(embree_peer *peer, const bg_scene_state *state)
{
    size_t n = state->object_count ? state->object_count : 1;
    peer->prim_object = malloc(n * sizeof *peer->prim_object);
    peer->planes = malloc(n * sizeof *peer->planes);
    peer->geom_object = malloc((n + 1) * sizeof *peer->geom_object);
    peer->mesh_scenes = calloc(n, sizeof *peer->mesh_scenes);
    if (!peer->prim_object || !peer->planes || !peer->geom_object || !peer->mesh_scenes)
        return false;
    const bg_vec3 e = state->camera.camera.position;
    double magnitude = fmax(fabs(e.x), fmax(fabs(e.y), fabs(e.z)));
    for (uint32_t j = 0; j < state->object_count; j++) {
        const bg_object_data *object = &state->objects[j];
        if (object->mesh)
            continue;
        if (!object->bounded) {
            peer->planes[peer->plane_count++] = j;
            continue;
        }
        peer->prim_object[peer->prim_count++] = j;
        for (int k = 0; k < 3; k++)
            magnitude = fmax(magnitude, fmax(fabs(object->bounds_min[k]), fabs(object->bounds_max[k])));
    }
    peer->box_pad = float_at_or_above(fmax(magnitude * BOX_PAD_REL, FLT_MIN));
    return true;
}

/* Attaches geometry g to the BVH as the geometry of object (BG_CPU_NONE: the user geometry). */
static void attach(embree_peer *peer, RTCGeometry g, uint32_t object)
{
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(peer->bvh, g);
    rtcReleaseGeometry(g);
    if (id < peer->state->object_count + 1) {
        while (peer->geom_count <= id)
            peer->geom_object[peer->geom_count++] = BG_CPU_NONE;
        peer->geom_object[id] = object;
    }
}

/* The triangles of one mesh: the vertices copied into Embree's padded buffer, the indices shared. */
static RTCGeometry mesh_geometry(embree_peer *peer, const bg_mesh_data *m)
{
    RTCGeometry g = rtcNewGeometry(peer->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g)
        return NULL;
    float *vertices = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                              m->vertex_count);
    if (vertices)
        memcpy(vertices, m->positions, (size_t)m->vertex_count * 3 * sizeof(float));
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->indices, 0, 3 * sizeof(uint32_t),
                               m->triangle_count);
    return g;
}

static bool is_identity(const double m[4][4])
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            if (m[r][c] != (r == c ? 1.0 : 0.0))
                return false;
    return true;
}

/* How many objects show mesh m, and (in first) the lowest index of one. */
static uint32_t showing(const bg_scene_state *state, const bg_mesh_data *m, uint32_t *first)
{
    uint32_t count = 0;
    *first = BG_CPU_NONE;
    for (uint32_t j = 0; j < state->object_count; j++)
        if (state->objects[j].mesh == m && count++ == 0)
            *first = j;
    return count;
}

static void set_flags(RTCScene scene, enum RTCSceneFlags flags)
{
    rtcSetSceneFlags(scene, flags);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
}

/* Every mesh object into the BVH: a mesh shown by one untransformed object as its triangles, any
 * other through one scene per mesh and an instance per object. Returns the meshes' commit time. */
static double build_meshes(embree_peer *peer, const bg_scene_state *state)
{
    const enum RTCSceneFlags flags = RTC_SCENE_FLAG_ROBUST | PEER_SCENE_FLAG_FILTER;
    double commit_ms = 0.0;
    for (uint32_t j = 0; j < state->object_count; j++) {
        const bg_object_data *object = &state->objects[j];
        uint32_t first = BG_CPU_NONE, shows = object->mesh ? showing(state, object->mesh, &first) : 0;
        if (first != j)
            continue; /* each mesh once, at its first object */
        if (shows == 1 && is_identity(object->to_world)) {
            RTCGeometry g = mesh_geometry(peer, object->mesh);
            if (g)
                attach(peer, g, j);
            continue;
        }
        RTCScene ms = rtcNewScene(peer->device);
        if (!ms)
            continue;
        peer->mesh_scenes[peer->mesh_scene_count++] = ms;
        set_flags(ms, flags);
        RTCGeometry g = mesh_geometry(peer, object->mesh);
        if (g) {
            rtcCommitGeometry(g);
            rtcAttachGeometry(ms, g);
            rtcReleaseGeometry(g);
        }
        double t0 = now_ms();
        rtcCommitScene(ms);
        commit_ms += now_ms() - t0;
        for (uint32_t k = j; k < state->object_count; k++) {
            const bg_object_data *shown = &state->objects[k];
            if (shown->mesh != object->mesh)
                continue;
            RTCGeometry inst = rtcNewGeometry(peer->device, RTC_GEOMETRY_TYPE_INSTANCE);
            if (!inst)
                continue;
            float xfm[12]; /* 3x4, column major */
            for (int c = 0; c < 4; c++)
                for (int r = 0; r < 3; r++)
                    xfm[3 * c + r] = (float)shown->to_world[r][c];
            rtcSetGeometryInstancedScene(inst, ms);
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            attach(peer, inst, k);
            peer->instanced_objects++;
        }
    }
    return commit_ms;
}

static bool build_bvh(embree_peer *peer, const bg_scene_state *state, char *message, size_t size)
{
    double t0 = now_ms();
    release_bvh(peer);
    peer->device_error[0] = '\0';
    if (!sort_objects(peer, state)) {
        release_bvh(peer);
        return embree_fail(message, size, "embree peer: out of memory");
    }
    peer->state = state;
    peer->commit_count = state->commit_count;
    peer->bvh = rtcNewScene(peer->device);
    peer->commit_ms = 0.0;
    if (peer->bvh) {
        /* Robust: Embree's float traversal must not lose a box a grazing double ray meets, nor a
         * triangle at an edge; the query's filter is the triangle skip of rays leaving a mesh. */
        set_flags(peer->bvh, RTC_SCENE_FLAG_ROBUST |
                                 (state->mesh_object_count > 0 ? PEER_SCENE_FLAG_FILTER : 0));
        peer->commit_ms = build_meshes(peer, state);
    }
    if (peer->bvh && peer->prim_count > 0) {
        RTCGeometry g = rtcNewGeometry(peer->device, RTC_GEOMETRY_TYPE_USER);
        if (g) {
            rtcSetGeometryUserPrimitiveCount(g, peer->prim_count);
            rtcSetGeometryUserData(g, peer);
            rtcSetGeometryBoundsFunction(g, object_bounds, NULL);
            rtcSetGeometryIntersectFunction(g, object_intersect);
            rtcSetGeometryOccludedFunction(g, object_occluded);
            attach(peer, g, BG_CPU_NONE);
        }
    }
    if (peer->bvh) {
        double c0 = now_ms();
        rtcCommitScene(peer->bvh);
        peer->commit_ms += now_ms() - c0;
    }
    if (!peer->bvh || peer->device_error[0]) {
        const char *why = peer->device_error[0] ? peer->device_error : "rtcNewScene failed";
        embree_fail(message, size, "embree peer: %s", why);
        release_bvh(peer);
        return false;
    }
    peer->build_ms = now_ms() - t0;
    return true;
}

/* ---- ray queries ------------------------------------------------------------------------------ */

/* filtered: whether Embree calls mesh_filter on the query's triangle hits, needed where a ray may
 * start on a mesh or meet a mesh that casts no shadow; without it Embree calls no filter at all. */
static void init_context(query_context *q, const embree_peer *peer, bool coherent, bool filtered)
{
    memset(q, 0, sizeof *q);
    peer_query_init(&q->base, coherent, filtered ? mesh_filter : NULL);
    q->peer = peer;
}

static void intersect_packet(const embree_peer *peer, query_context *q, hit_packet *p)
{
    switch (peer->packet_width) {
    case 1: PEER_INTERSECT1(peer->bvh, &q->base, (struct RTCRayHit *)&p->rays); break;
    case 4: PEER_INTERSECT(4, p->valid, peer->bvh, &q->base, (struct RTCRayHit4 *)&p->rays); break;
    case 8: PEER_INTERSECT(8, p->valid, peer->bvh, &q->base, (struct RTCRayHit8 *)&p->rays); break;
    default: PEER_INTERSECT(16, p->valid, peer->bvh, &q->base, &p->rays); break;
    }
}

static void occluded_packet(const embree_peer *peer, query_context *q, shadow_packet *p)
{
    switch (peer->packet_width) {
    case 1: PEER_OCCLUDED1(peer->bvh, &q->base, (struct RTCRay *)&p->rays); break;
    case 4: PEER_OCCLUDED(4, p->valid, peer->bvh, &q->base, (struct RTCRay4 *)&p->rays); break;
    case 8: PEER_OCCLUDED(8, p->valid, peer->bvh, &q->base, (struct RTCRay8 *)&p->rays); break;
    default: PEER_OCCLUDED(16, p->valid, peer->bvh, &q->base, &p->rays); break;
    }
}

/* Where Embree's last accepted hit of lane i is a triangle, it is the ray's nearest: it replaces what
 * the planes and the user geometry had (their hits made tfar, so a triangle Embree kept is nearer). */
static void take_triangle_hit(const embree_peer *peer, hit_packet *p, unsigned n, unsigned i, const peer_ray *ray,
                              peer_hit *hit)
{
    void *h = hit_part(&p->rays, n);
    unsigned geom = *lane_uint(h, n, HIT_GEOM_ID, i), inst = *lane_uint(h, n, HIT_INST_ID, i);
    if (geom == RTC_INVALID_GEOMETRY_ID)
        return;
    uint32_t object = mesh_object_of(peer, geom, inst);
    if (object == BG_CPU_NONE)
        return; /* the user geometry's: already in hit */
    float t = *lane_float(&p->rays, n, RAY_TFAR, i);
    hit->t = t;
    hit->object = object;
    mesh_candidate(&peer->state->objects[object], ray, t, *lane_uint(h, n, HIT_PRIM_ID, i), *lane_float(h, n, HIT_U, i),
                   *lane_float(h, n, HIT_V, i), &hit->candidate);
}

/* The nearest hit of every ray: planes first (outside Embree), then the BVH with tfar at that hit. */
void embree_nearest_hits(const embree_peer *peer, const peer_ray *rays, peer_hit *hits, int count, bool coherent)
{
    bool leaves_mesh = false;
    for (int k = 0; k < count; k++) {
        hits[k].t = DBL_MAX;
        hits[k].object = BG_CPU_NONE;
        for (uint32_t j = 0; j < peer->plane_count; j++)
            offer_object(peer->state, peer->planes[j], &rays[k], hits[k].t, &hits[k]);
        leaves_mesh = leaves_mesh || rays[k].skip_triangle != BG_CPU_NONE;
    }
    if (peer->geom_count == 0)
        return;
    query_context q;
    init_context(&q, peer, coherent, leaves_mesh);
    q.rays = rays;
    q.hits = hits;
    const unsigned n = (unsigned)peer->packet_width;
    hit_packet packet;
    for (int base = 0; base < count; base += (int)n) {
        for (unsigned i = 0; i < n; i++) {
            int k = base + (int)i;
            packet.valid[i] = k < count ? -1 : 0;
            if (k >= count)
                continue;
            fill_lane(&packet.rays, n, i, rays[k].o, rays[k].d, float_at_or_above(hits[k].t), (unsigned)k);
            *lane_uint(hit_part(&packet.rays, n), n, HIT_GEOM_ID, i) = RTC_INVALID_GEOMETRY_ID;
            *lane_uint(hit_part(&packet.rays, n), n, HIT_INST_ID, i) = RTC_INVALID_GEOMETRY_ID;
        }
        intersect_packet(peer, &q, &packet);
        for (unsigned i = 0; i < n && base + (int)i < count; i++)
            take_triangle_hit(peer, &packet, n, i, &rays[base + (int)i], &hits[base + (int)i]);
    }
}

/* Marks each shadow segment blocked or not: planes first, the rest through Embree. */
void embree_trace_shadows(const embree_peer *peer, const shadow_ray *shadows, bool *blocked, int count)
{
    int pending[EMBREE_WAVE_MAX], pending_count = 0;
    for (int k = 0; k < count; k++) {
        blocked[k] = false;
        for (uint32_t j = 0; j < peer->plane_count && !blocked[k]; j++)
            blocked[k] = blocks(peer->state, peer->planes[j], &shadows[k]);
        if (!blocked[k] && peer->geom_count > 0)
            pending[pending_count++] = k;
    }
    query_context q;
    init_context(&q, peer, false, peer->state->mesh_object_count > 0);
    q.shadows = shadows;
    const unsigned n = (unsigned)peer->packet_width;
    shadow_packet packet;
    for (int base = 0; base < pending_count; base += (int)n) {
        for (unsigned i = 0; i < n; i++) {
            int p = base + (int)i;
            packet.valid[i] = p < pending_count ? -1 : 0;
            if (p >= pending_count)
                continue;
            const shadow_ray *s = &shadows[pending[p]];
            fill_lane(&packet.rays, n, i, s->o, s->l, float_at_or_above(s->t_max * (1.0 - BG_SHADOW_END_REL)),
                      (unsigned)pending[p]);
        }
        occluded_packet(peer, &q, &packet);
        for (unsigned i = 0; i < n && base + (int)i < pending_count; i++)
            blocked[pending[base + (int)i]] = *lane_float(&packet.rays, n, RAY_TFAR, i) < 0.0f;
    }
}

/* ---- the public calls ------------------------------------------------------------------------- */

embree_peer *embree_peer_create(const embree_peer_desc *desc, char *message, size_t message_size)
{
    embree_peer_desc d = desc ? *desc : (embree_peer_desc){0, 0};
    if (d.threads == 0) {
        long online = sysconf(_SC_NPROCESSORS_ONLN);
        d.threads = online < 1 ? 1 : (online > EMBREE_MAX_THREADS ? EMBREE_MAX_THREADS : (int)online);
    }
    if (d.packet_width == 0)
        d.packet_width = 4;
    if (d.threads < 1 || d.threads > EMBREE_MAX_THREADS) {
        embree_fail(message, message_size, "embree peer: threads %d is not in 0..%d", d.threads, EMBREE_MAX_THREADS);
        return NULL;
    }
    if (d.packet_width != 1 && d.packet_width != 4 && d.packet_width != 8 && d.packet_width != 16) {
        embree_fail(message, message_size, "embree peer: packet_width %d is not 0, 1, 4, 8 or 16", d.packet_width);
        return NULL;
    }
    embree_peer *peer = calloc(1, sizeof *peer);
    if (!peer) {
        embree_fail(message, message_size, "embree peer: out of memory");
        return NULL;
    }
    if (pthread_mutex_init(&peer->memory.lock, NULL) != 0) {
        free(peer);
        embree_fail(message, message_size, "embree peer: pthread_mutex_init failed");
        return NULL;
    }
    peer->threads = d.threads;
    peer->packet_width = d.packet_width;
    char config[64];
    snprintf(config, sizeof config, "threads=%d", d.threads);
    peer->device = rtcNewDevice(config);
    if (!peer->device) {
        embree_fail(message, message_size, "embree peer: rtcNewDevice(\"%s\") failed (error %d)", config,
                    (int)rtcGetDeviceError(NULL));
        pthread_mutex_destroy(&peer->memory.lock);
        free(peer);
        return NULL;
    }
    rtcSetDeviceErrorFunction(peer->device, device_error, peer);
    rtcSetDeviceMemoryMonitorFunction(peer->device, memory_monitor, &peer->memory);
    for (int i = 0; i < d.threads; i++) {
        peer->workers[i] = embree_worker_create();
        if (!peer->workers[i]) {
            embree_peer_destroy(peer);
            embree_fail(message, message_size, "embree peer: out of memory");
            return NULL;
        }
    }
    return peer;
}

void embree_peer_destroy(embree_peer *peer)
{
    if (!peer)
        return;
    release_bvh(peer);
    for (int i = 0; i < peer->threads; i++)
        embree_worker_destroy(peer->workers[i]);
    rtcReleaseDevice(peer->device);
    pthread_mutex_destroy(&peer->memory.lock);
    free(peer);
}

bool embree_peer_build(embree_peer *peer, const bg_scene *scene, char *message, size_t message_size)
{
    if (!peer || !scene)
        return embree_fail(message, message_size, "embree peer: a NULL argument");
    const bg_scene_state *state = bgi_scene_committed(scene);
    if (!state)
        return embree_fail(message, message_size, "embree peer: the scene was never committed");
    return build_bvh(peer, state, message, message_size);
}

const char *embree_peer_describe(const embree_peer *peer, char *buffer, size_t size)
{
    if (peer->packet_width == 1)
        snprintf(buffer, size, "rtcIntersect1/rtcOccluded1 single rays, %d threads", peer->threads);
    else
        snprintf(buffer, size, "rtcIntersect%d/rtcOccluded%d packets, %d threads", peer->packet_width,
                 peer->packet_width, peer->threads);
    return buffer;
}

double embree_peer_build_ms(const embree_peer *peer)
{
    return peer ? peer->build_ms : 0.0;
}

double embree_peer_commit_ms(const embree_peer *peer)
{
    return peer ? peer->commit_ms : 0.0;
}

size_t embree_peer_bytes(embree_peer *peer)
{
    if (!peer)
        return 0;
    pthread_mutex_lock(&peer->memory.lock);
    long long live = peer->memory.live;
    pthread_mutex_unlock(&peer->memory.lock);
    return live > 0 ? (size_t)live : 0;
}

unsigned embree_peer_instanced_objects(const embree_peer *peer)
{
    return peer ? peer->instanced_objects : 0;
}

bool embree_peer_frame(void *job, bg_image *image)
{
    embree_peer_job *p = job;
    char message[512];
    bool ok = embree_peer_render(p->peer, &p->settings, image, message, sizeof message);
    if (!ok)
        fprintf(stderr, "%s\n", message);
    return ok;
}
