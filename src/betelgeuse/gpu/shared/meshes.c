/* The meshes' textures, one copy that every plan reads (r->meshes): every distinct mesh's own tree
 * in one texture, its triangles in the other, each addressed by texel index (bg_mesh.glsl gives the
 * layout), and per mesh object the texels its mesh starts at, which the plans pass as a uniform (the
 * fused tree in its objects texture); mesh_source.c walks them. A mesh's serial names its contents
 * for good, so a commit that keeps the meshes, and the order their trees are laid out in, uploads
 * nothing here, whichever plan renders it.
 *
 * Each tree goes up ordered for the camera (bgi_bvh_view_order, for a point chosen by where the eye
 * lies in the object space of the first object that shows the copy, order_point): a walk then meets
 * the nearer child of every node first, and a camera ray that hits the near side of a closed mesh
 * skips the far side's boxes. A walk in the build's order took twice the steps on an icosphere's
 * camera rays (docs/benchmarks.md, "Mesh trees in view order"). The order changes no hit: the walk's
 * tie rule (distance, then the lower triangle) does not depend on it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "../../common/bvh.h"
#include "shared.h"

enum { MESH_TRIANGLE_TEXELS = 6 };
/* A mesh tree's leaf holds its triangle's corners, one texel each, in place of its box (bg_mesh.glsl):
 * the walk reads three texels at a leaf instead of the box's two and the triangle's three. */
enum { MESH_LEAF_TEXELS = 3 };
/* The most texels of each mesh texture. llvmpipe (Mesa 22.3) reads texels past the first 2^23 of
 * one RGBA32F texture wrongly, though they upload and read back intact (measured: a terrain of
 * 845,000 triangles, 8.45 million texels in one texture, lost its nearest rows; 720,000 rendered
 * right). Nodes and triangles therefore have a texture each (bg_mesh.glsl), which also keeps every
 * texel index a whole float. */
#define MESH_TEXTURE_TEXELS (1ull << 23)

/* Each mesh copy's triangles are preceded by its filter's record (bg_mesh.glsl, bg_mesh_keeps):
 * {flags, cut-off, coverage value, channel}, {first mask texel, mask width, mask height, nearest},
 * {uv scale u, v, clamp, open}; flags 1 front only, 4 cut-out, 8 a coverage texture;
 * open 1 for BG_SIDES_BOTH (bg_mesh_open), whose walk drops nothing. A
 * cut-out's texture follows the triangles as its coverage channel, four texels to an RGBA texel. */
enum { MESH_FILTER_TEXELS = 3 };

/* What object i's material lets through, as its copy's record holds it (the first mask texel left
 * 0) and the coverage texture (NULL: none). An object whose material filters nothing has an all-zero
 * record. */
typedef struct mesh_filter {
    float record[4 * MESH_FILTER_TEXELS];
    const bg_texture_data *mask;
} mesh_filter;

static void filter_of(const bg_scene_state *state, uint32_t i, mesh_filter *f)
{
    memset(f, 0, sizeof *f);
    const bg_object_data *o = &state->objects[i];
    const bg_material *m = &state->materials[o->material];
    bool cut = m->coverage_cutoff > 0.0;
    f->record[11] = m->sides == BG_SIDES_BOTH ? 1.0f : 0.0f;
    if (m->sides != BG_SIDES_FRONT && !cut)
        return;
    f->mask = cut && m->coverage.texture ? &state->textures[m->coverage.texture - 1] : NULL;
    f->record[0] = (float)((m->sides == BG_SIDES_FRONT ? 1 : 0) + (cut ? 4 : 0) + (f->mask ? 8 : 0));
    if (!cut)
        return;
    f->record[1] = (float)m->coverage_cutoff;
    f->record[2] = (float)m->coverage.value;
    f->record[3] = (float)(f->mask ? m->coverage.channel : 0);
    if (f->mask) {
        f->record[5] = (float)f->mask->width;
        f->record[6] = (float)f->mask->height;
        f->record[7] = f->mask->filter == BG_FILTER_NEAREST ? 1.0f : 0.0f;
        f->record[8] = (float)o->uv_scale[0];
        f->record[9] = (float)o->uv_scale[1];
        f->record[10] = f->mask->wrap == BG_WRAP_CLAMP ? 1.0f : 0.0f;
    }
}

