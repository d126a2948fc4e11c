/* Writing the node array: the binned SAH build, the refit and the stats (bvh.h states the
 * invariant both writers keep).
 *
 * The build splits ranges of a working copy of the primitives (each box with its index), top-down.
 * The boxes travel with their indices so that every pass reads memory in order rather than the
 * caller's array at random (twice as fast at a million boxes). Partitions are stable and the copy
 * starts in index order, so every range lists its primitives in ascending index order: "split by
 * index median" is then just the middle of the range, and nothing depends on a sort's tie order.
 * A node over k primitives has 2k - 1 nodes in its subtree, so its children's indices and its miss
 * link follow from the counts alone, whatever order the ranges are worked in. */
#include "bvh.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "alloc.h"

/* Bins per axis; 16 is the usual point past which a finer grid no longer pays for its sweep. */
#define BINS 16
/* An axis whose centroids spread less than this is flat: BINS / extent must stay finite. */
#define MIN_EXTENT 0x1p-1000
/* Pending ranges: the build always continues with the smaller child and keeps the larger one, so
 * each kept range is at most half the one before it and 2^23 primitives need at most 23. */
#define MAX_PENDING 64

/* ---- checks and outward rounding ----------------------------------------------------------- */

static bg_status check_box(const bg_bvh_box *box)
{
    for (int a = 0; a < 3; a++) {
        double lo = box->min[a], hi = box->max[a];
        if (!isfinite(lo) || !isfinite(hi) || lo > hi)
            return BG_ERR_INVALID_ARGUMENT;
        if (fabs(lo) > FLT_MAX || fabs(hi) > FLT_MAX)
            return BG_ERR_LIMIT;
    }
    return BG_OK;
}

bg_status bgi_bvh_check_boxes(const bg_bvh_box *boxes, uint32_t count, uint32_t *out_first_bad)
{
    if (count > 0 && !boxes)
        return BG_ERR_INVALID_ARGUMENT;
    for (uint32_t i = 0; i < count; i++) {
        bg_status st = check_box(&boxes[i]);
        if (st != BG_OK) {
            if (out_first_bad)
                *out_first_bad = i;
            return st;
        }
    }
    return BG_OK;
}

/* The largest normal float or zero <= x (|x| <= FLT_MAX). Rounding to a fixed set of values is
 * monotone, so the rounded union of two boxes is the union of the rounded boxes: refit may combine
 * children's floats and still get what the build computed from doubles. Zero is always +0 so that
 * equal boxes have equal bits. */
static float float_down(double x)
{
    float f = (float)x;
    if ((double)f > x)
        f = nextafterf(f, -FLT_MAX);
    if (fabsf(f) < FLT_MIN)
        f = f < 0.0f ? -FLT_MIN : 0.0f;
    return f;
}

/* The smallest normal float or zero >= x (|x| <= FLT_MAX). */
static float float_up(double x)
{
    float f = (float)x;
    if ((double)f < x)
        f = nextafterf(f, FLT_MAX);
    if (fabsf(f) < FLT_MIN)
        f = f > 0.0f ? FLT_MIN : 0.0f;
    return f;
}

static void write_box(float *node, const bg_bvh_box *box)
{
    for (int a = 0; a < 3; a++) {
        node[BG_BVH_NODE_MIN + a] = float_down(box->min[a]);
        node[BG_BVH_NODE_MAX + a] = float_up(box->max[a]);
    }
}

/* ---- boxes -------------------------------------------------------------------------------- */

/* A primitive's box as the build works with it: its double box rounded outward to the floats the
 * node will hold. The union of rounded boxes is the rounded union (float_down), so nodes come out
 * as from the doubles, and half the bytes of a double box go through every level's passes. Boxes
 * of float vertices (every mesh) are floats already and lose nothing. */
typedef struct fbox {
    float min[3], max[3];
} fbox;

static const fbox EMPTY_BOX = {{FLT_MAX, FLT_MAX, FLT_MAX}, {-FLT_MAX, -FLT_MAX, -FLT_MAX}};
static const bg_bvh_box EMPTY_CENTROIDS = {{DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}};

