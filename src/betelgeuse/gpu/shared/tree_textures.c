/* The object tree's textures (the fused plan's tree variant, BG_PLAN_FUSED_TREE, walks them) and
 * the meshes' (every plan walks them).
 *
 * The scene's object tree (common/bvh.h) goes to the GPU as it is, seen from the camera: the GPU's
 * frame is camera-relative (origin.c), so each frame's nodes are the tree's boxes minus the eye,
 * rounded outward again and ordered near to far (bgi_bvh_view_nodes), with each leaf naming its object. Each object's
 * transforms and kinds go in a second texture, indexed by object (bg_tree_textures.glsl gives both
 * layouts). A frame of the commit they hold touches neither; after another commit both are rebuilt
 * on the host and uploaded only where they differ from what the textures hold, so a commit that
 * changes nothing the tree holds (a material value, a light) uploads nothing but uniforms.
 *
 * A scene with meshes has two more textures on the same rule: every distinct mesh's own tree in
 * one, its triangles in the other, each addressed by texel index (bg_mesh.glsl gives the layout),
 * which each mesh object's texel 4 points into; mesh_source.c walks them.
 *
 * The shader's walks share one step count per pixel, what llvmpipe's loop limit leaves them; a
 * pixel that runs out (a ray through thousands of overlapping boxes) is marked with alpha 0 and
 * rendered by the CPU reference, pixel by pixel, on the same tree: never cut short silently
 * (fallback.c). */
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "../../common/bvh.h"
#include "shared.h"

enum { NODE_TEXELS = 2, OBJECT_TEXELS = 8, WIDEST_ROW = 4096, MESH_TRIANGLE_TEXELS = 6 };
/* A mesh tree's leaf holds its triangle's corners, one texel each, in place of its box (bg_mesh.glsl):
 * the walk reads three texels at a leaf instead of the box's two and the triangle's three. */
enum { MESH_LEAF_TEXELS = 3 };
/* The most texels of each mesh texture. llvmpipe (Mesa 22.3) reads texels past the first 2^23 of
 * one RGBA32F texture wrongly, though they upload and read back intact (measured: a terrain of
 * 845,000 triangles, 8.45 million texels in one texture, lost its nearest rows; 720,000 rendered
 * right). Nodes and triangles therefore have a texture each (bg_mesh.glsl), which also keeps every
 * texel index a whole float. */
#define MESH_TEXTURE_TEXELS (1ull << 23)

/* Items per row (a power of two), width and height of a texture of `items` items of `per` texels
 * within max_size; false when even the widest rows need more than max_size of them. */
static bool geometry(int max_size, uint32_t items, int per, int *per_row, int *width, int *height)
{
    int cap = max_size < WIDEST_ROW ? max_size : WIDEST_ROW;
    int k = 1;
    while (2 * k * per <= cap && (uint32_t)k < items)
        k *= 2;
    uint64_t rows = items ? ((uint64_t)items + (uint64_t)k - 1) / (uint64_t)k : 1;
    *per_row = k;
    *width = k * per;
    *height = (int)(rows < (uint64_t)max_size ? rows : (uint64_t)max_size);
    return rows <= (uint64_t)max_size;
}

bool bgi_gpu_tree_textures_fit(const bg_renderer *r, const bg_scene_state *state, char *why, size_t size)
{
    int k, w, h;
    uint32_t nodes = state->tree ? state->tree->node_count : 0;
    if (!geometry(r->limits.max_texture_size, nodes, NODE_TEXELS, &k, &w, &h)) {
        snprintf(why, size, "the object tree's %u nodes need more than %d rows of a %d-texel texture", nodes,
                 r->limits.max_texture_size, w);
        return false;
    }
    if (!geometry(r->limits.max_texture_size, state->object_count, OBJECT_TEXELS, &k, &w, &h)) {
        snprintf(why, size, "the %u objects need more than %d rows of a %d-texel texture", state->object_count,
                 r->limits.max_texture_size, w);
        return false;
    }
    return bgi_gpu_meshes_fit(r, state, why, size);
}