/* Whether objects i and j can share one copy: the same mesh, filtered alike. */
static bool same_copy(const bg_scene_state *state, uint32_t i, uint32_t j)
{
    if (state->objects[i].mesh != state->objects[j].mesh)
        return false;
    mesh_filter a, b;
    filter_of(state, i, &a);
    filter_of(state, j, &b);
    return a.mask == b.mask && memcmp(a.record, b.record, sizeof a.record) == 0;
}

/* The RGBA texels of a copy's coverage mask. */
static uint64_t mask_texels(const mesh_filter *f)
{
    return f->mask ? ((uint64_t)f->mask->width * (uint64_t)f->mask->height + 3) / 4 : 0;
}

int bgi_gpu_meshes_filters(const bg_scene_state *state)
{
    int filters = 0;
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_object_data *o = &state->objects[i];
        const bg_material *m = &state->materials[o->material];
        if (!o->mesh)
            continue;
        filters |= m->sides == BG_SIDES_FRONT ? GPU_MESH_FRONT_ONLY : m->sides == BG_SIDES_BOTH ? GPU_MESH_OPEN : 0;
        filters |= m->coverage_cutoff > 0.0 ? GPU_MESH_CUT_OUT : 0;
    }
    return filters;
}

/* The texels the distinct meshes take in each mesh texture. */
typedef struct mesh_texels {
    uint64_t nodes; /* mesh_tree_texels of each tree */
    uint64_t tris;  /* MESH_TRIANGLE_TEXELS per triangle */
} mesh_texels;

/* For every object, the first object that shows the same mesh filtered alike (itself when it is the
 * first; the texture holds each such copy once, in the order of the objects that first show them;
 * most scenes filter nothing, and have one copy per mesh), found through a
 * hash of the mesh pointers: linear in the objects, which may be thousands of instances. NULL when
 * out of memory; the caller frees it. */
static uint32_t *mesh_firsts(const bg_allocator *a, const bg_scene_state *state)
{
    size_t room = 2;
    while (room < 2 * (size_t)state->mesh_object_count)
        room *= 2;
    uint32_t *first = bgi_alloc(a, ((size_t)state->object_count + 1) * sizeof *first);
    uint32_t *slot = bgi_alloc(a, room * sizeof *slot); /* an object index + 1, 0 empty */
    if (!first || !slot) {
        bgi_free(a, first);
        bgi_free(a, slot);
        return NULL;
    }
    memset(slot, 0, room * sizeof *slot);
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_mesh_data *m = state->objects[i].mesh;
        first[i] = i;
        if (!m)
            continue;
        size_t h = (size_t)(((uint64_t)(uintptr_t)m >> 4) * 0x9e3779b97f4a7c15ull >> 17) & (room - 1);
        while (slot[h] != 0 && !same_copy(state, slot[h] - 1, i))
            h = (h + 1) & (room - 1);
        if (slot[h] == 0)
            slot[h] = i + 1;
        else
            first[i] = slot[h] - 1;
    }
    bgi_free(a, slot);
    return first;
}

/* The texels of a mesh tree over `triangles` (> 0) triangles, one per leaf: GPU_NODE_TEXELS per interior
 * node, MESH_LEAF_TEXELS per leaf. Also the span of a subtree over that many triangles. */
static uint64_t mesh_tree_texels(uint64_t triangles)
{
    return (uint64_t)GPU_NODE_TEXELS * (triangles - 1) + (uint64_t)MESH_LEAF_TEXELS * triangles;
}

/* The texels every distinct mesh takes; also the texel bases of each mesh object into base when it
 * is not NULL (its mesh's root node in the node texture, its first triangle in the triangle texture). */