static fbox round_box(const bg_bvh_box *box)
{
    fbox f;
    for (int a = 0; a < 3; a++) {
        f.min[a] = float_down(box->min[a]);
        f.max[a] = float_up(box->max[a]);
    }
    return f;
}

static inline float min_f(float a, float b)
{
    return a < b ? a : b;
}

static inline float max_f(float a, float b)
{
    return a > b ? a : b;
}

/* Written out rather than looped over the axes: the build's inner loops run this for every
 * primitive at every level, and the compiler kept the loop. */
static inline void grow_box(fbox *box, const fbox *by)
{
    box->min[0] = min_f(by->min[0], box->min[0]);
    box->min[1] = min_f(by->min[1], box->min[1]);
    box->min[2] = min_f(by->min[2], box->min[2]);
    box->max[0] = max_f(by->max[0], box->max[0]);
    box->max[1] = max_f(by->max[1], box->max[1]);
    box->max[2] = max_f(by->max[2], box->max[2]);
}

/* The one centroid formula: binning and partitioning must agree on every primitive's bin. */
static inline double centroid(const fbox *box, int axis)
{
    return 0.5 * ((double)box->min[axis] + (double)box->max[axis]);
}

static inline void grow_centroid(bg_bvh_box *bounds, const fbox *box, int axis)
{
    double c = centroid(box, axis);
    bounds->min[axis] = c < bounds->min[axis] ? c : bounds->min[axis];
    bounds->max[axis] = c > bounds->max[axis] ? c : bounds->max[axis];
}

static inline void grow_centroids(bg_bvh_box *bounds, const fbox *box)
{
    grow_centroid(bounds, box, 0);
    grow_centroid(bounds, box, 1);
    grow_centroid(bounds, box, 2);
}

/* Half the surface area; the factor 2 drops out of every comparison. */
static inline double half_area(const fbox *box)
{
    double dx = (double)box->max[0] - box->min[0], dy = (double)box->max[1] - box->min[1],
           dz = (double)box->max[2] - box->min[2];
    return dx * dy + dy * dz + dz * dx;
}

/* ---- the build ----------------------------------------------------------------------------- */

/* A range items[begin .. begin + count - 1] that becomes node `node` at depth `depth` (root 1). */
typedef struct range {
    uint32_t begin, count, node, depth;
    fbox bounds;          /* union of the range's boxes */
    bg_bvh_box centroids; /* bounds of their centroids */
} range;

/* A primitive in the build's working copy. */
typedef struct item {
    fbox box;
    uint32_t prim;
} item;

typedef struct builder {
    item *items;   /* every range in ascending primitive order */
    item *scratch; /* the right side of a partition in progress */
    float *nodes;
    uint32_t depth;
} builder;

/* A split of a range: primitives whose bin on axis is below bin go left. axis -1 is the index
 * median: the lower-indexed half goes left. */
typedef struct split {
    int axis, bin;
} split;

/* Maps a centroid to its bin; the scale is BINS / extent of the range's centroids on that axis. */
static inline int bin_of(double c, double lo, double scale)
{
    int b = (int)((c - lo) * scale);
    return b < BINS ? b : BINS - 1;
}

static double bin_scale(const range *r, int axis)
{
    double extent = r->centroids.max[axis] - r->centroids.min[axis];
    return extent >= MIN_EXTENT ? BINS / extent : 0.0;
}

typedef struct bins {
    uint32_t count[BINS];
    fbox box[BINS]; /* meaningful where count > 0 */
} bins;

static inline void add_to_bin(bins *bn, int k, const fbox *box)
{
    if (bn->count[k]++ == 0)
        bn->box[k] = *box;
    else
        grow_box(&bn->box[k], box);
}

/* A bin's box is set by its first primitive rather than cleared first: most ranges are small and
 * leave most of their 3 BINS bins empty, so only the counts are cleared. */
