/* The acceleration structure (src/betelgeuse/common/bvh.h): on random scenes built through the
 * public API, the tree's nearest and any hits equal a brute-force loop over every object, exactly
 * (same object, same t, ties to the lower index); the layout and outward-rounding invariant on
 * every node; determinism; refit against rebuild; degenerate and bad input; out of memory. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/common/bvh.h"
#include "betelgeuse/cpu/cpu_internal.h"

#define NODE(bvh, i) ((bvh)->nodes + (size_t)(i) * BG_BVH_NODE_FLOATS)

/* ---- deterministic random numbers (splitmix64) ---- */

static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double rng_range(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(rng_next(s) >> 11) * 0x1p-53);
}

static uint32_t rng_below(uint64_t *s, uint32_t n)
{
    return (uint32_t)(rng_next(s) % n);
}

/* ---- the layout and rounding invariant, node by node ---- */

static bool float_gpu_safe(float f)
{
    return f == 0.0f || fabsf(f) >= FLT_MIN;
}

static bool contains(const float *outer, const float *inner)
{
    for (int a = 0; a < 3; a++)
        if (outer[BG_BVH_NODE_MIN + a] > inner[BG_BVH_NODE_MIN + a] ||
            outer[BG_BVH_NODE_MAX + a] < inner[BG_BVH_NODE_MAX + a])
            return false;
    return true;
}

static bool contains_double(const float *node, const bg_bvh_box *box)
{
    for (int a = 0; a < 3; a++)
        if ((double)node[BG_BVH_NODE_MIN + a] > box->min[a] || (double)node[BG_BVH_NODE_MAX + a] < box->max[a])
            return false;
    return true;
}

static uint32_t field(const bg_bvh *bvh, uint32_t node, int f)
{
    float v = NODE(bvh, node)[f];
    assert_true(v >= 0.0f && v == floorf(v));
    return (uint32_t)v;
}

/* Pre-order with miss links, one primitive per leaf (each exactly once), every box containing its
 * children and every leaf the double box of its primitive, floats a GPU reads as themselves, and
 * the reported depth. */
static void check_tree(const bg_bvh *bvh, const bg_bvh_box *boxes, uint32_t n)
{
    assert_int_equal(bvh->prim_count, n);
    if (n == 0) {
        assert_int_equal(bvh->node_count, 0);
        assert_int_equal(bvh->depth, 0);
        return;
    }
    assert_int_equal(bvh->node_count, 2 * n - 1);
    assert_int_equal(field(bvh, 0, BG_BVH_NODE_MISS), bvh->node_count);
    uint8_t *seen = calloc(n, 1);
    uint32_t *depth = calloc(bvh->node_count, sizeof *depth);
    assert_non_null(seen);
    assert_non_null(depth);
    depth[0] = 1;
    uint32_t max_depth = 0;
    for (uint32_t i = 0; i < bvh->node_count; i++) {
        const float *node = NODE(bvh, i);
        for (int a = 0; a < 3; a++) {
            assert_true(float_gpu_safe(node[BG_BVH_NODE_MIN + a]));
            assert_true(float_gpu_safe(node[BG_BVH_NODE_MAX + a]));
            assert_true(node[BG_BVH_NODE_MIN + a] <= node[BG_BVH_NODE_MAX + a]);
        }
        uint32_t miss = field(bvh, i, BG_BVH_NODE_MISS);
        if (node[BG_BVH_NODE_PRIM] >= 0.0f) {
            uint32_t prim = field(bvh, i, BG_BVH_NODE_PRIM);
            assert_true(prim < n);
            assert_false(seen[prim]);
            seen[prim] = 1;
            assert_int_equal(miss, i + 1);
            if (!contains_double(node, &boxes[prim]))
                fail_msg("leaf %u does not contain the double box of primitive %u", i, prim);
            if (depth[i] > max_depth)
                max_depth = depth[i];
            continue;
        }
        assert_true(node[BG_BVH_NODE_PRIM] == -1.0f);
        uint32_t first = i + 1, second = field(bvh, first, BG_BVH_NODE_MISS);
        assert_true(second > first && second < miss);
        assert_int_equal(field(bvh, second, BG_BVH_NODE_MISS), miss);
        if (!contains(node, NODE(bvh, first)) || !contains(node, NODE(bvh, second)))
            fail_msg("node %u does not contain its children %u and %u", i, first, second);
        depth[first] = depth[second] = depth[i] + 1;
    }
    for (uint32_t p = 0; p < n; p++)
        assert_true(seen[p]);
    assert_int_equal(bvh->depth, max_depth);
    free(seen);
    free(depth);
}

static bg_bvh build_ok(const bg_bvh_box *boxes, uint32_t n)
{
    bg_bvh bvh;
    assert_int_equal(bgi_bvh_build(NULL, boxes, n, &bvh), BG_OK);
    check_tree(&bvh, boxes, n);
    return bvh;
}

/* ---- random scenes through the public API ---- */

static bg_mat4 random_transform(uint64_t *rng, double extent, double size)
{
    bg_vec3 axis = bg_vec3_make(rng_range(rng, -1, 1), rng_range(rng, -1, 1), rng_range(rng, -1, 1) + 2.5);
    bg_mat4 t = bg_mat4_translate(rng_range(rng, -extent, extent), rng_range(rng, -extent, extent),
                                  rng_range(rng, -extent, extent));
    bg_mat4 r = bg_mat4_rotate(axis, rng_range(rng, 0, 360));
    bg_mat4 s = bg_mat4_scale(size * rng_range(rng, 0.2, 1.0), size * rng_range(rng, 0.2, 1.0),
                              size * rng_range(rng, 0.2, 1.0));
    return bg_mat4_mul(t, bg_mat4_mul(r, s));
}

typedef struct test_scene {
    bg_scene *scene;
    const bg_scene_state *state;
    uint32_t n;
    double extent;
    bg_bvh_box *boxes;
    uint32_t *object_of; /* primitive -> object (here the same: every object is bounded) */
} test_scene;

static void collect_boxes(test_scene *ts)
{
    ts->state = bgi_scene_committed(ts->scene);
    assert_non_null(ts->state);
    assert_int_equal(ts->state->object_count, ts->n);
    uint32_t k = 0;
    for (uint32_t j = 0; j < ts->n; j++) {
        const bg_object_data *o = &ts->state->objects[j];
        if (!o->bounded)
            continue;
        memcpy(ts->boxes[k].min, o->bounds_min, sizeof o->bounds_min);
        memcpy(ts->boxes[k].max, o->bounds_max, sizeof o->bounds_max);
        ts->object_of[k++] = j;
    }
    assert_int_equal(k, ts->n);
}