static mesh_texels mesh_layout(const bg_scene_state *state, const uint32_t *first, float *base)
{
    mesh_texels at = {0, 0};
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_mesh_data *m = state->objects[i].mesh;
        if (!m)
            continue;
        if (first[i] != i) {
            if (base) {
                base[2 * (size_t)i] = base[2 * (size_t)first[i]];
                base[2 * (size_t)i + 1] = base[2 * (size_t)first[i] + 1];
            }
            continue;
        }
        mesh_filter f;
        filter_of(state, i, &f);
        at.tris += MESH_FILTER_TEXELS;
        if (base) {
            base[2 * (size_t)i] = (float)at.nodes;
            base[2 * (size_t)i + 1] = (float)at.tris;
        }
        at.nodes += mesh_tree_texels(m->triangle_count);
        at.tris += (uint64_t)MESH_TRIANGLE_TEXELS * m->triangle_count + mask_texels(&f);
    }
    return at;
}

/* The texture's width: the widest power of two rows may have. */
static int mesh_width(int max_size)
{
    int cap = max_size < GPU_WIDEST_ROW ? max_size : GPU_WIDEST_ROW, w = 1;
    while (2 * w <= cap)
        w *= 2;
    return w;
}

bool bgi_gpu_meshes_fit(const bg_renderer *r, const bg_scene_state *state, char *why, size_t size)
{
    if (state->mesh_object_count == 0)
        return true;
    uint32_t *first = mesh_firsts(&r->allocator, state);
    if (!first) {
        snprintf(why, size, "out of memory ordering the %u mesh objects", state->mesh_object_count);
        return false;
    }
    mesh_texels texels = mesh_layout(state, first, NULL);
    bgi_free(&r->allocator, first);
    int w = mesh_width(r->limits.max_texture_size);
    uint64_t most = MESH_TEXTURE_TEXELS / (uint64_t)w;
    if (most > (uint64_t)r->limits.max_texture_size)
        most = (uint64_t)r->limits.max_texture_size;
    most *= (uint64_t)w;
    const char *what = texels.nodes > most ? "nodes of their trees" : "triangles";
    uint64_t need = texels.nodes > most ? texels.nodes : texels.tris;
    if (need > most) {
        snprintf(why, size, "the meshes' %s need %llu texels, more than the %llu of a mesh texture (at most %llu "
                 "texels, %d rows of %d)", what, (unsigned long long)need, (unsigned long long)most,
                 (unsigned long long)MESH_TEXTURE_TEXELS, r->limits.max_texture_size, w);
        return false;
    }
    return true;
}

/* The point a copy's tree is ordered for, named by a key, from the camera's eye in the object space
 * of the first object that shows the copy.
 * - An eye outside the mesh's box orders for its octant around the box's centre: a point far out
 *   along the octant's diagonal. Eight orders per mesh, which a camera orbiting the mesh changes at
 *   most every quarter turn. Measured by step counts (docs/benchmarks.md, "Mesh trees in view
 *   order"), the octant's order costs a camera ray 0-5 % more steps than one made for the exact eye,
 *   from any side; the exact eye's order would change at every move, and each change costs a pass
 *   over the tree and the node texture's upload (about 170 ms for 1.3 million triangles). An eye within
 *   ORDER_MARGIN of the box's extent of a plane through the centre keeps the side the held order has
 *   on that axis, so that a camera standing over the centre, as many do, does not flip the order at
 *   every small move.
 * - An eye inside the box (a walk through a building, a flight low over a terrain) orders for the
 *   centre of its cell on a grid of ORDER_CELLS cells across the box's largest extent: there the
 *   octant says little about which boxes are near.
 * An octant's key is 1 + 2 (x side) + 4 (y side) + 8 (z side), a side 1 for the positive one; a
 * cell's is a hash of its coordinates, even. */
enum { ORDER_CELLS = 16 };
#define ORDER_FAR 1024.0   /* the octant's point: this many extents from the centre along each axis */
#define ORDER_MARGIN 0.125 /* of the extent, around the centre's planes */

typedef struct mesh_frame {
    double eye[3], lo[3], hi[3], unit; /* unit: the largest extent, or 1 for a point */
    bool inside;
} mesh_frame;

