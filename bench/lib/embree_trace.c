/* The tracing side of the benchmark peer (embree_peer.h): the reference's Whitted model per hit,
 * run level by level over 8x8 tiles so that Embree gets full packets, on a pthread pool. */
#include "embree_internal.h" /* same directory: bench/lib objects are built without -Ibench */

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "betelgeuse/common/encoding.h"
#include "betelgeuse/common/image.h"

#define PEER_PI 3.14159265358979323846264338327950288
#define TILE 8 /* tile side in pixels: 64 camera rays, one wave */
#define WAVE_MAX EMBREE_WAVE_MAX

static bool is_thin(bg_shape shape)
{
    return shape == BG_SHAPE_PLANE || shape == BG_SHAPE_RECTANGLE;
}

/* ---- a render's state ----------------------------------------------------------------------------- */

/* What a hit's light loop needs. */
typedef struct peer_shade {
    bool lit; /* may receive direct light (docs/shading.md 7) */
    double opaque;
    bg_cpu_hit hit;
    bg_cpu_surface surface;
} peer_shade;

/* The buffers of one bounce level, reused for every wave of that level. */
typedef struct level_buffers {
    int count;
    peer_ray rays[WAVE_MAX];
    peer_hit hits[WAVE_MAX];
    peer_shade shade[WAVE_MAX];
    shadow_ray shadows[WAVE_MAX];
} level_buffers;

/* One render thread's state: its tile's radiance and one set of buffers per level reached. */
struct peer_worker {
    double rgb[TILE * TILE][3];
    level_buffers *levels[BG_MAX_DEPTH + 1];
    bool failed;
};

peer_worker *embree_worker_create(void)
{
    return calloc(1, sizeof(peer_worker));
}

void embree_worker_destroy(peer_worker *worker)
{
    if (!worker)
        return;
    for (int l = 0; l <= BG_MAX_DEPTH; l++)
        free(worker->levels[l]);
    free(worker);
}

/* A render's shared inputs. */
typedef struct render_job {
    embree_peer *peer;
    const bg_scene_state *state;
    const bg_render_settings *settings;
    const bg_image *image;
    size_t stride;
    int tiles_x, tiles_y;
    pthread_mutex_t lock;
    int next_tile;
} render_job;

/* ---- shading (docs/shading.md 7-9, the reference's helpers per hit) ------------------------- */

/* How far a ray leaving a mesh starts off the surface, in float ulps (2^-23) of the point's
 * magnitude: the reference's rule (docs/shading.md 2.10) in float units, since Embree rounds the
 * origin to float and tests the triangles in float, so the reference's 256 double ulps would vanish.
 * Measured against the reference (512x512, a terrain of 10^5 triangles 2e-3 units wide placed at
 * (1, 0, 1), pixels off by more than 8/255): 0 ulps 937 (neighbour triangles shadow the start),
 * 1 ulp 21, 4 ulps 51, 16 ulps 198, 256 ulps 2082 (the start moves far enough to shift shadows); at
 * unit scale 4 ulps give 0 and 0 ulps 1. 4 is the GPU's own measured need, 4x the peer's. */
#define LEAVE_FLOAT_ULPS 4.0
#define LEAVE_REFERENCE_ULPS 256.0 /* mesh_hit.c's MESH_OFFSET_ULPS, in which hit->offset comes */

/* Where a ray leaving hit in direction dir starts: the hit point for the analytic shapes; off a mesh,
 * LEAVE_FLOAT_ULPS of the point's magnitude along the geometric normal, to dir's side. */
static void leave_origin(const bg_cpu_hit *hit, const double dir[3], double origin[3])
{
    bg_cpu_hit h = *hit;
    h.offset *= LEAVE_FLOAT_ULPS / LEAVE_REFERENCE_ULPS * ((double)FLT_EPSILON / DBL_EPSILON);
    bgi_cpu_leave_origin(&h, dir, origin);
}

static void trace_wave(const render_job *job, peer_worker *w, int level);

/* The level's buffers, allocated the first time a tile reaches that level. */
static level_buffers *level_of(peer_worker *w, int level)
{
    if (!w->levels[level]) {
        w->levels[level] = malloc(sizeof *w->levels[level]);
        if (!w->levels[level]) {
            w->failed = true;
            return NULL;
        }
    }
    return w->levels[level];
}

