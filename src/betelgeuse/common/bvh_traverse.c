/* The walks of the node array in double. The threaded one is the GPU's, in float: an entered box
 * sends the walk to the next node, a missed box or a tested leaf to the miss link. The ordered one
 * takes each entered node's children nearer first along the ray, keeping the other on a stack of
 * one entry per level, so that a nearest-hit walk prunes the farther boxes: the CPU reference's
 * walk, where a stack costs nothing. Either visits each node at most once, so a valid tree ends
 * within node_count steps; the bound of twice that turns a corrupt array into an error instead of
 * an endless loop (bvh.h states the slab rules). */
#include "bvh.h"

#include <float.h>
#include <math.h>

/* Each slab distance carries two roundings (2^-53 each); widening by 4 ulps covers both. */
#define WIDEN_REL 0x1p-50

/* n / d for d != 0, saturated at +-DBL_MAX. |n / d| can only overflow when |d| < 1, where
 * |d| * DBL_MAX is finite; its rounding errs by at most 2^-53, which rounds back to DBL_MAX. */
static double saturating_div(double n, double d)
{
    if (fabs(d) < 1.0 && fabs(n) >= fabs(d) * DBL_MAX)
        return (n < 0.0) != (d < 0.0) ? -DBL_MAX : DBL_MAX;
    return n / d;
}

static double widen_down(double x)
{
    double w = fabs(x) * WIDEN_REL;
    return x >= -DBL_MAX + w ? x - w : -DBL_MAX;
}

static double widen_up(double x)
{
    double w = fabs(x) * WIDEN_REL;
    return x <= DBL_MAX - w ? x + w : DBL_MAX;
}

/* True when the ray's parameter interval [t_min, t_max] meets the node's box (rules in bvh.h). */
static bool box_entered(const float *node, const double o[3], const double d[3], double t_min, double t_max)
{
    double enter = t_min, exit = t_max;
    for (int a = 0; a < 3; a++) {
        double lo = node[BG_BVH_NODE_MIN + a], hi = node[BG_BVH_NODE_MAX + a];
        if (d[a] == 0.0) {
            if (o[a] < lo || o[a] > hi)
                return false;
            continue;
        }
        double t_lo = saturating_div(lo - o[a], d[a]), t_hi = saturating_div(hi - o[a], d[a]);
        double near = widen_down(t_lo < t_hi ? t_lo : t_hi), far = widen_up(t_lo < t_hi ? t_hi : t_lo);
        if (near > enter)
            enter = near;
        if (far < exit)
            exit = far;
        if (enter > exit)
            return false;
    }
    return true;
}

/* A node field holding an index: a whole float in [0, limit), or false for a corrupt array. */
static bool read_index(float value, uint32_t limit, uint32_t *out)
{
    if (!(value >= 0.0f && value < (float)limit) || value != floorf(value))
        return false;
    *out = (uint32_t)value;
    return true;
}

static bool ray_finite(const double o[3], const double d[3], double t_min, double t_max)
{
    for (int a = 0; a < 3; a++)
        if (!isfinite(o[a]) || !isfinite(d[a]))
            return false;
    return isfinite(t_min) && isfinite(t_max);
}

/* The interior node's child the ray should meet first: the one on the near side, along the ray, of
 * the axis on which the children's box centres lie farthest apart. Any order finds the same
 * hits; this one lets a nearest-hit walk shorten the ray before it reaches the farther boxes. */
static bool second_first(const float *first, const float *second, const double d[3])
{
    int axis = 0;
    double best = -1.0, along = 0.0;
    for (int a = 0; a < 3; a++) {
        double c1 = (double)first[BG_BVH_NODE_MIN + a] + first[BG_BVH_NODE_MAX + a];
        double c2 = (double)second[BG_BVH_NODE_MIN + a] + second[BG_BVH_NODE_MAX + a];
        if (fabs(c2 - c1) > best) {
            best = fabs(c2 - c1);
            axis = a;
            along = c2 - c1;
        }
    }
    return along * d[axis] < 0.0;
}

/* The ordered walk keeps the farther child of each entered interior node on its path: a tree
 * shallower than this needs no more; a deeper one is walked threaded. */
enum { ORDERED_DEPTH = 128 };

typedef struct walker {
    const bg_bvh *bvh;
    const double *o, *d;
    double t_min, *t_max;
    bg_bvh_visit_fn visit;
    void *user;
    bg_bvh_walk w;
} walker;

/* One step's common part: counts it (BG_ERR_LIMIT past twice the node count), checks the node's
 * miss link and tests its box. */