static void frame_of(const bg_scene_state *state, uint32_t i, mesh_frame *f)
{
    const double *o = &state->camera.camera.position.x;
    const double(*m)[4] = state->objects[i].to_object;
    const bg_bvh *tree = &state->objects[i].mesh->tree;
    double extent = 0.0;
    f->inside = true;
    for (int r = 0; r < 3; r++) {
        f->eye[r] = m[r][0] * o[0] + m[r][1] * o[1] + m[r][2] * o[2] + m[r][3];
        f->lo[r] = tree->node_count > 0 ? tree->nodes[BG_BVH_NODE_MIN + r] : 0.0;
        f->hi[r] = tree->node_count > 0 ? tree->nodes[BG_BVH_NODE_MAX + r] : 0.0;
        extent = f->hi[r] - f->lo[r] > extent ? f->hi[r] - f->lo[r] : extent;
        f->inside = f->inside && f->eye[r] >= f->lo[r] && f->eye[r] <= f->hi[r];
    }
    f->unit = extent > 0.0 && extent < 1e300 ? extent : 1.0;
}

/* The key of copy i's order, given the key its texture holds (held; 0 none). */
static uint64_t order_key(const bg_scene_state *state, uint32_t i, uint64_t held)
{
    mesh_frame f;
    frame_of(state, i, &f);
    if (f.inside) {
        uint64_t h = 0x243f6a8885a308d3ull;
        for (int r = 0; r < 3; r++) {
            double c = floor(f.eye[r] / (f.unit / ORDER_CELLS));
            c = c < -1e15 ? -1e15 : (c > 1e15 ? 1e15 : c); /* a tiny mesh far out: one far cell */
            h = bgi_gpu_hash_mix(h, (uint64_t)(int64_t)c);
        }
        return h & ~(uint64_t)1;
    }
    uint64_t key = 1;
    for (int r = 0; r < 3; r++) {
        double centre = 0.5 * (f.lo[r] + f.hi[r]);
        bool positive = f.eye[r] >= centre;
        if ((held & 1) && held < 16 && fabs(f.eye[r] - centre) <= ORDER_MARGIN * f.unit)
            positive = (held >> (r + 1)) & 1;
        key |= positive ? (uint64_t)2 << r : 0;
    }
    return key;
}

/* The point copy i's order of key is made for. */
static void order_point(const bg_scene_state *state, uint32_t i, uint64_t key, double point[3])
{
    mesh_frame f;
    frame_of(state, i, &f);
    for (int r = 0; r < 3; r++) {
        if (key & 1) {
            double side = (key >> (r + 1)) & 1 ? 1.0 : -1.0;
            point[r] = 0.5 * (f.lo[r] + f.hi[r]) + side * ORDER_FAR * f.unit;
        } else {
            double cell = f.unit / ORDER_CELLS;
            point[r] = (floor(f.eye[r] / cell) + 0.5) * cell;
        }
    }
}

/* The most nodes of any distinct mesh's tree: the room the view orders need. */
static uint32_t most_nodes(const bg_scene_state *state, const uint32_t *first)
{
    uint32_t most = 0;
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_mesh_data *mesh = state->objects[i].mesh;
        if (mesh && first[i] == i && mesh->tree.node_count > most)
            most = mesh->tree.node_count;
    }
    return most;
}

/* Every distinct mesh once: its tree in common/bvh.h's pre-order, ordered for the camera, into
 * nodes, interior nodes as their two texels with the miss links turned into texel indices of the
 * node texture, each leaf as its triangle's corners {v0, triangle}, {v1, miss}, {v2, 0}; and its
 * triangles' attributes into tris (docs/gpu_pipeline.md, "Meshes"). A subtree over k triangles has
 * 2k - 1 nodes and takes mesh_tree_texels(k) texels, which turns a miss link's node span into a
 * texel span. Each tree goes in the order its copy's key in m->keys names (meshes_held writes the
 * keys first). With tris NULL only the trees. */