/* n objects of the four bounded shapes, randomly placed, turned and stretched; every seventh is a
 * copy of an earlier one, so exact ties (same t, two objects) are common. */
static test_scene random_scene(uint32_t n, uint64_t seed)
{
    static const bg_shape shapes[] = {BG_SHAPE_SPHERE, BG_SHAPE_BOX, BG_SHAPE_CYLINDER, BG_SHAPE_RECTANGLE};
    uint64_t rng = seed;
    test_scene ts = {NULL, NULL, n, 2.0 * cbrt((double)n) + 2.0, NULL, NULL};
    assert_int_equal(bg_scene_create(NULL, &ts.scene), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat, id;
    assert_int_equal(bg_scene_add_material(ts.scene, &m, &mat), BG_OK);
    bg_object_desc *descs = calloc(n, sizeof *descs);
    assert_non_null(descs);
    for (uint32_t j = 0; j < n; j++) {
        if (j % 7 == 6) {
            descs[j] = descs[rng_below(&rng, j)];
        } else {
            descs[j] = bg_object_desc_init(shapes[rng_below(&rng, 4)], mat);
            descs[j].transform = random_transform(&rng, ts.extent, 1.2);
        }
        assert_int_equal(bg_scene_add_object(ts.scene, &descs[j], &id), BG_OK);
    }
    free(descs);
    assert_int_equal(bg_scene_commit(ts.scene), BG_OK);
    ts.boxes = calloc(n, sizeof *ts.boxes);
    ts.object_of = calloc(n, sizeof *ts.object_of);
    assert_non_null(ts.boxes);
    assert_non_null(ts.object_of);
    collect_boxes(&ts);
    return ts;
}

static void free_scene(test_scene *ts)
{
    bg_scene_destroy(ts->scene);
    free(ts->boxes);
    free(ts->object_of);
}

/* Moves every object and re-commits: the same primitives with new boxes. */
static void move_objects(test_scene *ts, uint64_t seed)
{
    uint64_t rng = seed;
    for (uint32_t j = 0; j < ts->n; j++) {
        bg_mat4 m = random_transform(&rng, ts->extent, 1.2);
        assert_int_equal(bg_scene_set_transform(ts->scene, j + 1, &m), BG_OK);
    }
    assert_int_equal(bg_scene_commit(ts->scene), BG_OK);
    collect_boxes(ts);
}

/* Rays of every kind: at an object's centre, in a random direction, along axes (zero
 * components), from inside the scene or outside it. */
static void random_ray(const test_scene *ts, uint64_t *rng, double o[3], double d[3])
{
    double r = 1.5 * ts->extent;
    for (int a = 0; a < 3; a++)
        o[a] = rng_range(rng, -r, r);
    uint32_t kind = rng_below(rng, 6);
    if (kind <= 2) {
        const bg_object_data *target = &ts->state->objects[rng_below(rng, ts->n)];
        for (int a = 0; a < 3; a++)
            d[a] = target->to_world[a][3] + rng_range(rng, -0.3, 0.3) - o[a];
    } else if (kind == 3) {
        for (int a = 0; a < 3; a++)
            d[a] = rng_range(rng, -1, 1);
    } else {
        /* Along one axis (kind 4) or in an axis plane (kind 5), aimed near an object's centre. */
        const bg_object_data *target = &ts->state->objects[rng_below(rng, ts->n)];
        int keep = (int)rng_below(rng, 3);
        for (int a = 0; a < 3; a++) {
            bool moving = kind == 4 ? a == keep : a != keep;
            if (!moving)
                o[a] = target->to_world[a][3] + rng_range(rng, -0.3, 0.3);
            d[a] = moving ? target->to_world[a][3] - o[a] : 0.0;
        }
    }
    if (!bg_v3_normalize(d))
        bg_v3_set(d, 0.0, 0.0, 1.0);
}

typedef struct nearest {
    const test_scene *ts;
    const double *o, *d;
    uint32_t object;
    double t;
} nearest;

/* The brute-force rule of the CPU reference: every object in order, a strictly nearer hit wins,
 * so of equal distances the lower index stays. */
static void brute_nearest(const test_scene *ts, const double o[3], const double d[3], nearest *out)
{
    out->object = BG_CPU_NONE;
    out->t = DBL_MAX;
    for (uint32_t j = 0; j < ts->n; j++) {
        bg_cpu_candidate c;
        if (bgi_cpu_intersect_object(&ts->state->objects[j], o, d, false, out->t, &c) &&
            (out->object == BG_CPU_NONE || c.t < out->t)) {
            out->object = j;
            out->t = c.t;
        }
    }
}

/* The same rule in any order: compare distance, then index. */
static bool visit_nearest(void *user, uint32_t prim, double *t_max)
{
    nearest *n = user;
    uint32_t j = n->ts->object_of[prim];
    bg_cpu_candidate c;
    if (bgi_cpu_intersect_object(&n->ts->state->objects[j], n->o, n->d, false, *t_max, &c) &&
        (n->object == BG_CPU_NONE || c.t < n->t || (c.t == n->t && j < n->object))) {
        n->object = j;
        n->t = c.t;
        *t_max = c.t;
    }
    return true;
}

static bg_bvh_walk bvh_nearest(const bg_bvh *bvh, const test_scene *ts, const double o[3], const double d[3],
                               nearest *out)
{
    out->ts = ts;
    out->o = o;
    out->d = d;
    out->object = BG_CPU_NONE;
    out->t = DBL_MAX;
    double t_max = DBL_MAX;
    bg_bvh_walk walk;
    assert_int_equal(bgi_bvh_traverse(bvh, o, d, 0.0, &t_max, visit_nearest, out, &walk), BG_OK);
    assert_false(walk.stopped);
    assert_true(walk.nodes_visited <= bvh->node_count);
    return walk;
}

static void same_nearest(const nearest *got, const nearest *want, uint32_t ray)
{
    if (got->object != want->object || got->t != want->t)
        fail_msg("ray %u: tree gives object %u at t %.17g, brute force object %u at t %.17g", ray, got->object,
                 got->t, want->object, want->t);
}

typedef struct any_hit {
    const test_scene *ts;
    const double *p, *l;
    uint32_t skip;
    bool blocked;
} any_hit;

static bool visit_blocked(void *user, uint32_t prim, double *t_max)
{
    any_hit *s = user;
    uint32_t j = s->ts->object_of[prim];
    if (j == s->skip || !bgi_cpu_segment_blocked(&s->ts->state->objects[j], s->p, s->l, *t_max))
        return true;
    s->blocked = true;
    return false;
}

static bool brute_blocked(const test_scene *ts, const double p[3], const double l[3], uint32_t skip)
{
    for (uint32_t j = 0; j < ts->n; j++)
        if (j != skip && bgi_cpu_segment_blocked(&ts->state->objects[j], p, l, 1.0))
            return true;
    return false;
}

/* ---- tests on random scenes ---- */

static const uint32_t SCENE_SIZES[] = {1, 2, 3, 17, 100, 1000, 5000};

/* Brute force costs objects x rays: fewer rays for the big scenes keep the suite fast. */
static uint32_t rays_for(uint32_t n)
{
    return n >= 5000 ? 500 : n >= 1000 ? 1000 : 2000;
}

static void test_nearest_hit_matches_brute_force(void **state)
{
    (void)state;
    for (size_t s = 0; s < sizeof SCENE_SIZES / sizeof SCENE_SIZES[0]; s++) {
        uint32_t n = SCENE_SIZES[s], hits = 0, ties = 0;
        test_scene ts = random_scene(n, 1000 + n);
        bg_bvh bvh = build_ok(ts.boxes, n);
        uint64_t rng = 77 + n;
        uint64_t visited = 0;
        for (uint32_t k = 0; k < rays_for(n); k++) {
            double o[3], d[3];
            random_ray(&ts, &rng, o, d);
            nearest want, got;
            brute_nearest(&ts, o, d, &want);
            visited += bvh_nearest(&bvh, &ts, o, d, &got).nodes_visited;
            same_nearest(&got, &want, k);
            hits += want.object != BG_CPU_NONE;
            /* A tie: another object at exactly the winner's distance. */
            for (uint32_t j = 0; want.object != BG_CPU_NONE && j < n; j++) {
                bg_cpu_candidate c;
                if (j != want.object && bgi_cpu_intersect_object(&ts.state->objects[j], o, d, false, want.t, &c) &&
                    c.t == want.t) {
                    ties++;
                    break;
                }
            }
        }
        /* The rays must exercise the test: most hit something, and the copies make ties. */
        assert_true(hits > rays_for(n) / 3);
        if (n >= 100)
            assert_true(ties > 0);
        /* A tree that visits nearly everything would pass the equality above and be useless. */
        if (n >= 1000)
            assert_true((double)visited / rays_for(n) < 0.05 * bvh.node_count);
        bgi_bvh_destroy(&bvh);
        free_scene(&ts);
    }
}

static void test_any_hit_matches_brute_force(void **state)
{
    (void)state;
    for (size_t s = 0; s < sizeof SCENE_SIZES / sizeof SCENE_SIZES[0]; s++) {
        uint32_t n = SCENE_SIZES[s], blocked = 0, stopped = 0;
        test_scene ts = random_scene(n, 2000 + n);
        bg_bvh bvh = build_ok(ts.boxes, n);
        uint64_t rng = 99 + n;
        for (uint32_t k = 0; k < rays_for(n); k++) {
            /* A segment from a point on an object (or anywhere) towards a light-like point. */
            double p[3], dir[3], l[3];
            random_ray(&ts, &rng, p, dir);
            nearest first;
            brute_nearest(&ts, p, dir, &first);
            uint32_t skip = BG_CPU_NONE;
            if (first.object != BG_CPU_NONE && rng_below(&rng, 2)) {
                skip = first.object; /* a shadow ray leaves the surface it starts on */
                for (int a = 0; a < 3; a++)
                    p[a] += first.t * dir[a];
            }
            double r = 1.5 * ts.extent;
            for (int a = 0; a < 3; a++)
                l[a] = rng_range(&rng, -r, r) - p[a];
            any_hit hit = {&ts, p, l, skip, false};
            double t_max = 1.0;
            bg_bvh_walk walk;
            assert_int_equal(bgi_bvh_traverse(&bvh, p, l, 0.0, &t_max, visit_blocked, &hit, &walk), BG_OK);
            bool want = brute_blocked(&ts, p, l, skip);
            if (hit.blocked != want)
                fail_msg("segment %u: tree says %s, brute force %s", k, hit.blocked ? "blocked" : "open",
                         want ? "blocked" : "open");
            assert_true(walk.stopped == hit.blocked);
            blocked += want;
            stopped += walk.stopped;
        }
        /* Both outcomes occur on the busy scenes. */
        if (n >= 100) {
            assert_true(blocked > 0);
            assert_true(blocked < rays_for(n));
        }
        assert_int_equal(stopped, blocked);
        bgi_bvh_destroy(&bvh);
        free_scene(&ts);
    }
}

static void test_build_is_deterministic(void **state)
{
    (void)state;
    test_scene ts = random_scene(1000, 3000);
    bg_bvh_box *copy = malloc(ts.n * sizeof *copy);
    assert_non_null(copy);
    memcpy(copy, ts.boxes, ts.n * sizeof *copy);
    bg_bvh a = build_ok(ts.boxes, ts.n), b = build_ok(copy, ts.n);
    assert_int_equal(a.node_count, b.node_count);
    assert_int_equal(a.depth, b.depth);
    assert_memory_equal(a.nodes, b.nodes, (size_t)a.node_count * BG_BVH_NODE_FLOATS * sizeof(float));
    bgi_bvh_destroy(&a);
    bgi_bvh_destroy(&b);
    free(copy);
    free_scene(&ts);
}

static void test_refit_matches_rebuild(void **state)
{
    (void)state;
    test_scene ts = random_scene(1000, 4000);
    bg_bvh refit = build_ok(ts.boxes, ts.n);
    bg_bvh_stats before, after, rebuilt_stats;
    bgi_bvh_get_stats(&refit, &before);

    /* Refitting to the build's own boxes gives back the built floats bit for bit. */
    size_t bytes = (size_t)refit.node_count * BG_BVH_NODE_FLOATS * sizeof(float);
    float *built = malloc(bytes);
    assert_non_null(built);
    memcpy(built, refit.nodes, bytes);
    assert_int_equal(bgi_bvh_refit(&refit, ts.boxes, ts.n), BG_OK);
    assert_memory_equal(refit.nodes, built, bytes);

    move_objects(&ts, 4001);
    assert_int_equal(bgi_bvh_refit(&refit, ts.boxes, ts.n), BG_OK);
    check_tree(&refit, ts.boxes, ts.n);
    assert_int_equal(refit.depth, before.depth); /* same topology */
    bg_bvh rebuilt = build_ok(ts.boxes, ts.n);
    bgi_bvh_get_stats(&refit, &after);
    bgi_bvh_get_stats(&rebuilt, &rebuilt_stats);
    /* Scattering every object makes the old topology much worse than a fresh tree. */
    assert_true(after.sah_cost > rebuilt_stats.sah_cost);

    uint64_t rng = 4002;
    for (uint32_t k = 0; k < 400; k++) {
        double o[3], d[3];
        random_ray(&ts, &rng, o, d);
        nearest a, b, want;
        bvh_nearest(&refit, &ts, o, d, &a);
        bvh_nearest(&rebuilt, &ts, o, d, &b);
        brute_nearest(&ts, o, d, &want);
        same_nearest(&a, &b, k);
        same_nearest(&b, &want, k);
    }
    free(built);
    bgi_bvh_destroy(&refit);
    bgi_bvh_destroy(&rebuilt);
    free_scene(&ts);
}

/* ---- synthetic boxes: the primitive is its own double box ---- */

/* The entry t of the ray into a double box within (t_min, t_max], by exact-rule slabs in double;
 * false when it misses. The reference the conservative float walk must agree with. */
static bool box_hit(const bg_bvh_box *b, const double o[3], const double d[3], double t_max, double *t)
{
    double enter = 0.0, exit = t_max;
    for (int a = 0; a < 3; a++) {
        if (d[a] == 0.0) {
            if (o[a] < b->min[a] || o[a] > b->max[a])
                return false;
            continue;
        }
        double t0 = (b->min[a] - o[a]) / d[a], t1 = (b->max[a] - o[a]) / d[a];
        if (t0 > t1) {
            double s = t0;
            t0 = t1;
            t1 = s;
        }
        enter = t0 > enter ? t0 : enter;
        exit = t1 < exit ? t1 : exit;
    }
    if (enter > exit)
        return false;
    *t = enter;
    return true;
}

typedef struct box_nearest {
    const bg_bvh_box *boxes;
    const double *o, *d;
    uint32_t prim, visits;
    double t;
} box_nearest;

static bool visit_box(void *user, uint32_t prim, double *t_max)
{
    box_nearest *n = user;
    double t;
    n->visits++;
    if (box_hit(&n->boxes[prim], n->o, n->d, *t_max, &t) &&
        (n->prim == BG_CPU_NONE || t < n->t || (t == n->t && prim < n->prim))) {
        n->prim = prim;
        n->t = t;
        *t_max = t;
    }
    return true;
}

static void boxes_agree(const bg_bvh *bvh, const bg_bvh_box *boxes, uint32_t n, const double o[3], const double d[3])
{
    box_nearest want = {boxes, o, d, BG_CPU_NONE, 0, 0.0}, got = want;
    double t;
    for (uint32_t p = 0; p < n; p++)
        if (box_hit(&boxes[p], o, d, want.prim == BG_CPU_NONE ? DBL_MAX : want.t, &t) &&
            (want.prim == BG_CPU_NONE || t < want.t)) {
            want.prim = p;
            want.t = t;
        }
    double t_max = DBL_MAX;
    assert_int_equal(bgi_bvh_traverse(bvh, o, d, 0.0, &t_max, visit_box, &got, NULL), BG_OK);
    if (got.prim != want.prim || got.t != want.t)
        fail_msg("tree gives box %u at %.17g, brute force box %u at %.17g", got.prim, got.t, want.prim, want.t);
}

static bg_bvh_box make_box(double x0, double y0, double z0, double x1, double y1, double z1)
{
    bg_bvh_box b = {{x0, y0, z0}, {x1, y1, z1}};
    return b;
}

static void test_single_primitive(void **state)
{
    (void)state;
    bg_bvh_box box = make_box(-1, -1, -1, 1, 1, 1);
    bg_bvh bvh = build_ok(&box, 1);
    assert_int_equal(bvh.node_count, 1);
    assert_int_equal(bvh.depth, 1);
    assert_true(bvh.nodes[BG_BVH_NODE_PRIM] == 0.0f);
    assert_true(bvh.nodes[BG_BVH_NODE_MISS] == 1.0f);
    const double o[3] = {0, 0, -5}, d[3] = {0, 0, 1}, away[3] = {0, 1, 0};
    boxes_agree(&bvh, &box, 1, o, d);
    box_nearest got = {&box, o, away, BG_CPU_NONE, 0, 0.0};
    double t_max = DBL_MAX;
    bg_bvh_walk walk;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, away, 0.0, &t_max, visit_box, &got, &walk), BG_OK);
    assert_int_equal(walk.nodes_visited, 1);
    assert_int_equal(walk.prims_visited, 0);
    bgi_bvh_destroy(&bvh);
    assert_null(bvh.nodes);
    assert_int_equal(bvh.node_count, 0);
}

