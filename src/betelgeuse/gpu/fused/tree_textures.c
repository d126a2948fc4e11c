/* The object tree's textures, which the fused plan's tree variant (BG_PLAN_FUSED_TREE) walks.
 *
 * The scene's object tree (common/bvh.h) goes to the GPU as it is, seen from the camera: the GPU's
 * frame is camera-relative (origin.c), so each frame's nodes are the tree's boxes minus the eye,
 * rounded outward again and ordered near to far (bgi_bvh_view_nodes), with each leaf naming its object. Each object's
 * transforms and kinds go in a second texture, indexed by object (bg_tree_textures.glsl gives both
 * layouts), a mesh object's with the texels its mesh starts at in the meshes' textures
 * (shared/meshes.c). A frame of the commit they hold touches neither; after another commit both are
 * rebuilt on the host and uploaded only where they differ from what the textures hold, so a commit
 * that changes nothing the tree holds (a material value, a light) uploads nothing but uniforms.
 *
 * The shader's walks share one step count per pixel, what llvmpipe's loop limit leaves them; a
 * pixel that runs out (a ray through thousands of overlapping boxes) is marked with alpha 0 and
 * rendered by the CPU reference, pixel by pixel, on the same tree: never cut short silently
 * (shared/fallback.c). */
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "../../common/bvh.h"
#include "fused.h"

enum { OBJECT_TEXELS = 8 };

/* Items per row (a power of two), width and height of a texture of `items` items of `per` texels
 * within max_size; false when even the widest rows need more than max_size of them. */
static bool geometry(int max_size, uint32_t items, int per, int *per_row, int *width, int *height)
{
    int cap = max_size < GPU_WIDEST_ROW ? max_size : GPU_WIDEST_ROW;
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
    if (!geometry(r->limits.max_texture_size, nodes, GPU_NODE_TEXELS, &k, &w, &h)) {
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

static bg_status fill_nodes(const bg_scene_state *state, const gpu_meshes *m, float *out)
{
    (void)m;
    const bg_vec3 *eye = &state->camera.camera.position;
    double origin[3] = {eye->x, eye->y, eye->z};
    return state->tree ? bgi_bvh_view_nodes(state->tree, origin, state->tree_objects, out) : BG_OK;
}

/* Object i's texels, as bg_tree_textures.glsl reads them. */
static void fill_object(const bg_scene_state *state, const gpu_meshes *m, uint32_t i, float *o)
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
        o[18] = m->base[2 * (size_t)i];
        o[19] = m->base[2 * (size_t)i + 1];
    }
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++)
            o[20 + 4 * r + c] = (float)obj->to_world[r][c];
        o[23 + 4 * r] = 0.0f;
    }
}

static bg_status fill_objects(const bg_scene_state *state, const gpu_meshes *m, float *out)
{
    for (uint32_t i = 0; i < state->object_count; i++)
        fill_object(state, m, i, out + (size_t)i * OBJECT_TEXELS * 4);
    return BG_OK;
}

/* ---- one texture ---- */

/* Makes *texture hold what fill writes for a width x height texture, uploading only a change. */
static bg_status texture_prepare(bg_renderer *r, gpu_held_texture *t,
                                 const bg_scene_state *state, int width, int height,
                                 bg_status (*fill)(const bg_scene_state *, const gpu_meshes *, float *),
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
    if (fill(state, &r->meshes, t->scratch) != BG_OK)
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

bg_status bgi_gpu_tree_textures_prepare(bg_renderer *r, gpu_tree_textures *t, const bg_scene_state *state)
{
    if (t->serial != 0 && t->serial == state->serial)
        return BG_OK; /* the same commit: the textures hold it, nothing to build or compare */
    t->serial = 0;
    uint32_t nodes = state->tree ? state->tree->node_count : 0;
    int k, w, h;
    geometry(r->limits.max_texture_size, nodes, GPU_NODE_TEXELS, &k, &w, &h);
    set_dims(t->dims.nodes, k, w, h);
    t->dims.node_count = (float)nodes;
    bg_status st = texture_prepare(r, &t->nodes, state, w, h, fill_nodes, "object tree texture");
    if (st != BG_OK)
        return st;
    geometry(r->limits.max_texture_size, state->object_count, OBJECT_TEXELS, &k, &w, &h);
    set_dims(t->dims.objects, k, w, h);
    st = texture_prepare(r, &t->objects, state, w, h, fill_objects, "tree objects texture");
    if (st == BG_OK)
        t->serial = state->serial;
    return st;
}

void bgi_gpu_tree_textures_release(const bg_allocator *a, gpu_tree_textures *t)
{
    texture_release(a, &t->nodes);
    texture_release(a, &t->objects);
    memset(&t->dims, 0, sizeof t->dims);
    t->serial = 0;
}