/* Queues a secondary ray at level + 1, tracing that level's wave first when it is full. */
static void spawn(const render_job *job, peer_worker *w, int level, const peer_ray *ray)
{
    level_buffers *next = level_of(w, level + 1);
    if (!next)
        return;
    if (next->count == WAVE_MAX) {
        trace_wave(job, w, level + 1);
        next->count = 0;
    }
    next->rays[next->count++] = *ray;
}

/* Emission, ambient and background of one ray's hit (or miss), and what its light loop needs. */
static void shade_surface(const render_job *job, peer_worker *w, const peer_ray *ray, const peer_hit *h,
                          peer_shade *s)
{
    double *out = w->rgb[ray->pixel];
    s->lit = false;
    if (h->object == BG_CPU_NONE) {
        for (int i = 0; i < 3; i++)
            out[i] += ray->weight[i] * job->settings->background[i];
        return;
    }
    const bg_object_data *object = &job->state->objects[h->object];
    bgi_cpu_hit_attributes(object, h->object, ray->o, ray->d, &h->candidate, &s->hit);
    bgi_cpu_surface_eval(job->state, &job->state->materials[object->material], s->hit.uv, &s->surface);
    s->opaque = 1.0 - s->surface.transparency;
    for (int i = 0; i < 3; i++)
        out[i] += ray->weight[i] *
                  (s->surface.emission[i] + s->opaque * job->state->ambient[i] * s->surface.ambient[i]);
    const double view[3] = {-ray->d[0], -ray->d[1], -ray->d[2]};
    /* Direct light reaches a closed object's surface only from outside. */
    s->lit = s->opaque > 0.0 && bg_v3_dot(s->hit.normal, view) > 0.0 &&
             (is_thin(object->shape) || s->hit.entering);
}

/* The shadow segment towards one light of the lit hit of ray r; false when the light contributes
 * nothing even unblocked (no shadow test is made then). */
static bool light_segment(const bg_light *light, const peer_shade *s, int r, shadow_ray *out)
{
    if (!bgi_cpu_light_arrival(light, s->hit.position, out->l, &out->t_max, out->radiance))
        return false;
    out->vl = bg_v3_dot(s->hit.normal, out->l);
    if (!(out->vl > 0.0))
        return false; /* facing away from the light: none of it */
    leave_origin(&s->hit, out->l, out->o);
    out->self = s->hit.object;
    out->self_triangle = s->hit.triangle;
    out->ray = (uint32_t)r;
    return true;
}

/* What an unblocked light adds to the pixel of its ray: weight x opaque x pi x f x radiance x v'. */
static void add_light(peer_worker *w, const peer_ray *ray, const peer_shade *s, const shadow_ray *sh)
{
    const double view[3] = {-ray->d[0], -ray->d[1], -ray->d[2]};
    double f[3];
    bgi_cpu_brdf(&s->surface, s->hit.normal, s->hit.tangent, view, sh->l, f);
    for (int i = 0; i < 3; i++)
        w->rgb[ray->pixel][i] += ray->weight[i] * s->opaque * PEER_PI * f[i] * sh->radiance[i] * sh->vl;
}

/* Every light of the scene over the wave's lit hits, one batch of shadow segments per light. */
static void light_wave(const render_job *job, peer_worker *w, level_buffers *b)
{
    bool blocked[WAVE_MAX];
    for (uint32_t k = 0; k < job->state->light_count; k++) {
        int n = 0;
        for (int r = 0; r < b->count; r++)
            if (b->shade[r].lit && light_segment(&job->state->lights[k], &b->shade[r], r, &b->shadows[n]))
                n++;
        embree_trace_shadows(job->peer, b->shadows, blocked, n);
        for (int s = 0; s < n; s++) {
            const shadow_ray *sh = &b->shadows[s];
            if (!blocked[s])
                add_light(w, &b->rays[sh->ray], &b->shade[sh->ray], sh);
        }
    }
}