/* Equal centroids cannot be binned: the split is the index median, and ties go to index 0. */
static void test_equal_centroids(void **state)
{
    (void)state;
    bg_bvh_box boxes[100];
    for (int i = 0; i < 100; i++)
        boxes[i] = make_box(1, 2, 3, 4, 5, 6);
    bg_bvh bvh = build_ok(boxes, 100);
    assert_int_equal(bvh.depth, 8); /* 100, 50, 25, 13, 7, 4, 2, 1 */
    const double o[3] = {2, 3, -10}, d[3] = {0, 0, 1};
    box_nearest got = {boxes, o, d, BG_CPU_NONE, 0, 0.0};
    double t_max = DBL_MAX;
    bg_bvh_walk walk;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, visit_box, &got, &walk), BG_OK);
    assert_int_equal(got.prim, 0);
    assert_true(got.t == 13.0);
    /* Inclusive entry: every copy at the same distance is still offered to the callee. */
    assert_int_equal(got.visits, 100);
    assert_int_equal(walk.nodes_visited, bvh.node_count);
    bgi_bvh_destroy(&bvh);
}

/* Point boxes on a grid, hit by axis-aligned rays through them exactly (two zero components). */
static void test_zero_size_boxes(void **state)
{
    (void)state;
    bg_bvh_box boxes[64];
    for (int i = 0; i < 64; i++) {
        double x = i % 4 * 0.1, y = i / 4 % 4 * 0.1, z = i / 16 * 0.1;
        boxes[i] = make_box(x, y, z, x, y, z);
    }
    bg_bvh bvh = build_ok(boxes, 64);
    for (int i = 0; i < 64; i++) {
        const double o[3] = {boxes[i].min[0], boxes[i].min[1], -1.0}, d[3] = {0, 0, 1};
        box_nearest got = {boxes, o, d, BG_CPU_NONE, 0, 0.0};
        double t_max = DBL_MAX;
        assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, visit_box, &got, NULL), BG_OK);
        assert_int_equal(got.prim, i % 16); /* the nearest of the column: z = 0 */
        boxes_agree(&bvh, boxes, 64, o, d);
    }
    bgi_bvh_destroy(&bvh);
}