/* ---- the host copies ---- */

static bg_status fill_nodes(const bg_scene_state *state, const gpu_tree_textures *t, float *out)
{
    (void)t;
    const bg_vec3 *eye = &state->camera.camera.position;
    double origin[3] = {eye->x, eye->y, eye->z};
    return state->tree ? bgi_bvh_view_nodes(state->tree, origin, state->tree_objects, out) : BG_OK;
}

/* Object i's texels, as bg_tree_textures.glsl reads them. */
static void fill_object(const bg_scene_state *state, const gpu_tree_textures *t, uint32_t i, float *o)
{
    const bg_object_data *obj = &state->objects[i];
    float m16[16];
    bgi_gpu_origin_to_object(state, i, m16); /* column-major */
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            o[4 * r + c] = m16[c * 4 + r];
    o[12] = (float)obj->shape;
    o[13] = (float)obj->material;
    o[14] = (float)obj->uv_mapping;
    o[15] = obj->casts_shadows ? 1.0f : 0.0f;
    o[16] = (float)obj->uv_scale[0];
    o[17] = (float)obj->uv_scale[1];
    if (obj->mesh) {
        o[18] = t->mesh_base[2 * (size_t)i];
        o[19] = t->mesh_base[2 * (size_t)i + 1];
    }
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++)
            o[20 + 4 * r + c] = (float)obj->to_world[r][c];
        o[23 + 4 * r] = 0.0f;
    }
}

static bg_status fill_objects(const bg_scene_state *state, const gpu_tree_textures *t, float *out)
{
    for (uint32_t i = 0; i < state->object_count; i++)
        fill_object(state, t, i, out + (size_t)i * OBJECT_TEXELS * 4);
    return BG_OK;
}

/* ---- one texture ---- */

/* Makes *texture hold what fill writes for a width x height texture, uploading only a change. */
static bg_status texture_prepare(bg_renderer *r, const gpu_tree_textures *tree, gpu_held_texture *t,
                                 const bg_scene_state *state, int width, int height,
                                 bg_status (*fill)(const bg_scene_state *, const gpu_tree_textures *, float *),
                                 const char *what)
{
    size_t floats = (size_t)width * (size_t)height * 4;
    if (t->floats != floats || !t->held || !t->scratch) {
        macs_texture_destroy(t->texture);
        bgi_free(&r->allocator, t->held);
        bgi_free(&r->allocator, t->scratch);
        memset(t, 0, sizeof *t);
        t->held = bgi_alloc(&r->allocator, floats * sizeof(float));
        t->scratch = bgi_alloc(&r->allocator, floats * sizeof(float));
        if (!t->held || !t->scratch)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the %s (%zu floats)", what,
                            floats);
        t->floats = floats;
    }
    memset(t->scratch, 0, floats * sizeof(float));
    if (fill(state, tree, t->scratch) != BG_OK)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory ordering the %s", what);
    if (t->texture && memcmp(t->scratch, t->held, floats * sizeof(float)) == 0)
        return BG_OK;
    macs_status ms = MACS_OK;
    if (!t->texture) {
        bg_status st = bgi_gpu_texture_ensure(r, width, height, MACS_FORMAT_RGBA32F, &t->texture, what);
        if (st != BG_OK)
            return st;
    }
    ms = macs_texture_upload(t->texture, t->scratch, 0);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, what);
    float *swap = t->held;
    t->held = t->scratch;
    t->scratch = swap;
    return BG_OK;
}

static void texture_release(const bg_allocator *a, gpu_held_texture *t)
{
    macs_texture_destroy(t->texture);
    bgi_free(a, t->held);
    bgi_free(a, t->scratch);
    memset(t, 0, sizeof *t);
}

static void set_dims(float dims[4], int per_row, int width, int height)
{
    dims[0] = (float)per_row;
    dims[1] = 1.0f / (float)per_row;
    dims[2] = 1.0f / (float)width;
    dims[3] = 1.0f / (float)height;
}

