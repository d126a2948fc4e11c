/* The bounding volume hierarchy both renderers walk: the GPU as two RGBA32F texels per node, the
 * CPU reference in double over the very same floats.
 *
 * Invariant, kept by build and refit alike:
 * - Every node's float box contains the double box it stands for: the union of its primitives'
 *   boxes, computed in double and rounded outward (min down, max up) to floats a GPU reads as
 *   themselves (normal floats or zero, since GPUs may flush subnormals to zero). A node's box
 *   therefore also contains its children's boxes.
 * - Nodes are stored in depth-first pre-order, node 0 the root. An interior node's first child is
 *   the next node; its second child is the first child's miss link. Each node's miss link is the
 *   first node after its subtree (node_count at the end), so a walk that goes to index + 1 when a
 *   box is entered and to the miss link otherwise visits every node at most once, always forward,
 *   and needs no stack.
 * - Every leaf holds exactly one primitive, so a tree of n primitives has 2n - 1 nodes and a node
 *   over k primitives has miss link index + 2k - 1.
 *
 * A node is 8 floats, the two texels {min.xyz, prim} and {max.xyz, miss}: prim is the leaf's
 * primitive index, or -1 for an interior node; miss is a node index. Every index is a whole float
 * no larger than 2^24, where floats hold every integer exactly; that caps a tree at 2^23
 * primitives (2^24 - 1 nodes).
 *
 * The build is top-down binned SAH and fully deterministic: it depends only on the boxes and their
 * order (no sort, no threads, no pointers), and equal costs or indistinguishable centroids are
 * resolved by primitive index. Boxes are checked first: a box with a NaN or infinite coordinate or
 * min > max is BG_ERR_INVALID_ARGUMENT, a coordinate beyond the float range (|x| > FLT_MAX, which
 * no float box can contain) BG_ERR_LIMIT. */
#ifndef BG_BVH_H
#define BG_BVH_H

#include "betelgeuse.h"

/* The node layout: float offsets within one node of BG_BVH_NODE_FLOATS floats. */
enum {
    BG_BVH_NODE_MIN = 0,   /* min x, y, z */
    BG_BVH_NODE_PRIM = 3,  /* leaf: primitive index; interior: -1 */
    BG_BVH_NODE_MAX = 4,   /* max x, y, z */
    BG_BVH_NODE_MISS = 7,  /* the node after this subtree; node_count means done */
    BG_BVH_NODE_FLOATS = 8
};

/* The most primitives a tree takes: its 2n - 1 node indices must stay exact in a float. */
#define BG_BVH_MAX_PRIMS (1u << 23)

/* One primitive's world box in double; min <= max per axis, a point box is fine. */
typedef struct bg_bvh_box {
    double min[3], max[3];
} bg_bvh_box;

/* A built tree; all zero is the empty tree (no nodes), which every ray misses. */
typedef struct bg_bvh {
    float *nodes;           /* node_count * BG_BVH_NODE_FLOATS floats: upload with one memcpy */
    uint32_t node_count;    /* 2 prim_count - 1, or 0 */
    uint32_t prim_count;
    uint32_t depth;         /* nodes on the longest root-to-leaf path (0 empty, 1 a single leaf) */
    bg_allocator allocator; /* the hooks nodes came from */
} bg_bvh;

/* What bgi_bvh_get_stats reports. */
typedef struct bg_bvh_stats {
    uint32_t node_count, prim_count, depth;
    /* Sum over nodes of their surface area over the root's: the expected number of boxes a random
     * line through the root box tests when the walk never shortens it. Lower is better; a refit
     * tree's value against a rebuild's shows what the refit cost. 0 for an empty tree or a flat
     * root box. */
    double sah_cost;
} bg_bvh_stats;

/* Checks count boxes as the build does; on failure writes the first bad index (when out_first_bad
 * is not NULL) and returns BG_ERR_INVALID_ARGUMENT or BG_ERR_LIMIT as described above. */
bg_status bgi_bvh_check_boxes(const bg_bvh_box *boxes, uint32_t count, uint32_t *out_first_bad);

/* Builds a tree over boxes[0 .. count - 1] into *out through allocator (NULL: the C library's).
 * count 0 gives the empty tree; count > BG_BVH_MAX_PRIMS is BG_ERR_LIMIT. Besides the 32 bytes per
 * node it keeps, the build borrows 56 bytes per primitive while it runs, and takes one pass over
 * the primitives per tree level. On any failure *out is the empty tree and nothing stays
 * allocated; *out is overwritten, so destroy a previous tree first. */
bg_status bgi_bvh_build(const bg_allocator *allocator, const bg_bvh_box *boxes, uint32_t count, bg_bvh *out);

/* Frees the tree's nodes and leaves it empty; NULL and the empty tree are ignored. */
void bgi_bvh_destroy(bg_bvh *bvh);