/* Coordinates near 1e30, tiny boxes among huge ones, and boxes at powers of two (the most lopsided
 * SAH splits); rays of every kind against brute force. */
static void test_extreme_coordinates(void **state)
{
    (void)state;
    enum { N = 600 };
    bg_bvh_box boxes[N];
    uint64_t rng = 5;
    for (int i = 0; i < N; i++) {
        double c[3], h;
        if (i % 3 == 0) {
            for (int a = 0; a < 3; a++)
                c[a] = rng_range(&rng, -1e30, 1e30);
            h = rng_range(&rng, 0, 1e29);
        } else if (i % 3 == 1) {
            for (int a = 0; a < 3; a++)
                c[a] = rng_range(&rng, -1, 1);
            h = rng_range(&rng, 0, 1e-3);
        } else {
            for (int a = 0; a < 3; a++)
                c[a] = ldexp(1.0, i / 3 - 100) * (a == 0 ? 1 : 0.5);
            h = ldexp(1.0, i / 3 - 104);
        }
        boxes[i] = make_box(c[0] - h, c[1] - h, c[2] - h, c[0] + h, c[1] + h, c[2] + h);
    }
    bg_bvh bvh = build_ok(boxes, N);
    for (int k = 0; k < 300; k++) {
        const bg_bvh_box *target = &boxes[rng_below(&rng, N)];
        double o[3], d[3];
        double scale = k % 2 ? 1e30 : 2.0;
        for (int a = 0; a < 3; a++) {
            o[a] = rng_range(&rng, -scale, scale);
            d[a] = 0.5 * (target->min[a] + target->max[a]) - o[a];
        }
        if (k % 5 == 0)
            d[k % 3] = 0.0;
        if (k % 7 == 0)
            d[(k + 1) % 3] = 1e-300; /* a tiny component: saturated slab distances */
        boxes_agree(&bvh, boxes, N, o, d);
    }
    bgi_bvh_destroy(&bvh);
}