static void fill_bins(const builder *b, const range *r, const double scale[3], bins per_axis[3])
{
    for (int a = 0; a < 3; a++)
        memset(per_axis[a].count, 0, sizeof per_axis[a].count);
    for (uint32_t i = r->begin; i < r->begin + r->count; i++) {
        const fbox *box = &b->items[i].box;
        for (int a = 0; a < 3; a++)
            if (scale[a] != 0.0)
                add_to_bin(&per_axis[a], bin_of(centroid(box, a), r->centroids.min[a], scale[a]), box);
    }
}

/* The cheapest plane of one axis: cost = traversal + A(left) n(left) + A(right) n(right), over
 * the parent's area. Every split of a range has the same traversal term and the same parent (a
 * leaf holds one primitive, so "no split" is never an option), which leaves the area-weighted
 * counts to compare. Planes are tried left to right and only a strictly lower cost replaces the
 * best, so ties go to the lowest plane.
 *
 * Only planes just above a non-empty bin are costed: a plane above an empty bin has the same two
 * sides as the plane below it, hence the same cost, and loses the tie to it. */
static void best_plane(const bins *bn, int axis, split *best, double *best_cost)
{
    double right_area[BINS];
    uint32_t right_count[BINS];
    fbox acc = EMPTY_BOX;
    uint32_t n = 0;
    double area = 0.0;
    for (int k = BINS - 1; k > 0; k--) {
        if (bn->count[k] > 0) {
            grow_box(&acc, &bn->box[k]);
            n += bn->count[k];
            area = half_area(&acc);
        }
        right_area[k] = area;
        right_count[k] = n;
    }
    acc = EMPTY_BOX;
    n = 0;
    for (int k = 1; k < BINS; k++) {
        if (bn->count[k - 1] == 0)
            continue;
        grow_box(&acc, &bn->box[k - 1]);
        n += bn->count[k - 1];
        if (right_count[k] == 0)
            break;
        double cost = half_area(&acc) * n + right_area[k] * right_count[k];
        if (best->axis < 0 || cost < *best_cost) {
            best->axis = axis;
            best->bin = k;
            *best_cost = cost;
        }
    }
}

/* The SAH split of a range, or the index median when binning cannot separate its centroids (all
 * equal, or too close for BINS bins). Axes are tried x, y, z: ties go to the lowest axis. */
static split choose_split(const builder *b, const range *r, double scale[3])
{
    bins per_axis[3];
    split best = {-1, 0};
    double best_cost = 0.0;
    for (int a = 0; a < 3; a++)
        scale[a] = bin_scale(r, a);
    if (scale[0] == 0.0 && scale[1] == 0.0 && scale[2] == 0.0)
        return best;
    fill_bins(b, r, scale, per_axis);
    for (int a = 0; a < 3; a++)
        if (scale[a] != 0.0)
            best_plane(&per_axis[a], a, &best, &best_cost);
    return best;
}

static bool goes_left(const builder *b, const range *r, const split *s, const double scale[3], uint32_t i)
{
    if (s->axis < 0)
        return i - r->begin < r->count / 2;
    double c = centroid(&b->items[i].box, s->axis);
    return bin_of(c, r->centroids.min[s->axis], scale[s->axis]) < s->bin;
}

static void start_range(range *child, uint32_t begin, uint32_t node, uint32_t depth)
{
    child->begin = begin;
    child->count = 0;
    child->node = node;
    child->depth = depth;
    child->bounds = EMPTY_BOX;
    child->centroids = EMPTY_CENTROIDS;
}

static inline void add_to_range(range *child, const fbox *box)
{
    child->count++;
    grow_box(&child->bounds, box);
    grow_centroids(&child->centroids, box);
}

/* Stable partition of the range into its two children, which get their exact bounds on
 * the way. Left primitives are compacted in place (the write position never passes the read
 * position), right ones wait in scratch and are copied in behind. */
static void partition(builder *b, const range *r, const split *s, const double scale[3], range *left,
                      range *right)
{
    uint32_t w = r->begin, nr = 0;
    start_range(left, r->begin, r->node + 1, r->depth + 1);
    start_range(right, 0, 0, r->depth + 1);
    for (uint32_t i = r->begin; i < r->begin + r->count; i++) {
        const item it = b->items[i];
        if (goes_left(b, r, s, scale, i)) {
            b->items[w++] = it;
            add_to_range(left, &it.box);
        } else {
            b->scratch[nr++] = it;
            add_to_range(right, &it.box);
        }
    }
    memcpy(b->items + w, b->scratch, nr * sizeof *b->scratch);
    right->begin = w;
    right->node = r->node + 2 * left->count; /* after the left subtree's 2 n - 1 nodes */
}

