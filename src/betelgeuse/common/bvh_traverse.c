/* The stackless walk of the threaded node array in double, as the GPU walks it in float: an
 * entered box sends the walk to the next node, a missed box or a tested leaf to the miss link.
 * Every step moves forward, so a valid tree ends within node_count steps; the bound of twice that
 * turns a corrupt array into an error instead of an endless loop (bvh.h states the slab rules). */
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

bg_status bg_bvh_traverse(const bg_bvh *bvh, const double origin[3], const double direction[3], double t_min,
                          double *t_max, bg_bvh_visit_fn visit, void *user, bg_bvh_walk *walk)
{
    bg_bvh_walk w = {0, 0, false};
    if (walk)
        *walk = w;
    if (!bvh || !origin || !direction || !t_max || !visit || !ray_finite(origin, direction, t_min, *t_max))
        return BG_ERR_INVALID_ARGUMENT;
    const uint32_t count = bvh->node_count;
    const uint64_t step_limit = 2 * (uint64_t)count;
    bg_status st = BG_OK;
    uint32_t i = 0;
    while (i < count) {
        if (w.nodes_visited >= step_limit) {
            st = BG_ERR_LIMIT;
            break;
        }
        w.nodes_visited++;
        const float *node = bvh->nodes + (size_t)i * BG_BVH_NODE_FLOATS;
        uint32_t miss, prim;
        /* node_count itself is a valid miss link: the end of the walk. */
        if (!read_index(node[BG_BVH_NODE_MISS], count + 1, &miss)) {
            st = BG_ERR_INVALID_ARGUMENT;
            break;
        }
        bool entered = box_entered(node, origin, direction, t_min, *t_max);
        if (node[BG_BVH_NODE_PRIM] < 0.0f) {
            i = entered ? i + 1 : miss;
            continue;
        }
        if (!read_index(node[BG_BVH_NODE_PRIM], bvh->prim_count, &prim)) {
            st = BG_ERR_INVALID_ARGUMENT;
            break;
        }
        if (entered) {
            w.prims_visited++;
            if (!visit(user, prim, t_max)) {
                w.stopped = true;
                break;
            }
        }
        i = miss;
    }
    if (walk)
        *walk = w;
    return st;
}