static bg_status fill_meshes(const bg_scene_state *state, const uint32_t *first, const gpu_meshes *m,
                             uint32_t *order, float *nodes, float *tris)
{
    uint32_t copy = 0;
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_mesh_data *mesh = state->objects[i].mesh;
        if (!mesh || first[i] != i)
            continue;
        double point[3];
        order_point(state, i, m->keys[GPU_MESH_KEYS * (size_t)copy++ + 2], point);
        bg_status st = bgi_bvh_view_order(&mesh->tree, point, order);
        if (st != BG_OK)
            return st;
        uint64_t at = (uint64_t)m->base[2 * (size_t)i];
        for (uint32_t p = 0; p < mesh->tree.node_count; p++) {
            uint32_t k = order[p];
            const float *node = mesh->tree.nodes + (size_t)k * BG_BVH_NODE_FLOATS;
            float *o = nodes + (size_t)at * 4;
            uint64_t span = (uint64_t)node[BG_BVH_NODE_MISS] - k; /* nodes in the subtree */
            uint64_t miss = at + mesh_tree_texels((span + 1) / 2);
            float prim = node[BG_BVH_NODE_PRIM];
            if (prim < 0.0f) {
                memcpy(o, node, BG_BVH_NODE_FLOATS * sizeof *o);
                o[BG_BVH_NODE_MISS] = (float)miss;
                at += GPU_NODE_TEXELS;
                continue;
            }
            const uint32_t *corner = mesh->indices + 3 * (size_t)prim;
            for (int c = 0; c < 3; c++)
                memcpy(o + 4 * c, &mesh->positions[3 * (size_t)corner[c]], 3 * sizeof *o);
            o[3] = prim;
            o[7] = (float)miss;
            o[11] = 0.0f;
            at += MESH_LEAF_TEXELS;
        }
        if (!tris)
            continue;
        float *o = tris + (size_t)m->base[2 * (size_t)i + 1] * 4;
        mesh_filter f;
        filter_of(state, i, &f);
        if (f.mask) {
            uint64_t first_mask = (uint64_t)m->base[2 * (size_t)i + 1] + (uint64_t)MESH_TRIANGLE_TEXELS * mesh->triangle_count;
            f.record[4] = (float)first_mask;
            int channel = (int)f.record[3];
            size_t n = (size_t)f.mask->width * (size_t)f.mask->height;
            float *mask = tris + (size_t)first_mask * 4;
            for (size_t k = 0; k < n; k++)
                mask[k] = (float)bgi_texture_channel(f.mask, k, channel);
        }
        memcpy(o - 4 * MESH_FILTER_TEXELS, f.record, sizeof f.record);
        for (uint32_t k = 0; k < mesh->triangle_count; k++) {
            for (int c = 0; c < 3; c++) {
                uint32_t v = mesh->indices[3 * (size_t)k + (size_t)c];
                float *p = o + 4 * c, *n = o + 12 + 4 * c;
                memcpy(p, &mesh->positions[3 * (size_t)v], 3 * sizeof *p);
                if (mesh->normals)
                    memcpy(n, &mesh->normals[3 * (size_t)v], 3 * sizeof *n);
                if (mesh->uvs) {
                    p[3] = mesh->uvs[2 * (size_t)v];
                    n[3] = mesh->uvs[2 * (size_t)v + 1];
                }
            }
            o += MESH_TRIANGLE_TEXELS * 4;
        }
    }
    return BG_OK;
}

/* A copy's filter as a number: its record and, for a cut-out with a texture, every coverage value
 * it reads (a texture's handle may name other texels after a remove and an add). 0 without one. */
static uint64_t filter_key(const bg_scene_state *state, uint32_t i)
{
    mesh_filter f;
    filter_of(state, i, &f);
    if (f.record[0] == 0.0f && f.record[11] == 0.0f)
        return 0;
    uint64_t h = 0x13198a2e03707344ull;
    for (int k = 0; k < 4 * MESH_FILTER_TEXELS; k++) {
        uint32_t bits;
        memcpy(&bits, &f.record[k], sizeof bits);
        h = bgi_gpu_hash_mix(h, bits);
    }
    if (f.mask) {
        size_t n = (size_t)f.mask->width * (size_t)f.mask->height;
        int channel = (int)f.record[3];
        for (size_t k = 0; k < n; k++) {
            uint32_t bits;
            float value = (float)bgi_texture_channel(f.mask, k, channel);
            memcpy(&bits, &value, sizeof bits);
            h = bgi_gpu_hash_mix(h, bits);
        }
    }
    return h;
}