static void write_node(builder *b, const range *r)
{
    float *node = b->nodes + (size_t)r->node * BG_BVH_NODE_FLOATS;
    for (int a = 0; a < 3; a++) {
        node[BG_BVH_NODE_MIN + a] = r->bounds.min[a];
        node[BG_BVH_NODE_MAX + a] = r->bounds.max[a];
    }
    node[BG_BVH_NODE_PRIM] = r->count == 1 ? (float)b->items[r->begin].prim : -1.0f;
    node[BG_BVH_NODE_MISS] = (float)(r->node + 2 * r->count - 1);
    if (r->count == 1 && r->depth > b->depth)
        b->depth = r->depth;
}

static void root_range(builder *b, const bg_bvh_box *boxes, uint32_t count, range *root)
{
    start_range(root, 0, 0, 1);
    for (uint32_t i = 0; i < count; i++) {
        b->items[i].box = round_box(&boxes[i]);
        b->items[i].prim = i;
        add_to_range(root, &b->items[i].box);
    }
}

/* Writes every node: each range is written, then split; the smaller child is worked on next and
 * the larger one kept, which bounds the pending list (MAX_PENDING). */
static void build_nodes(builder *b, const bg_bvh_box *boxes, uint32_t count)
{
    range pending[MAX_PENDING], current;
    int pending_count = 0;
    root_range(b, boxes, count, &current);
    for (;;) {
        write_node(b, &current);
        if (current.count > 1) {
            double scale[3];
            split s = choose_split(b, &current, scale);
            range left, right;
            partition(b, &current, &s, scale, &left, &right);
            bool left_smaller = left.count <= right.count;
            pending[pending_count++] = left_smaller ? right : left;
            current = left_smaller ? left : right;
            continue;
        }
        if (pending_count == 0)
            return;
        current = pending[--pending_count];
    }
}

static void empty_tree(bg_bvh *bvh, const bg_allocator *allocator)
{
    memset(bvh, 0, sizeof *bvh);
    if (allocator)
        bvh->allocator = *allocator;
}

/* The node array and the build's working copy and scratch, all or nothing. */
static bg_status allocate(const bg_allocator *a, uint32_t count, builder *b)
{
    size_t node_bytes, item_bytes;
    size_t node_floats = (size_t)(2 * count - 1) * BG_BVH_NODE_FLOATS;
    if (!bgi_size_mul(node_floats, sizeof(float), &node_bytes) || !bgi_size_mul(count, sizeof(item), &item_bytes))
        return BG_ERR_OUT_OF_MEMORY;
    b->nodes = bgi_alloc(a, node_bytes);
    b->items = bgi_alloc(a, item_bytes);
    b->scratch = bgi_alloc(a, item_bytes);
    if (b->nodes && b->items && b->scratch)
        return BG_OK;
    bgi_free(a, b->nodes);
    bgi_free(a, b->items);
    bgi_free(a, b->scratch);
    return BG_ERR_OUT_OF_MEMORY;
}

bg_status bgi_bvh_build(const bg_allocator *allocator, const bg_bvh_box *boxes, uint32_t count, bg_bvh *out)
{
    static const bg_allocator default_allocator = {NULL, NULL, NULL, NULL};
    if (!out)
        return BG_ERR_INVALID_ARGUMENT;
    const bg_allocator *a = allocator ? allocator : &default_allocator;
    empty_tree(out, a);
    if (!bgi_allocator_valid(a))
        return BG_ERR_INVALID_ARGUMENT;
    if (count > BG_BVH_MAX_PRIMS)
        return BG_ERR_LIMIT;
    bg_status st = bgi_bvh_check_boxes(boxes, count, NULL);
    if (st != BG_OK || count == 0)
        return st;

    builder b = {NULL, NULL, NULL, 0};
    st = allocate(a, count, &b);
    if (st != BG_OK)
        return st;
    build_nodes(&b, boxes, count);
    bgi_free(a, b.items);
    bgi_free(a, b.scratch);

    out->nodes = b.nodes;
    out->node_count = 2 * count - 1;
    out->prim_count = count;
    out->depth = b.depth;
    return BG_OK;
}