/* Outward rounding exactly: the nearest float outside when the double is not a float, the float
 * itself when it is, and no subnormal (GPUs may flush them to zero). */
static void test_outward_rounding(void **state)
{
    (void)state;
    bg_bvh_box boxes[3] = {make_box(0.1, -0.1, 0.5, 0.1, 0.3, 0.75), make_box(1e30, -1e30, 1e-320, 1e30, 1e30, 1e-320),
                           make_box(-1e-40, 1e-40, -FLT_MAX, -1e-300, 1e-39, FLT_MAX)};
    bg_bvh bvh = build_ok(boxes, 3);
    for (uint32_t i = 0; i < bvh.node_count; i++) {
        const float *node = NODE(&bvh, i);
        if (node[BG_BVH_NODE_PRIM] < 0.0f)
            continue;
        const bg_bvh_box *b = &boxes[(int)node[BG_BVH_NODE_PRIM]];
        for (int a = 0; a < 3; a++) {
            float lo = node[BG_BVH_NODE_MIN + a], hi = node[BG_BVH_NODE_MAX + a];
            assert_true((double)lo <= b->min[a] && (double)hi >= b->max[a]);
            /* Tight: the next GPU-safe float inwards would cut the double box. */
            float lo_in = lo == -FLT_MIN ? 0.0f : lo == 0.0f ? FLT_MIN : nextafterf(lo, FLT_MAX);
            float hi_in = hi == FLT_MIN ? 0.0f : hi == 0.0f ? -FLT_MIN : nextafterf(hi, -FLT_MAX);
            assert_true((double)lo_in > b->min[a]);
            assert_true((double)hi_in < b->max[a]);
        }
    }
    const float *leaf0 = NULL;
    for (uint32_t i = 0; i < bvh.node_count; i++)
        if (NODE(&bvh, i)[BG_BVH_NODE_PRIM] == 0.0f)
            leaf0 = NODE(&bvh, i);
    assert_non_null(leaf0);
    assert_true(leaf0[BG_BVH_NODE_MIN + 0] < 0.1f && leaf0[BG_BVH_NODE_MAX + 0] == 0.1f); /* (float)0.1 > 0.1 */
    assert_true(leaf0[BG_BVH_NODE_MIN + 2] == 0.5f && leaf0[BG_BVH_NODE_MAX + 2] == 0.75f); /* exact */
    bgi_bvh_destroy(&bvh);
}

/* ---- bad input, empty trees, corrupt arrays ---- */

static void assert_empty(const bg_bvh *bvh)
{
    assert_null(bvh->nodes);
    assert_int_equal(bvh->node_count, 0);
    assert_int_equal(bvh->prim_count, 0);
}

static void test_bad_boxes(void **state)
{
    (void)state;
    bg_bvh_box boxes[4] = {make_box(0, 0, 0, 1, 1, 1), make_box(0, 0, 0, 1, 1, 1), make_box(0, 0, 0, 1, 1, 1),
                           make_box(0, 0, 0, 1, 1, 1)};
    bg_bvh bvh;
    uint32_t bad = 99;
    boxes[2].min[1] = NAN;
    assert_int_equal(bgi_bvh_build(NULL, boxes, 4, &bvh), BG_ERR_INVALID_ARGUMENT);
    assert_empty(&bvh);
    assert_int_equal(bgi_bvh_check_boxes(boxes, 4, &bad), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bad, 2);
    boxes[2].min[1] = 0.0;
    boxes[1].max[2] = INFINITY;
    assert_int_equal(bgi_bvh_build(NULL, boxes, 4, &bvh), BG_ERR_INVALID_ARGUMENT);
    boxes[1].max[2] = 1.0;
    boxes[3].min[0] = 2.0; /* min > max */
    assert_int_equal(bgi_bvh_check_boxes(boxes, 4, &bad), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bad, 3);
    assert_int_equal(bgi_bvh_build(NULL, boxes, 4, &bvh), BG_ERR_INVALID_ARGUMENT);
    assert_empty(&bvh);
    boxes[3].min[0] = 0.0;
    boxes[0].max[0] = 1e39; /* no float box holds it */
    assert_int_equal(bgi_bvh_build(NULL, boxes, 4, &bvh), BG_ERR_LIMIT);
    assert_empty(&bvh);
    boxes[0].max[0] = 1.0;
    assert_int_equal(bgi_bvh_build(NULL, NULL, 4, &bvh), BG_ERR_INVALID_ARGUMENT);
    /* Too many primitives: refused before any box is read. */
    assert_int_equal(bgi_bvh_build(NULL, boxes, BG_BVH_MAX_PRIMS + 1, &bvh), BG_ERR_LIMIT);
    assert_empty(&bvh);
    assert_int_equal(bgi_bvh_build(NULL, boxes, 4, NULL), BG_ERR_INVALID_ARGUMENT);
}