/* The mirror and dielectric rays of one hit (docs/shading.md 9), with the reference's root rules. */
static void secondary_rays(const render_job *job, peer_worker *w, int level, const peer_ray *ray,
                           const peer_shade *s)
{
    const bg_cpu_hit *hit = &s->hit;
    const double *n = hit->normal, *d = ray->d;
    const bool thin = is_thin(job->state->objects[hit->object].shape);
    const bool mesh = job->state->objects[hit->object].mesh != NULL;
    const double v = -bg_v3_dot(n, d);
    /* Interface: exact dielectric Fresnel for closed shapes; thin shapes pass light straight on. */
    double fresnel = 0.0, cos_t = 0.0, eta = 1.0;
    double cos_i = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0;
    if (s->surface.transparency > 0.0 && !thin) {
        double n1 = hit->entering ? 1.0 : s->surface.ior, n2 = hit->entering ? s->surface.ior : 1.0;
        fresnel = bgi_cpu_fresnel(cos_i, n1, n2, &cos_t);
        eta = n1 / n2;
    }
    double mirror[3];
    bgi_cpu_mirror_weight(&s->surface, cos_i, mirror);
    peer_ray refl, refr;
    for (int i = 0; i < 3; i++) {
        refl.weight[i] = ray->weight[i] * (s->opaque * mirror[i] + s->surface.transparency * fresnel);
        refr.weight[i] = ray->weight[i] * s->surface.transparency * (1.0 - fresnel);
    }
    refl.pixel = refr.pixel = ray->pixel;
    const double min_weight = job->settings->min_weight;
    /* A ray leaving a closed object's inside stays inside after reflection (far root); any other
     * secondary ray leaves the object it starts on and skips it. A mesh has no far root: a ray leaving
     * it skips its triangle only, from just off the surface (leave_origin). */
    const bool stays_inside = !thin && !hit->entering && !mesh;
    refl.skip_triangle = refr.skip_triangle = hit->triangle;
    if (bgi_cpu_worth_following(refl.weight, min_weight)) {
        double dn = bg_v3_dot(d, n);
        bg_v3_set(refl.d, d[0] - 2.0 * dn * n[0], d[1] - 2.0 * dn * n[1], d[2] - 2.0 * dn * n[2]);
        leave_origin(hit, refl.d, refl.o);
        refl.skip = stays_inside ? BG_CPU_NONE : hit->object;
        refl.inside = stays_inside ? hit->object : BG_CPU_NONE;
        if (bg_v3_normalize(refl.d))
            spawn(job, w, level, &refl);
    }
    if (bgi_cpu_worth_following(refr.weight, min_weight)) {
        bg_v3_set(refr.d, d[0], d[1], d[2]);
        if (!thin) {
            double k = eta * cos_i - cos_t;
            for (int i = 0; i < 3; i++)
                refr.d[i] = eta * d[i] + k * n[i];
        }
        leave_origin(hit, refr.d, refr.o);
        const bool enters = !thin && hit->entering && !mesh;
        refr.skip = enters ? BG_CPU_NONE : hit->object;
        refr.inside = enters ? hit->object : BG_CPU_NONE;
        if (bg_v3_normalize(refr.d))
            spawn(job, w, level, &refr);
    }
}

/* ---- tiles and waves -------------------------------------------------------------------------- */

/* Traces the rays queued at this level: hits, surface terms, lights, then the next level's rays
 * (in waves of at most WAVE_MAX, depth first across waves so memory stays one set per level). */
static void trace_wave(const render_job *job, peer_worker *w, int level)
{
    level_buffers *b = w->levels[level];
    embree_nearest_hits(job->peer, b->rays, b->hits, b->count, level == 0);
    for (int r = 0; r < b->count; r++)
        shade_surface(job, w, &b->rays[r], &b->hits[r], &b->shade[r]);
    light_wave(job, w, b);
    if (level >= job->settings->max_depth)
        return;
    level_buffers *next = level_of(w, level + 1);
    if (!next)
        return;
    next->count = 0;
    for (int r = 0; r < b->count; r++)
        if (b->hits[r].object != BG_CPU_NONE)
            secondary_rays(job, w, level, &b->rays[r], &b->shade[r]);
    if (next->count > 0)
        trace_wave(job, w, level + 1);
}

/* The camera rays of a tile in Morton order, so that every aligned group of 4, 16 or 64 rays (one
 * packet) covers a square patch of 2x2, 4x4 or 8x8 pixels. */
static void camera_rays(const render_job *job, level_buffers *b, int x0, int y0)
{
    const bg_image *img = job->image;
    b->count = 0;
    for (int j = 0; j < TILE * TILE; j++) {
        int lx = (j & 1) | ((j >> 1) & 2) | ((j >> 2) & 4);        /* the even bits of j */
        int ly = ((j >> 1) & 1) | ((j >> 2) & 2) | ((j >> 3) & 4); /* the odd bits */
        int x = x0 + lx, y = y0 + ly;
        if (x >= img->width || y >= img->height)
            continue;
        peer_ray *r = &b->rays[b->count++];
        bgi_cpu_primary_ray(&job->state->camera, img->width, img->height, x, y, r->o, r->d);
        bg_v3_set(r->weight, 1.0, 1.0, 1.0);
        r->pixel = (uint32_t)(ly * TILE + lx);
        r->skip = r->skip_triangle = r->inside = BG_CPU_NONE;
    }
}