/* ---- the meshes' texture ---- */

/* The texels the distinct meshes take in each mesh texture. */
typedef struct mesh_texels {
    uint64_t nodes; /* mesh_tree_texels of each tree */
    uint64_t tris;  /* MESH_TRIANGLE_TEXELS per triangle */
} mesh_texels;

/* For every object, the first object that shows the same mesh (itself when it is the first; the
 * texture holds each mesh once, in the order of the objects that first show them), found through a
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
        while (slot[h] != 0 && state->objects[slot[h] - 1].mesh != m)
            h = (h + 1) & (room - 1);
        if (slot[h] == 0)
            slot[h] = i + 1;
        else
            first[i] = slot[h] - 1;
    }
    bgi_free(a, slot);
    return first;
}

/* The texels of a mesh tree over `triangles` (> 0) triangles, one per leaf: NODE_TEXELS per interior
 * node, MESH_LEAF_TEXELS per leaf. Also the span of a subtree over that many triangles. */
static uint64_t mesh_tree_texels(uint64_t triangles)
{
    return (uint64_t)NODE_TEXELS * (triangles - 1) + (uint64_t)MESH_LEAF_TEXELS * triangles;
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
        if (base) {
            base[2 * (size_t)i] = (float)at.nodes;
            base[2 * (size_t)i + 1] = (float)at.tris;
        }
        at.nodes += mesh_tree_texels(m->triangle_count);
        at.tris += (uint64_t)MESH_TRIANGLE_TEXELS * m->triangle_count;
    }
    return at;
}

/* The texture's width: the widest power of two rows may have. */
static int mesh_width(int max_size)
{
    int cap = max_size < WIDEST_ROW ? max_size : WIDEST_ROW, w = 1;
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

/* Every distinct mesh once: its tree in common/bvh.h's pre-order into nodes, interior nodes as
 * their two texels with the miss links turned into texel indices of the node texture, each leaf as
 * its triangle's corners {v0, triangle}, {v1, miss}, {v2, 0}; and its triangles' attributes into tris
 * (docs/gpu_pipeline.md, "Meshes"). A subtree over k triangles has 2k - 1 nodes and takes
 * mesh_tree_texels(k) texels, which turns a miss link's node span into a texel span. */
static void fill_meshes(const bg_scene_state *state, const uint32_t *first, const gpu_tree_textures *t, float *nodes,
                        float *tris)
{
    for (uint32_t i = 0; i < state->object_count; i++) {
        const bg_mesh_data *m = state->objects[i].mesh;
        if (!m || first[i] != i)
            continue;
        uint64_t at = (uint64_t)t->mesh_base[2 * (size_t)i];
        for (uint32_t k = 0; k < m->tree.node_count; k++) {
            const float *node = m->tree.nodes + (size_t)k * BG_BVH_NODE_FLOATS;
            float *o = nodes + (size_t)at * 4;
            uint64_t span = (uint64_t)node[BG_BVH_NODE_MISS] - k; /* nodes in the subtree */
            uint64_t miss = at + mesh_tree_texels((span + 1) / 2);
            float prim = node[BG_BVH_NODE_PRIM];
            if (prim < 0.0f) {
                memcpy(o, node, BG_BVH_NODE_FLOATS * sizeof *o);
                o[BG_BVH_NODE_MISS] = (float)miss;
                at += NODE_TEXELS;
                continue;
            }
            const uint32_t *corner = m->indices + 3 * (size_t)prim;
            for (int c = 0; c < 3; c++)
                memcpy(o + 4 * c, &m->positions[3 * (size_t)corner[c]], 3 * sizeof *o);
            o[3] = prim;
            o[7] = (float)miss;
            o[11] = 0.0f;
            at += MESH_LEAF_TEXELS;
        }
        float *o = tris + (size_t)t->mesh_base[2 * (size_t)i + 1] * 4;
        for (uint32_t k = 0; k < m->triangle_count; k++) {
            for (int c = 0; c < 3; c++) {
                uint32_t v = m->indices[3 * (size_t)k + (size_t)c];
                float *p = o + 4 * c, *n = o + 12 + 4 * c;
                memcpy(p, &m->positions[3 * (size_t)v], 3 * sizeof *p);
                if (m->normals)
                    memcpy(n, &m->normals[3 * (size_t)v], 3 * sizeof *n);
                if (m->uvs) {
                    p[3] = m->uvs[2 * (size_t)v];
                    n[3] = m->uvs[2 * (size_t)v + 1];
                }
            }
            o += MESH_TRIANGLE_TEXELS * 4;
        }
    }
}

/* Whether the mesh textures already hold the scene's distinct meshes in their order (a mesh's
 * serial names its contents for good, so a commit that only moves the camera or objects keeps them,
 * and the ten million texels of a million triangles need neither a rebuild nor a comparison);
 * otherwise records them as what they are about to hold. False when out of memory for the record. */
static bool meshes_held(bg_renderer *r, gpu_tree_textures *t, const bg_scene_state *state, const uint32_t *first,
                        bool *held)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < state->object_count; i++)
        n += state->objects[i].mesh && first[i] == i ? 1 : 0;
    bool same = t->mesh_nodes.texture && t->mesh_keys && n == t->mesh_key_count;
    for (uint32_t i = 0, k = 0; i < state->object_count && same; i++)
        if (state->objects[i].mesh && first[i] == i)
            same = t->mesh_keys[k++] == state->objects[i].mesh->serial;
    *held = same;
    if (same)
        return true;
    if (t->mesh_key_room < n) {
        bgi_free(&r->allocator, t->mesh_keys);
        t->mesh_key_room = 0;
        t->mesh_keys = bgi_alloc(&r->allocator, (size_t)n * sizeof *t->mesh_keys);
        if (!t->mesh_keys)
            return false;
        t->mesh_key_room = n;
    }
    t->mesh_key_count = 0;
    for (uint32_t i = 0; i < state->object_count; i++)
        if (state->objects[i].mesh && first[i] == i)
            t->mesh_keys[t->mesh_key_count++] = state->objects[i].mesh->serial;
    return true;
}