void bgi_bvh_destroy(bg_bvh *bvh)
{
    if (!bvh)
        return;
    bgi_free(&bvh->allocator, bvh->nodes);
    bg_allocator a = bvh->allocator;
    empty_tree(bvh, &a);
}

/* ---- refit --------------------------------------------------------------------------------- */

static uint32_t node_index(const float *node, int field)
{
    return (uint32_t)node[field];
}

/* An interior node's box is the union of its children's floats, which by the monotone rounding
 * equals the rounded union of their doubles (float_down). Children follow their parent in
 * pre-order, so a backward sweep meets them first. */
bg_status bgi_bvh_refit(bg_bvh *bvh, const bg_bvh_box *boxes, uint32_t count)
{
    if (!bvh || count != bvh->prim_count)
        return BG_ERR_INVALID_ARGUMENT;
    bg_status st = bgi_bvh_check_boxes(boxes, count, NULL);
    if (st != BG_OK)
        return st;
    for (uint32_t i = bvh->node_count; i-- > 0;) {
        float *node = bvh->nodes + (size_t)i * BG_BVH_NODE_FLOATS;
        if (node[BG_BVH_NODE_PRIM] >= 0.0f) {
            write_box(node, &boxes[node_index(node, BG_BVH_NODE_PRIM)]);
            continue;
        }
        const float *first = node + BG_BVH_NODE_FLOATS;
        const float *second = bvh->nodes + (size_t)node_index(first, BG_BVH_NODE_MISS) * BG_BVH_NODE_FLOATS;
        for (int a = 0; a < 3; a++) {
            float lo0 = first[BG_BVH_NODE_MIN + a], lo1 = second[BG_BVH_NODE_MIN + a];
            float hi0 = first[BG_BVH_NODE_MAX + a], hi1 = second[BG_BVH_NODE_MAX + a];
            node[BG_BVH_NODE_MIN + a] = lo1 < lo0 ? lo1 : lo0;
            node[BG_BVH_NODE_MAX + a] = hi1 > hi0 ? hi1 : hi0;
        }
    }
    return BG_OK;
}

/* ---- stats --------------------------------------------------------------------------------- */

static double node_half_area(const float *node)
{
    fbox box;
    for (int a = 0; a < 3; a++) {
        box.min[a] = node[BG_BVH_NODE_MIN + a];
        box.max[a] = node[BG_BVH_NODE_MAX + a];
    }
    return half_area(&box);
}

void bgi_bvh_get_stats(const bg_bvh *bvh, bg_bvh_stats *stats)
{
    memset(stats, 0, sizeof *stats);
    stats->node_count = bvh->node_count;
    stats->prim_count = bvh->prim_count;
    stats->depth = bvh->depth;
    if (bvh->node_count == 0)
        return;
    double root = node_half_area(bvh->nodes);
    if (!(root > 0.0))
        return;
    double sum = 0.0;
    for (uint32_t i = 0; i < bvh->node_count; i++)
        sum += node_half_area(bvh->nodes + (size_t)i * BG_BVH_NODE_FLOATS);
    stats->sah_cost = sum / root;
}

/* ---- a copy for one viewpoint ------------------------------------------------------------- */

static double clamp_to_float_range(double x)
{
    return x < -FLT_MAX ? -FLT_MAX : (x > FLT_MAX ? FLT_MAX : x);
}

/* Squared distance from p to the node's box (0 inside it). */
static double box_distance2(const float *node, const double p[3])
{
    double d2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double lo = node[BG_BVH_NODE_MIN + a], hi = node[BG_BVH_NODE_MAX + a];
        double d = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0.0);
        d2 += d * d;
    }
    return d2;
}