static void write_tile(const render_job *job, const peer_worker *w, int x0, int y0)
{
    const bg_image *img = job->image;
    for (int ly = 0; ly < TILE && y0 + ly < img->height; ly++) {
        unsigned char *row = (unsigned char *)img->pixels + (size_t)(y0 + ly) * job->stride;
        for (int lx = 0; lx < TILE && x0 + lx < img->width; lx++) {
            const double *rgb = w->rgb[ly * TILE + lx];
            size_t x = (size_t)(x0 + lx);
            if (img->format == BG_PIXEL_RGBA32F) {
                float px[4] = {(float)rgb[0], (float)rgb[1], (float)rgb[2], 1.0f};
                memcpy(row + x * sizeof px, px, sizeof px);
            } else {
                for (int i = 0; i < 3; i++)
                    row[4 * x + (size_t)i] = bgi_encode_channel(rgb[i], job->settings->encoding);
                row[4 * x + 3] = 255;
            }
        }
    }
}

static void render_tile(const render_job *job, peer_worker *w, int tile)
{
    int x0 = tile % job->tiles_x * TILE, y0 = tile / job->tiles_x * TILE;
    memset(w->rgb, 0, sizeof w->rgb);
    level_buffers *b = level_of(w, 0);
    if (!b)
        return;
    camera_rays(job, b, x0, y0);
    trace_wave(job, w, 0);
    write_tile(job, w, x0, y0);
}

typedef struct worker_arg {
    render_job *job;
    peer_worker *worker;
} worker_arg;

/* Takes tiles from the shared counter until none is left (C99 has no atomics, hence the mutex). */
static void *render_worker(void *arg)
{
    worker_arg *a = arg;
    render_job *job = a->job;
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int tile = job->next_tile;
        if (tile < job->tiles_x * job->tiles_y)
            job->next_tile = tile + 1;
        pthread_mutex_unlock(&job->lock);
        if (tile >= job->tiles_x * job->tiles_y || a->worker->failed)
            break;
        render_tile(job, a->worker, tile);
    }
    return NULL;
}

/* ---- the public call ------------------------------------------------------------------------- */

bool embree_peer_render(embree_peer *peer, const bg_render_settings *settings, bg_image *image, char *message,
                        size_t message_size)
{
    if (!peer || !settings || !image)
        return embree_fail(message, message_size, "embree peer: a NULL argument");
    if (!peer->state)
        return embree_fail(message, message_size, "embree peer: no scene was built");
    if (peer->state->commit_count != peer->commit_count)
        return embree_fail(message, message_size, "embree peer: the scene was committed again since its build");
    char why[256];
    size_t stride = 0;
    if (bgi_render_settings_check(settings, "embree peer", why, sizeof why) != BG_OK)
        return embree_fail(message, message_size, "%s", why);
    if (bgi_image_check(image, &stride, why, sizeof why) != BG_OK)
        return embree_fail(message, message_size, "embree peer: %s", why);
    const bg_scene_state *state = peer->state;

    render_job job;
    job.peer = peer;
    job.state = state;
    job.settings = settings;
    job.image = image;
    job.stride = stride;
    job.tiles_x = (image->width + TILE - 1) / TILE;
    job.tiles_y = (image->height + TILE - 1) / TILE;
    job.next_tile = 0;
    if (pthread_mutex_init(&job.lock, NULL) != 0)
        return embree_fail(message, message_size, "embree peer: pthread_mutex_init failed");
    worker_arg args[EMBREE_MAX_THREADS];
    pthread_t pool[EMBREE_MAX_THREADS];
    int started = 0;
    /* The calling thread is worker 0; a thread that cannot start leaves its tiles to the others. */
    for (int i = 0; i < peer->threads; i++) {
        args[i].job = &job;
        args[i].worker = peer->workers[i];
        peer->workers[i]->failed = false;
    }
    for (int i = 1; i < peer->threads; i++) {
        if (pthread_create(&pool[started], NULL, render_worker, &args[i]) != 0)
            break;
        started++;
    }
    render_worker(&args[0]);
    for (int i = 0; i < started; i++)
        pthread_join(pool[i], NULL);
    pthread_mutex_destroy(&job.lock);
    for (int i = 0; i < peer->threads; i++)
        if (peer->workers[i]->failed)
            return embree_fail(message, message_size, "embree peer: out of memory for the ray buffers");
    return true;
}