/* Makes a mesh texture w x h hold `data` (h rows of w texels). */
static bg_status mesh_texture_upload(bg_renderer *r, gpu_held_texture *t, int w, int h, const float *data)
{
    size_t floats = (size_t)w * (size_t)h * 4;
    if (t->floats != floats) {
        macs_texture_destroy(t->texture);
        t->texture = NULL;
        t->floats = 0;
    }
    bg_status st = bgi_gpu_texture_ensure(r, w, h, MACS_FORMAT_RGBA32F, &t->texture, "mesh texture");
    if (st != BG_OK)
        return st;
    t->floats = floats;
    macs_status ms = macs_texture_upload(t->texture, data, 0);
    return ms ? bgi_gpu_fail_macs(r, ms, "mesh texture") : BG_OK;
}

/* Every distinct mesh into the mesh textures, first[] the objects' first-of-mesh indices. The host
 * copy lives only while it goes up: the textures' keys say what they hold. */
static bg_status meshes_upload(bg_renderer *r, gpu_tree_textures *t, const bg_scene_state *state, const uint32_t *first)
{
    mesh_texels texels = mesh_layout(state, first, t->mesh_base);
    int w = mesh_width(r->limits.max_texture_size);
    int h_nodes = (int)((texels.nodes + (uint64_t)w - 1) / (uint64_t)w);
    int h_tris = (int)((texels.tris + (uint64_t)w - 1) / (uint64_t)w);
    t->dims.meshes[0] = (float)w;
    t->dims.meshes[1] = 1.0f / (float)w;
    t->dims.meshes[2] = 1.0f / (float)h_tris;
    t->dims.meshes[3] = 1.0f / (float)h_nodes;
    bool held = false;
    if (!meshes_held(r, t, state, first, &held))
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the mesh textures' keys");
    if (held)
        return BG_OK;
    size_t node_floats = (size_t)w * (size_t)h_nodes * 4, floats = node_floats + (size_t)w * (size_t)h_tris * 4;
    float *data = bgi_alloc(&r->allocator, floats * sizeof *data);
    if (!data) {
        t->mesh_key_count = 0;
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the mesh textures (%zu floats)",
                            floats);
    }
    memset(data, 0, floats * sizeof *data);
    fill_meshes(state, first, t, data, data + node_floats);
    bg_status st = mesh_texture_upload(r, &t->mesh_nodes, w, h_nodes, data);
    if (st == BG_OK)
        st = mesh_texture_upload(r, &t->mesh_tris, w, h_tris, data + node_floats);
    bgi_free(&r->allocator, data);
    if (st != BG_OK)
        t->mesh_key_count = 0; /* they may hold anything now */
    return st;
}