/* Node old of the tree written at index at of out, shifted by -origin; a subtree keeps its size, so
 * its miss link is at plus the old span. Each coordinate's double difference is within half an ulp
 * of a double of the exact one, far below the float step the rounding adds, so a box the shifted
 * box should contain is inside it. */
static void write_shifted(const bg_bvh *bvh, uint32_t old, uint32_t at, const double origin[3],
                          const uint32_t *prim_ids, float *out)
{
    const float *node = bvh->nodes + (size_t)old * BG_BVH_NODE_FLOATS;
    float *o = out + (size_t)at * BG_BVH_NODE_FLOATS;
    for (int a = 0; a < 3; a++) {
        o[BG_BVH_NODE_MIN + a] = float_down(clamp_to_float_range((double)node[BG_BVH_NODE_MIN + a] - origin[a]));
        o[BG_BVH_NODE_MAX + a] = float_up(clamp_to_float_range((double)node[BG_BVH_NODE_MAX + a] - origin[a]));
    }
    float prim = node[BG_BVH_NODE_PRIM];
    o[BG_BVH_NODE_PRIM] = prim >= 0.0f && prim_ids ? (float)prim_ids[node_index(node, BG_BVH_NODE_PRIM)] : prim;
    o[BG_BVH_NODE_MISS] = (float)(at + (node_index(node, BG_BVH_NODE_MISS) - old));
}

/* A walk in pre-order meets a subtree's first child first; a ray from the viewpoint that hits
 * something in the nearer child then skips the farther one's boxes beyond that hit. The order is
 * chosen per node by the distance from the viewpoint to each child's box, the tree's first child on
 * a tie. The depth-first order leaves at most one pending subtree per level. */
bg_status bgi_bvh_view_order(const bg_bvh *bvh, const double origin[3], uint32_t *order)
{
    if (bvh->node_count == 0)
        return BG_OK;
    size_t room = (size_t)bvh->depth + 1;
    uint32_t *pending_old = bgi_alloc(&bvh->allocator, 2 * room * sizeof *pending_old);
    if (!pending_old)
        return BG_ERR_OUT_OF_MEMORY;
    uint32_t *pending_at = pending_old + room;
    size_t n = 0;
    pending_old[n] = 0;
    pending_at[n++] = 0;
    while (n > 0) {
        n--;
        uint32_t old = pending_old[n], at = pending_at[n];
        order[at] = old;
        const float *node = bvh->nodes + (size_t)old * BG_BVH_NODE_FLOATS;
        if (node[BG_BVH_NODE_PRIM] >= 0.0f)
            continue;
        uint32_t first = old + 1;
        uint32_t second = node_index(bvh->nodes + (size_t)first * BG_BVH_NODE_FLOATS, BG_BVH_NODE_MISS);
        uint32_t first_span = second - first;
        bool swap = box_distance2(bvh->nodes + (size_t)second * BG_BVH_NODE_FLOATS, origin) <
                    box_distance2(bvh->nodes + (size_t)first * BG_BVH_NODE_FLOATS, origin);
        uint32_t second_span = node_index(node, BG_BVH_NODE_MISS) - second;
        uint32_t near = swap ? second : first, far = swap ? first : second;
        uint32_t near_span = swap ? second_span : first_span;
        pending_old[n] = far;
        pending_at[n++] = at + 1 + near_span;
        pending_old[n] = near;
        pending_at[n++] = at + 1;
    }
    bgi_free(&bvh->allocator, pending_old);
    return BG_OK;
}

bg_status bgi_bvh_view_nodes(const bg_bvh *bvh, const double origin[3], const uint32_t *prim_ids, float *out)
{
    if (bvh->node_count == 0)
        return BG_OK;
    uint32_t *order = bgi_alloc(&bvh->allocator, (size_t)bvh->node_count * sizeof *order);
    bg_status st = order ? bgi_bvh_view_order(bvh, origin, order) : BG_ERR_OUT_OF_MEMORY;
    for (uint32_t at = 0; st == BG_OK && at < bvh->node_count; at++)
        write_shifted(bvh, order[at], at, origin, prim_ids, out);
    bgi_free(&bvh->allocator, order);
    return st;
}