/* Whether the mesh textures already hold the scene's distinct copies in their order (a mesh's
 * serial names its contents for good, and a copy is also keyed by its filter and by the octant or
 * cell its tree is ordered for, so a commit that moves the camera or objects within them keeps the
 * textures, and the ten million texels of a million triangles need neither a rebuild nor a
 * comparison); otherwise records them as what they are about to hold. *orders_only: only some order
 * changed. */
static bg_status meshes_held(bg_renderer *r, gpu_meshes *m, const bg_scene_state *state, const uint32_t *first,
                             bool *held, bool *orders_only)
{
    enum { KEYS = GPU_MESH_KEYS };
    uint32_t n = 0;
    for (uint32_t i = 0; i < state->object_count; i++)
        n += state->objects[i].mesh && first[i] == i ? 1 : 0;
    uint64_t *views = bgi_alloc(&r->allocator, (size_t)n * sizeof *views);
    if (!views)
        return BG_ERR_OUT_OF_MEMORY;
    for (uint32_t i = 0, k = 0; i < state->object_count; i++)
        if (state->objects[i].mesh && first[i] == i) {
            bool same_copy = m->keys && k < m->key_count && m->keys[KEYS * k] == state->objects[i].mesh->serial;
            views[k] = order_key(state, i, same_copy ? m->keys[KEYS * k + 2] : 0);
            k++;
        }
    bool same = m->nodes && m->keys && n == m->key_count, same_orders = same;
    for (uint32_t i = 0, k = 0; i < state->object_count && same; i++)
        if (state->objects[i].mesh && first[i] == i) {
            same = m->keys[KEYS * k] == state->objects[i].mesh->serial && m->keys[KEYS * k + 1] == filter_key(state, i);
            same_orders = same_orders && m->keys[KEYS * k + 2] == views[k];
            k++;
        }
    *orders_only = same && !same_orders;
    same = same && same_orders;
    *held = same;
    if (!same && m->key_room < n) {
        bgi_free(&r->allocator, m->keys);
        m->key_room = 0;
        m->keys = bgi_alloc(&r->allocator, KEYS * (size_t)n * sizeof *m->keys);
        if (m->keys)
            m->key_room = n;
    }
    if (!same && m->keys) {
        m->key_count = 0;
        for (uint32_t i = 0; i < state->object_count; i++)
            if (state->objects[i].mesh && first[i] == i) {
                uint64_t *key = m->keys + KEYS * (size_t)m->key_count;
                key[0] = state->objects[i].mesh->serial;
                key[1] = filter_key(state, i);
                key[2] = views[m->key_count];
                m->key_count++;
            }
    }
    bgi_free(&r->allocator, views);
    return same || m->keys ? BG_OK : BG_ERR_OUT_OF_MEMORY;
}

/* Makes a mesh texture w x h hold `data` (h rows of w texels); w is the same for every scene on a
 * GL, so only another height makes a new texture. */
static bg_status mesh_texture_upload(bg_renderer *r, macs_texture **t, int w, int h, const float *data)
{
    int have_w = 0, have_h = 0;
    macs_texture_size(*t, &have_w, &have_h);
    if (have_w != w || have_h != h) {
        macs_texture_destroy(*t);
        *t = NULL;
    }
    bg_status st = bgi_gpu_texture_ensure(r, w, h, MACS_FORMAT_RGBA32F, t, "mesh texture");
    if (st != BG_OK)
        return st;
    macs_status ms = macs_texture_upload(*t, data, 0);
    return ms ? bgi_gpu_fail_macs(r, ms, "mesh texture") : BG_OK;
}

/* Every distinct mesh into the mesh textures, first[] the objects' first-of-mesh indices. The host
 * copy lives only while it goes up: the textures' keys say what they hold. */