static bg_status step(walker *k, uint32_t i, uint32_t *miss, bool *entered)
{
    const uint32_t count = k->bvh->node_count;
    if (k->w.nodes_visited >= 2 * (uint64_t)count)
        return BG_ERR_LIMIT;
    k->w.nodes_visited++;
    const float *node = k->bvh->nodes + (size_t)i * BG_BVH_NODE_FLOATS;
    /* node_count itself is a valid miss link: the end of the walk. */
    if (!read_index(node[BG_BVH_NODE_MISS], count + 1, miss))
        return BG_ERR_INVALID_ARGUMENT;
    *entered = box_entered(node, k->o, k->d, k->t_min, *k->t_max);
    return BG_OK;
}

/* A leaf whose box was entered: the visit call; false ends the walk. */
static bg_status leaf(walker *k, const float *node, bool entered, bool *go_on)
{
    uint32_t prim;
    *go_on = true;
    if (!read_index(node[BG_BVH_NODE_PRIM], k->bvh->prim_count, &prim))
        return BG_ERR_INVALID_ARGUMENT;
    if (entered) {
        k->w.prims_visited++;
        if (!k->visit(k->user, prim, k->t_max)) {
            k->w.stopped = true;
            *go_on = false;
        }
    }
    return BG_OK;
}

/* Pre-order along the miss links: no state but the node index. */
static bg_status walk_threaded(walker *k)
{
    const uint32_t count = k->bvh->node_count;
    uint32_t i = 0;
    while (i < count) {
        uint32_t miss;
        bool entered, go_on;
        bg_status st = step(k, i, &miss, &entered);
        if (st != BG_OK)
            return st;
        const float *node = k->bvh->nodes + (size_t)i * BG_BVH_NODE_FLOATS;
        if (node[BG_BVH_NODE_PRIM] < 0.0f) {
            i = entered ? i + 1 : miss;
            continue;
        }
        st = leaf(k, node, entered, &go_on);
        if (st != BG_OK || !go_on)
            return st;
        i = miss;
    }
    return BG_OK;
}

/* Near child first (second_first), the other kept for later; count stands for "take the latest kept". */
static bg_status walk_ordered(walker *k)
{
    const uint32_t count = k->bvh->node_count;
    uint32_t pending[ORDERED_DEPTH];
    int n = 0;
    uint32_t i = 0;
    for (;;) {
        if (i == count) {
            if (n == 0)
                return BG_OK;
            i = pending[--n];
        }
        uint32_t miss, second;
        bool entered, go_on;
        bg_status st = step(k, i, &miss, &entered);
        if (st != BG_OK)
            return st;
        const float *node = k->bvh->nodes + (size_t)i * BG_BVH_NODE_FLOATS;
        if (node[BG_BVH_NODE_PRIM] >= 0.0f) {
            /* This walk never follows a leaf's miss link, but a wrong one shows a corrupt array. */
            if (miss != i + 1)
                return BG_ERR_INVALID_ARGUMENT;
            st = leaf(k, node, entered, &go_on);
            if (st != BG_OK || !go_on)
                return st;
            i = count;
            continue;
        }
        if (!entered) {
            i = count;
            continue;
        }
        /* An interior node's children: the next node and that one's miss link. */
        const float *first = node + BG_BVH_NODE_FLOATS;
        if (i + 1 >= count || !read_index(first[BG_BVH_NODE_MISS], count, &second) || n >= ORDERED_DEPTH)
            return BG_ERR_INVALID_ARGUMENT;
        bool swap = second_first(first, k->bvh->nodes + (size_t)second * BG_BVH_NODE_FLOATS, k->d);
        pending[n++] = swap ? i + 1 : second;
        i = swap ? second : i + 1;
    }
}

bg_status bgi_bvh_traverse(const bg_bvh *bvh, const double origin[3], const double direction[3], double t_min,
                          double *t_max, bg_bvh_visit_fn visit, void *user, bg_bvh_walk *walk)
{
    bg_bvh_walk none = {0, 0, false};
    if (walk)
        *walk = none;
    if (!bvh || !origin || !direction || !t_max || !visit || !ray_finite(origin, direction, t_min, *t_max))
        return BG_ERR_INVALID_ARGUMENT;
    walker k = {bvh, origin, direction, t_min, t_max, visit, user, none};
    bg_status st = bvh->node_count == 0 ? BG_OK : bvh->depth < ORDERED_DEPTH ? walk_ordered(&k) : walk_threaded(&k);
    if (walk)
        *walk = k.w;
    return st;
}