static bool count_visit(void *user, uint32_t prim, double *t_max)
{
    (void)prim;
    (void)t_max;
    (*(uint32_t *)user)++;
    return true;
}

static void test_empty_tree(void **state)
{
    (void)state;
    bg_bvh bvh;
    assert_int_equal(bgi_bvh_build(NULL, NULL, 0, &bvh), BG_OK);
    check_tree(&bvh, NULL, 0);
    assert_empty(&bvh);
    const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
    double t_max = DBL_MAX;
    uint32_t calls = 0;
    bg_bvh_walk walk;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, &walk), BG_OK);
    assert_int_equal(calls, 0);
    assert_int_equal(walk.nodes_visited, 0);
    assert_true(t_max == DBL_MAX);
    assert_int_equal(bgi_bvh_refit(&bvh, NULL, 0), BG_OK);
    bg_bvh_stats stats;
    bgi_bvh_get_stats(&bvh, &stats);
    assert_int_equal(stats.node_count, 0);
    assert_int_equal(stats.depth, 0);
    bgi_bvh_destroy(&bvh);
    bgi_bvh_destroy(NULL);
    /* A zeroed struct is the same empty tree. */
    bg_bvh zero;
    memset(&zero, 0, sizeof zero);
    assert_int_equal(bgi_bvh_traverse(&zero, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_OK);
    bgi_bvh_destroy(&zero);
}

/* Eight unit-high boxes along x, half a unit long and half a unit apart: the ray (-1, 0.5, 0.5) +
 * t (1, 0, 0) meets every one, the first at t = 1. */
static void boxes_in_a_row(bg_bvh_box boxes[8])
{
    for (int i = 0; i < 8; i++)
        boxes[i] = make_box(i, 0, 0, i + 0.5, 1, 1);
}

static void test_bad_rays_and_refits(void **state)
{
    (void)state;
    bg_bvh_box boxes[8];
    boxes_in_a_row(boxes);
    bg_bvh bvh = build_ok(boxes, 8);
    const double o[3] = {-1, 0.5, 0.5}, d[3] = {1, 0, 0}, nan_o[3] = {NAN, 0, 0}, inf_d[3] = {INFINITY, 0, 0};
    double t_max = DBL_MAX;
    uint32_t calls = 0;
    assert_int_equal(bgi_bvh_traverse(&bvh, nan_o, d, 0.0, &t_max, count_visit, &calls, NULL),
                     BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bgi_bvh_traverse(&bvh, o, inf_d, 0.0, &t_max, count_visit, &calls, NULL),
                     BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, NAN, &t_max, count_visit, &calls, NULL), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, NULL, &calls, NULL), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(calls, 0);
    /* A t range that ends before the first box: no visit. */
    t_max = 0.5;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_OK);
    assert_int_equal(calls, 0);
    /* Inclusive at t_max: the first box starts exactly at t = 1. */
    t_max = 1.0;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_OK);
    assert_int_equal(calls, 1);

    /* A refit that fails leaves the tree as it was. */
    size_t bytes = (size_t)bvh.node_count * BG_BVH_NODE_FLOATS * sizeof(float);
    float *before = malloc(bytes);
    assert_non_null(before);
    memcpy(before, bvh.nodes, bytes);
    bg_bvh_box moved[8];
    memcpy(moved, boxes, sizeof moved);
    for (int i = 0; i < 8; i++)
        moved[i].max[1] = 2.0;
    moved[7].min[2] = NAN;
    assert_int_equal(bgi_bvh_refit(&bvh, moved, 8), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bgi_bvh_refit(&bvh, boxes, 7), BG_ERR_INVALID_ARGUMENT);
    assert_memory_equal(bvh.nodes, before, bytes);
    free(before);
    bgi_bvh_destroy(&bvh);
}

/* A corrupt array cannot make the walk loop forever or read outside it: each is an error. */
static void test_corrupt_nodes(void **state)
{
    (void)state;
    bg_bvh_box boxes[8];
    boxes_in_a_row(boxes);
    bg_bvh bvh = build_ok(boxes, 8);
    const double o[3] = {-1, 0.5, 0.5}, d[3] = {1, 0, 0};
    uint32_t last = bvh.node_count - 1, calls = 0;
    double t_max = DBL_MAX;
    float *miss = &NODE(&bvh, last)[BG_BVH_NODE_MISS], *prim = &NODE(&bvh, last)[BG_BVH_NODE_PRIM];
    float keep_miss = *miss, keep_prim = *prim;
    bg_bvh_walk walk;

    *miss = 0.0f; /* back to the root: a cycle for the threaded walk, which deep trees take */
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, &walk), BG_ERR_INVALID_ARGUMENT);
    uint32_t depth = bvh.depth;
    bvh.depth = 200;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, &walk), BG_ERR_LIMIT);
    assert_int_equal(walk.nodes_visited, 2 * bvh.node_count);
    bvh.depth = depth;
    *miss = (float)(bvh.node_count + 1);
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_ERR_INVALID_ARGUMENT);
    *miss = NAN;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_ERR_INVALID_ARGUMENT);
    *miss = keep_miss;
    *prim = 8.0f;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_ERR_INVALID_ARGUMENT);
    *prim = 2.5f;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, NULL), BG_ERR_INVALID_ARGUMENT);
    *prim = keep_prim;
    calls = 0;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, count_visit, &calls, &walk), BG_OK);
    assert_int_equal(calls, 8);
    assert_int_equal(walk.nodes_visited, bvh.node_count);
    bgi_bvh_destroy(&bvh);
}

/* An any-hit callee ends the walk at once. */
static bool stop_at_first(void *user, uint32_t prim, double *t_max)
{
    (void)t_max;
    *(uint32_t *)user = prim;
    return false;
}