/* Recomputes every node's box from new boxes of the same count primitives, keeping the topology,
 * for transform changes. The tree stays valid (the invariant holds) but may lose quality: moved
 * primitives can make sibling boxes overlap and walks longer, which bg_bvh_stats's sah_cost shows.
 * Adding or removing primitives is a structure change and needs a rebuild. On failure (bad boxes,
 * count different from the tree's) the tree is left unchanged. Refitting with the build's own
 * boxes gives back the built floats bit for bit. */
bg_status bgi_bvh_refit(bg_bvh *bvh, const bg_bvh_box *boxes, uint32_t count);

/* The order in which bgi_bvh_view_nodes lays the nodes out for origin: order[at] is the node of the
 * tree that goes to index at (node_count entries). Each interior node's nearer child, by the distance
 * from origin to its box, comes first; the rest follows from the subtree sizes, so a node at index
 * at whose old index is old has miss link at + (miss - old). Origin is in the frame of the boxes (a
 * mesh's object space for a mesh's tree). Borrows
 * 8 bytes per tree level from the tree's allocator: BG_ERR_OUT_OF_MEMORY when they are refused. */
bg_status bgi_bvh_view_order(const bg_bvh *bvh, const double origin[3], uint32_t *order);

/* Writes the tree's node_count nodes into out as seen from origin, for walks of rays that start
 * there: every box minus origin, computed in double and rounded outward again (the invariant holds
 * for the shifted boxes); each interior node's children swapped where the second one's box is nearer
 * to origin, so that a walk meets nearer boxes first (the layout stays pre-order with miss links);
 * each leaf's primitive replaced by prim_ids[primitive] when prim_ids is not NULL (ids below 2^24
 * stay exact). The GPU keeps its world frame at the camera, where a float box far from the origin
 * would cost the ray its precision, and uploads this copy. Borrows 8 bytes per tree level from the
 * tree's allocator while it runs, and 4 bytes per node for the order: BG_ERR_OUT_OF_MEMORY when they
 * are refused (out then partly written or not written). */
bg_status bgi_bvh_view_nodes(const bg_bvh *bvh, const double origin[3], const uint32_t *prim_ids, float *out);

/* Fills *stats for the tree. */
void bgi_bvh_get_stats(const bg_bvh *bvh, bg_bvh_stats *stats);

/* Called for every leaf whose box the ray enters, with the leaf's primitive: the callee tests it,
 * may lower *t_max (nearest hit: later boxes are then tested against the shorter ray), and returns
 * false to end the walk (any hit, for shadow rays). */
typedef bool (*bg_bvh_visit_fn)(void *user, uint32_t prim, double *t_max);

/* What one walk did, for statistics and tests. */
typedef struct bg_bvh_walk {
    uint32_t nodes_visited; /* boxes tested */
    uint32_t prims_visited; /* visit calls */
    bool stopped;           /* a visit call returned false */
} bg_bvh_walk;

/* Walks the tree for the ray origin + t direction, t in (t_min, *t_max], in double, calling visit
 * for each entered leaf; *t_max is updated by the calls. Leaves come nearer child first: at each
 * interior node the child on the ray's near side of the axis that separates the children's centres
 * most (pre-order, along the miss links, for a tree of depth 128 or more). A box is entered when its
 * slab interval, clipped to [t_min, *t_max], is not empty: inclusive at both ends, so of two
 * primitives at one distance both are visited and the callee applies its tie rule (distance, then
 * lower primitive index). The slab test is conservative and needs no IEEE infinities:
 * - a direction component exactly zero: the slab is entered for every t when the origin lies in
 *   [min, max] on that axis (inclusive), never otherwise;
 * - otherwise the slab distances (bound - origin) / direction saturate at +-DBL_MAX instead of
 *   overflowing, so a tiny component puts the slab at "beyond every finite t": entered for every t
 *   from inside the slab, and from outside only by a ray whose *t_max is DBL_MAX (one needless
 *   leaf test, never a missed one);
 * - each distance is widened outward by 2^-50 of its magnitude, more than its two roundings (a
 *   subtraction, a division: 2^-52 together), so rounding never rejects a box the exact test
 *   would enter.
 * A valid tree ends within node_count steps; the walk gives up with BG_ERR_LIMIT rather than run
 * past 2 node_count steps, and a node index or primitive out of range (a corrupt node array) is
 * BG_ERR_INVALID_ARGUMENT, both before further visit calls. Non-finite ray values or a NULL visit
 * are BG_ERR_INVALID_ARGUMENT. walk may be NULL. */
bg_status bgi_bvh_traverse(const bg_bvh *bvh, const double origin[3], const double direction[3], double t_min,
                          double *t_max, bg_bvh_visit_fn visit, void *user, bg_bvh_walk *walk);

#endif