static bg_status meshes_upload(bg_renderer *r, gpu_meshes *m, const bg_scene_state *state, const uint32_t *first)
{
    mesh_texels texels = mesh_layout(state, first, m->base);
    int w = mesh_width(r->limits.max_texture_size);
    int h_nodes = (int)((texels.nodes + (uint64_t)w - 1) / (uint64_t)w);
    int h_tris = (int)((texels.tris + (uint64_t)w - 1) / (uint64_t)w);
    m->dims[0] = (float)w;
    m->dims[1] = 1.0f / (float)w;
    m->dims[2] = 1.0f / (float)h_tris;
    m->dims[3] = 1.0f / (float)h_nodes;
    bool held = false, orders_only = false;
    bg_status st = meshes_held(r, m, state, first, &held, &orders_only);
    if (st != BG_OK || held)
        return st == BG_OK ? BG_OK : bgi_gpu_fail(r, st, "out of memory for the mesh textures' keys");
    uint32_t nodes = most_nodes(state, first);
    uint32_t *order = bgi_alloc(&r->allocator, (size_t)(nodes ? nodes : 1) * sizeof *order);
    if (!order)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory ordering a mesh tree of %u nodes", nodes);
    /* Only the trees' order changed (the camera moved): the node texture is written in place, the
     * same texture of the same size, so the passes that bound it still bind it (uploads stays). */
    size_t node_floats = (size_t)w * (size_t)h_nodes * 4;
    size_t floats = node_floats + (orders_only ? 0 : (size_t)w * (size_t)h_tris * 4);
    float *data = bgi_alloc(&r->allocator, floats * sizeof *data);
    if (!data) {
        m->key_count = 0;
        bgi_free(&r->allocator, order);
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the mesh textures (%zu floats)",
                            floats);
    }
    memset(data, 0, floats * sizeof *data);
    st = fill_meshes(state, first, m, order, data, orders_only ? NULL : data + node_floats);
    bgi_free(&r->allocator, order);
    if (st != BG_OK) {
        m->key_count = 0;
        bgi_free(&r->allocator, data);
        return bgi_gpu_fail(r, st, "out of memory ordering the mesh trees");
    }
    macs_texture *held_nodes = m->nodes;
    st = mesh_texture_upload(r, &m->nodes, w, h_nodes, data);
    if (!orders_only || m->nodes != held_nodes)
        m->uploads++;
    if (st == BG_OK && !orders_only)
        st = mesh_texture_upload(r, &m->triangles, w, h_tris, data + node_floats);
    bgi_free(&r->allocator, data);
    if (st != BG_OK)
        m->key_count = 0; /* they may hold anything now */
    return st;
}

/* The textures go with the last mesh: a scene without meshes keeps no mesh data on the GPU. */
static void textures_release(gpu_meshes *m)
{
    if (m->nodes || m->triangles)
        m->uploads++;
    macs_texture_destroy(m->nodes);
    macs_texture_destroy(m->triangles);
    m->nodes = m->triangles = NULL;
    m->key_count = 0;
    memset(m->dims, 0, sizeof m->dims);
}

bg_status bgi_gpu_meshes_prepare(bg_renderer *r, const bg_scene_state *state)
{
    gpu_meshes *m = &r->meshes;
    if (m->serial != 0 && m->serial == state->serial)
        return BG_OK; /* the same commit: the textures and bases hold it */
    m->serial = 0;
    if (state->mesh_object_count == 0) {
        textures_release(m);
        m->serial = state->serial;
        return BG_OK;
    }
    if (m->base_count < state->object_count) {
        bgi_free(&r->allocator, m->base);
        m->base_count = 0;
        m->base = bgi_alloc(&r->allocator, 2 * (size_t)state->object_count * sizeof *m->base);
        if (!m->base)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the mesh texture's bases");
        m->base_count = state->object_count;
    }
    uint32_t *first = mesh_firsts(&r->allocator, state);
    if (!first)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory ordering the meshes");
    bg_status st = meshes_upload(r, m, state, first);
    bgi_free(&r->allocator, first);
    if (st == BG_OK)
        m->serial = state->serial;
    return st;
}

void bgi_gpu_meshes_release(bg_renderer *r)
{
    gpu_meshes *m = &r->meshes;
    textures_release(m);
    bgi_free(&r->allocator, m->base);
    bgi_free(&r->allocator, m->keys);
    uint64_t uploads = m->uploads;
    memset(m, 0, sizeof *m);
    m->uploads = uploads;
}