static void test_stop_early(void **state)
{
    (void)state;
    bg_bvh_box boxes[8];
    boxes_in_a_row(boxes);
    bg_bvh bvh = build_ok(boxes, 8);
    const double o[3] = {-1, 0.5, 0.5}, d[3] = {1, 0, 0};
    double t_max = DBL_MAX;
    uint32_t first = 99;
    bg_bvh_walk walk;
    assert_int_equal(bgi_bvh_traverse(&bvh, o, d, 0.0, &t_max, stop_at_first, &first, &walk), BG_OK);
    assert_true(walk.stopped);
    assert_int_equal(walk.prims_visited, 1);
    assert_true(first < 8);
    assert_true(walk.nodes_visited < bvh.node_count);
    /* A ray that misses the root box ends after that one box. */
    const double up[3] = {0, 1, 0};
    assert_int_equal(bgi_bvh_traverse(&bvh, o, up, 0.0, &t_max, stop_at_first, &first, &walk), BG_OK);
    assert_int_equal(walk.nodes_visited, 1);
    assert_int_equal(walk.prims_visited, 0);
    bgi_bvh_destroy(&bvh);
}

/* The copy for a viewpoint: the same tree shifted (a valid tree over the shifted double boxes),
 * each interior node's nearer child first, leaves renamed through the id list. */
static double distance2(const float *node, const double p[3])
{
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double lo = node[BG_BVH_NODE_MIN + a], hi = node[BG_BVH_NODE_MAX + a];
        double d = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0.0);
        d2 += d * d;
    }
    return d2;
}

static void test_view_nodes(void **state)
{
    (void)state;
    const double eye[3] = {3.25, -2.5, 7.0}, zero[3] = {0.0, 0.0, 0.0};
    for (size_t s = 0; s < sizeof SCENE_SIZES / sizeof SCENE_SIZES[0]; s++) {
        uint32_t n = SCENE_SIZES[s];
        test_scene ts = random_scene(n, 500 + n);
        bg_bvh bvh = build_ok(ts.boxes, n);
        float *out = malloc((size_t)bvh.node_count * BG_BVH_NODE_FLOATS * sizeof(float));
        bg_bvh_box *shifted = malloc(n * sizeof *shifted);
        assert_non_null(out);
        assert_non_null(shifted);
        for (uint32_t i = 0; i < n; i++)
            for (int a = 0; a < 3; a++) {
                shifted[i].min[a] = ts.boxes[i].min[a] - eye[a];
                shifted[i].max[a] = ts.boxes[i].max[a] - eye[a];
            }
        assert_int_equal(bgi_bvh_view_nodes(&bvh, eye, NULL, out), BG_OK);
        bg_bvh view = bvh;
        view.nodes = out;
        check_tree(&view, shifted, n);
        uint32_t swapped = 0;
        for (uint32_t i = 0; i < view.node_count; i++) {
            if (NODE(&view, i)[BG_BVH_NODE_PRIM] >= 0.0f)
                continue;
            uint32_t first = i + 1, second = field(&view, first, BG_BVH_NODE_MISS);
            if (distance2(NODE(&view, second), zero) < distance2(NODE(&view, first), zero))
                fail_msg("%u objects: node %u has its farther child first", n, i);
            swapped += field(&view, first, BG_BVH_NODE_MISS) - first != field(&bvh, i + 1, BG_BVH_NODE_MISS) - (i + 1);
        }
        /* The ids: leaf k of the view names ids[prim]. */
        uint32_t *ids = malloc(n * sizeof *ids);
        assert_non_null(ids);
        for (uint32_t p = 0; p < n; p++)
            ids[p] = 7 * p + 3;
        float *renamed = malloc((size_t)bvh.node_count * BG_BVH_NODE_FLOATS * sizeof(float));
        assert_non_null(renamed);
        assert_int_equal(bgi_bvh_view_nodes(&bvh, eye, ids, renamed), BG_OK);
        for (uint32_t i = 0; i < view.node_count; i++) {
            float p = out[(size_t)i * BG_BVH_NODE_FLOATS + BG_BVH_NODE_PRIM];
            float q = renamed[(size_t)i * BG_BVH_NODE_FLOATS + BG_BVH_NODE_PRIM];
            assert_true(p < 0.0f ? q == p : q == (float)ids[(uint32_t)p]);
        }
        /* Reordering happened: some node's first child now spans another count of nodes. */
        if (n >= 100)
            assert_true(swapped > 0);
        /* The order alone (what the mesh textures lay out unshifted): a permutation that puts each
         * view node's old node there, root first, the miss links following from the old spans. */
        uint32_t *order = malloc((size_t)bvh.node_count * sizeof *order);
        unsigned char *seen = calloc(bvh.node_count, 1);
        assert_non_null(order);
        assert_non_null(seen);
        assert_int_equal(bgi_bvh_view_order(&bvh, eye, order), BG_OK);
        assert_int_equal(order[0], 0);
        for (uint32_t at = 0; at < bvh.node_count; at++) {
            uint32_t old = order[at];
            assert_true(old < bvh.node_count);
            if (seen[old]++)
                fail_msg("%u objects: node %u placed twice", n, old);
            assert_true(NODE(&bvh, old)[BG_BVH_NODE_PRIM] == out[(size_t)at * BG_BVH_NODE_FLOATS + BG_BVH_NODE_PRIM]);
            assert_int_equal(field(&view, at, BG_BVH_NODE_MISS), at + (field(&bvh, old, BG_BVH_NODE_MISS) - old));
        }
        free(order);
        free(seen);
        free(ids);
        free(renamed);
        free(out);
        free(shifted);
        bgi_bvh_destroy(&bvh);
        free_scene(&ts);
    }
}

static void test_stats(void **state)
{
    (void)state;
    bg_bvh_box boxes[1000];
    uint64_t rng = 11;
    for (int i = 0; i < 1000; i++) {
        double x = rng_range(&rng, 0, 100), y = rng_range(&rng, 0, 100), z = rng_range(&rng, 0, 100);
        boxes[i] = make_box(x, y, z, x + 1, y + 1, z + 1);
    }
    bg_bvh bvh = build_ok(boxes, 1000);
    bg_bvh_stats stats;
    bgi_bvh_get_stats(&bvh, &stats);
    assert_int_equal(stats.node_count, 1999);
    assert_int_equal(stats.prim_count, 1000);
    assert_int_equal(stats.depth, bvh.depth);
    /* At least ceil(log2 1000) + 1 levels; SAH trees are a few levels deeper, not hundreds. */
    assert_true(stats.depth >= 11 && stats.depth <= 40);
    /* The root counts 1, so more than 1; far below the node count for a useful tree. */
    assert_true(stats.sah_cost > 1.0 && stats.sah_cost < 0.1 * stats.node_count);
    bgi_bvh_destroy(&bvh);
}

/* ---- allocation ---- */

typedef struct counting {
    int calls, live, fail_at; /* fail_at: the call (0-based) that returns NULL, or -1 */
} counting;