/* The mesh textures and every mesh object's bases for the committed scene. */
static bg_status meshes_prepare(bg_renderer *r, gpu_tree_textures *t, const bg_scene_state *state)
{
    if (state->mesh_object_count == 0) {
        texture_release(&r->allocator, &t->mesh_nodes);
        texture_release(&r->allocator, &t->mesh_tris);
        t->mesh_key_count = 0;
        memset(t->dims.meshes, 0, sizeof t->dims.meshes);
        return BG_OK;
    }
    if (t->mesh_base_count < state->object_count) {
        bgi_free(&r->allocator, t->mesh_base);
        t->mesh_base_count = 0;
        t->mesh_base = bgi_alloc(&r->allocator, 2 * (size_t)state->object_count * sizeof *t->mesh_base);
        if (!t->mesh_base)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the mesh texture's bases");
        t->mesh_base_count = state->object_count;
    }
    uint32_t *first = mesh_firsts(&r->allocator, state);
    if (!first)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory ordering the meshes");
    bg_status st = meshes_upload(r, t, state, first);
    bgi_free(&r->allocator, first);
    return st;
}

bg_status bgi_gpu_tree_textures_prepare(bg_renderer *r, gpu_tree_textures *t, const bg_scene_state *state, bool walks)
{
    if (t->serial != 0 && t->serial == state->serial && t->walks == walks)
        return BG_OK; /* the same commit: the textures hold it, nothing to build or compare */
    t->serial = 0;
    if (!walks) {
        bg_status st = meshes_prepare(r, t, state);
        if (st == BG_OK) {
            t->serial = state->serial;
            t->walks = false;
        }
        return st;
    }
    uint32_t nodes = state->tree ? state->tree->node_count : 0;
    int k, w, h;
    geometry(r->limits.max_texture_size, nodes, NODE_TEXELS, &k, &w, &h);
    set_dims(t->dims.nodes, k, w, h);
    t->dims.node_count = (float)nodes;
    bg_status st = texture_prepare(r, t, &t->nodes, state, w, h, fill_nodes, "object tree texture");
    if (st == BG_OK)
        st = meshes_prepare(r, t, state);
    if (st != BG_OK)
        return st;
    geometry(r->limits.max_texture_size, state->object_count, OBJECT_TEXELS, &k, &w, &h);
    set_dims(t->dims.objects, k, w, h);
    st = texture_prepare(r, t, &t->objects, state, w, h, fill_objects, "tree objects texture");
    if (st == BG_OK) {
        t->serial = state->serial;
        t->walks = true;
    }
    return st;
}

void bgi_gpu_tree_textures_release(const bg_allocator *a, gpu_tree_textures *t)
{
    texture_release(a, &t->nodes);
    texture_release(a, &t->objects);
    texture_release(a, &t->mesh_nodes);
    texture_release(a, &t->mesh_tris);
    bgi_free(a, t->mesh_base);
    t->mesh_base = NULL;
    t->mesh_base_count = 0;
    bgi_free(a, t->mesh_keys);
    t->mesh_keys = NULL;
    t->mesh_key_count = t->mesh_key_room = 0;
    bgi_gpu_marks_release(t);
    memset(&t->dims, 0, sizeof t->dims);
    t->serial = 0;
}