static void *c_alloc(size_t size, void *user)
{
    counting *c = user;
    if (c->calls++ == c->fail_at)
        return NULL;
    c->live++;
    return malloc(size);
}

static void c_free(void *p, void *user)
{
    counting *c = user;
    if (p)
        c->live--;
    free(p);
}

static void test_out_of_memory(void **state)
{
    (void)state;
    bg_bvh_box boxes[50];
    for (int i = 0; i < 50; i++)
        boxes[i] = make_box(i, -i, 0, i + 2, 1, i * 0.5 + 1);
    int failures = 0;
    for (int fail_at = 0;; fail_at++) {
        counting c = {0, 0, fail_at};
        bg_allocator a = {c_alloc, NULL, c_free, &c};
        bg_bvh bvh;
        bg_status st = bgi_bvh_build(&a, boxes, 50, &bvh);
        if (st == BG_OK) {
            assert_true(c.calls <= fail_at); /* no allocation failed */
            check_tree(&bvh, boxes, 50);
            assert_int_equal(c.live, 1); /* only the node array stays */
            bgi_bvh_destroy(&bvh);
            assert_int_equal(c.live, 0);
            break;
        }
        assert_int_equal(st, BG_ERR_OUT_OF_MEMORY);
        assert_empty(&bvh);
        assert_int_equal(c.live, 0);
        failures++;
        assert_true(failures < 100);
    }
    assert_true(failures >= 1);

    /* Hooks without free are refused before anything is allocated. */
    counting c = {0, 0, -1};
    bg_allocator half = {c_alloc, NULL, NULL, &c};
    bg_bvh bvh;
    assert_int_equal(bgi_bvh_build(&half, boxes, 50, &bvh), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(c.calls, 0);
    assert_empty(&bvh);
}

/* The scene's own tree (built at commit) drives the CPU reference's nearest hit: with planes and
 * an object beyond the float range in the always-tested list, bgi_cpu_nearest_hit must give the
 * object and t of a loop over every object, skip rule included. */
static void test_scene_tree_drives_cpu_nearest_hit(void **state)
{
    (void)state;
    test_scene ts = random_scene(600, 0x5eed7);
    uint32_t mat = 1, plane, far;
    assert_int_equal(bg_scene_add_plane(ts.scene, bg_vec3_make(0, -ts.extent, 0), bg_vec3_make(0, 1, 0), mat, &plane),
                     BG_OK);
    assert_int_equal(bg_scene_add_sphere(ts.scene, bg_vec3_make(1e39, 0, 0), 1.0, mat, &far), BG_OK);
    assert_int_equal(bg_scene_commit(ts.scene), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(ts.scene);
    assert_int_equal(st->tree_count, 600);
    assert_int_equal(st->always_count, 2);
    assert_int_equal(st->always_objects[0], plane - 1);
    assert_int_equal(st->always_objects[1], far - 1);
    ts.state = st;
    uint64_t rng = 99;
    int hits = 0;
    for (int i = 0; i < 4000; i++) {
        double o[3], d[3];
        random_ray(&ts, &rng, o, d);
        uint32_t skip = i % 3 == 0 ? rng_below(&rng, st->object_count) : BG_CPU_NONE;
        uint32_t want = BG_CPU_NONE;
        double want_t = DBL_MAX;
        for (uint32_t j = 0; j < st->object_count; j++) {
            bg_cpu_candidate c;
            if (j != skip && bgi_cpu_intersect_object(&st->objects[j], o, d, false, want_t, &c) &&
                (want == BG_CPU_NONE || c.t < want_t)) {
                want = j;
                want_t = c.t;
            }
        }
        bg_cpu_hit hit;
        bool got = bgi_cpu_nearest_hit(st, o, d, skip, BG_CPU_NONE, &hit);
        assert_int_equal(got, want != BG_CPU_NONE);
        if (got) {
            assert_int_equal(hit.object, want);
            assert_true(hit.t == want_t);
            hits++;
        }
    }
    assert_true(hits > 1000);
    free_scene(&ts);
}

/* Commits keep, refit or rebuild the scene's tree by what changed. */
static void test_scene_tree_follows_commits(void **state)
{
    (void)state;
    test_scene ts = random_scene(50, 0xabc);
    const bg_scene_state *st = ts.state;
    assert_int_equal(st->tree_builds, 1);
    assert_int_equal(st->tree_refits, 0);
    const float *nodes = st->tree->nodes;
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(1, 2, 30);
    assert_int_equal(bg_scene_set_camera(ts.scene, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(ts.scene), BG_OK);
    assert_int_equal(st->tree_builds, 1);
    assert_int_equal(st->tree_refits, 0);
    bg_mat4 m = bg_mat4_translate(0.5, 0, 0);
    assert_int_equal(bg_scene_set_transform(ts.scene, 3, &m), BG_OK);
    assert_int_equal(bg_scene_commit(ts.scene), BG_OK);
    assert_int_equal(st->tree_builds, 1);
    assert_int_equal(st->tree_refits, 1);
    assert_ptr_equal(st->tree->nodes, nodes); /* same layout, refitted in place */
    uint32_t id;
    assert_int_equal(bg_scene_add_sphere(ts.scene, bg_vec3_make(0, 0, 0), 1.0, 1, &id), BG_OK);
    assert_int_equal(bg_scene_commit(ts.scene), BG_OK);
    assert_int_equal(st->tree_builds, 2);
    assert_int_equal(st->tree_count, 51);
    free_scene(&ts);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nearest_hit_matches_brute_force),
        cmocka_unit_test(test_scene_tree_drives_cpu_nearest_hit),
        cmocka_unit_test(test_scene_tree_follows_commits),
        cmocka_unit_test(test_any_hit_matches_brute_force),
        cmocka_unit_test(test_build_is_deterministic),
        cmocka_unit_test(test_refit_matches_rebuild),
        cmocka_unit_test(test_single_primitive),
        cmocka_unit_test(test_equal_centroids),
        cmocka_unit_test(test_zero_size_boxes),
        cmocka_unit_test(test_extreme_coordinates),
        cmocka_unit_test(test_outward_rounding),
        cmocka_unit_test(test_bad_boxes),
        cmocka_unit_test(test_empty_tree),
        cmocka_unit_test(test_bad_rays_and_refits),
        cmocka_unit_test(test_corrupt_nodes),
        cmocka_unit_test(test_stop_early),
        cmocka_unit_test(test_view_nodes),
        cmocka_unit_test(test_stats),
        cmocka_unit_test(test_out_of_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
