/* Primary visibility by rasterisation (docs/gpu_pipeline.md): before the fused pass, the tree
 * objects' footprints are drawn into a map of the output's size, each fragment running the object's
 * exact test on its pixel's camera ray (primary_source.c) and writing the distance as depth, the
 * paper's intersection pass with the nearest kept by the depth test. The fused program then reads,
 * per pixel, which tree object (and triangle) its camera ray meets first and tests only that one,
 * where the walk would have visited the tree's boxes on the way.
 *
 * Footprints: an analytic object's world box (12 triangles, corners rounded outward to float), a
 * mesh object's triangles, each drawn solid, then as edges and corners two pixels wide: the rasteriser
 * decides nothing, it only has to reach every pixel whose centre the exact test may hit, which the
 * fill rule alone does not promise for a centre on an edge, or after the float rounding of a corner.
 *
 * Two draws of the same footprints: the first keeps each pixel's nearest depth, the second, with
 * depth test LEQUAL against it and its own depth scaled by 1 - 2^-16, blends (object, -object,
 * triangle, -triangle) by GL_MAX over every fragment within that margin of the nearest. One object
 * and triangle is left where R = -G and B = -A; anything else is a tie (two triangles of an edge, two
 * objects at one distance, or merely within rounding of each other, where two programs' floats might
 * order them differently), and that pixel's camera ray walks the tree as before. The map starts as
 * (-1, -1e30, -2, -1e30): no tree object on the ray. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "fused.h"

/* A footprint vertex: its triangle's three corners (object space for a mesh, camera-relative for a
 * box), then (object, triangle, which corner): every vertex of a triangle computes the same footprint
 * (bg_primary_cover.glsl). */
enum { FLOATS = 12, BOX_VERTICES = 36 };
/* The second draw's margin: fragments within this fraction of the nearest distance tie with it. */
#define TIE_SCALE (1.0f - 1.0f / 65536.0f)
/* BG_PRIMARY_AUTO rasterises a scene whose tree holds a mesh, when the footprints have at most one
 * triangle per this many pixels: every triangle costs a vertex shader run per corner in both draws,
 * seen or not, where a camera ray's walk through a mesh costs the two trees' steps. Measured
 * (bench_primary, llvmpipe, 2 cores, interleaved rounds, raster / walk): an icosphere of 5120
 * triangles 0.63 at 512x512 and 1024x1024, one of 81920 triangles 1.01 at 512x512 (a triangle per 3.2
 * pixels) and 0.69 at 1024x1024 (per 12.8), one of 1310720 triangles 4.5 at 512x512; many_spheres
 * (64 and 1024 boxes) 0.96-1.05, since its camera rays' walks are about 6 % of its frame: analytic
 * scenes keep the walk. With the mesh trees in view order (shared/meshes.c) the walk got cheaper and
 * the icospheres measured 0.81-0.95 / 0.76, 1.55 / 0.96-1.05 and 6.8-6.9 / 2.7 (512 / 1024, two
 * runs): the same choices, the 81920-triangle sphere at 1024 now at break-even within the noise. */
#define AUTO_PIXELS_PER_TRIANGLE 8.0

typedef struct primary_mesh {
    uint64_t serial; /* the mesh's (bg_mesh_data.serial) */
    macs_geometry *geometry;
    int vertices;
    bool used; /* by the commit the geometries were last gathered for */
} primary_mesh;

struct gpu_primary {
    char *key; /* the program's source */
    macs_pass *depth_pass, *id_pass;
    int width, height;
    macs_texture *map;
    macs_depth_stencil *depth;
    macs_geometry *boxes;
    int box_vertices;
    int box_room;      /* vertices boxes has room for */
    uint64_t serial;   /* the commit the boxes and meshes were gathered for; 0 none */
    primary_mesh *meshes;
    uint32_t mesh_count, mesh_room;
};

/* ---- when ---- */

bool bgi_gpu_primary_supported(const bg_renderer *r, const gpu_fused_layout *l, char *why, size_t size)
{
    macs_features f;
    macs_context_get_features(r->ctx, &f);
    if (!bgi_gpu_fused_layout_walks(l))
        snprintf(why, size, "the frame walks no object tree (BG_PLAN_FUSED_TREE with bounded objects)");
    else if (l->lens)
        snprintf(why, size, "the camera has an aperture: its rays do not leave one point per pixel");
    else if (l->mesh_filters)
        snprintf(why, size, "a mesh is front-only or cut out, which its footprint cannot show");
    else if (!f.float32_blend)
        snprintf(why, size, "GL cannot blend RGBA32F outputs (GL_MAX picks the nearest object)");
    else
        return true;
    return false;
}

static uint64_t footprint_triangles(const bg_scene_state *state)
{
    uint64_t n = 0;
    for (uint32_t k = 0; k < state->tree_count; k++) {
        const bg_object_data *o = &state->objects[state->tree_objects[k]];
        n += o->mesh ? o->mesh->triangle_count : 12;
    }
    return n;
}

bool bgi_gpu_primary_pays(const bg_scene_state *state, const gpu_fused_layout *l, uint64_t pixels)
{
    return l->kinds.mesh && (double)footprint_triangles(state) * AUTO_PIXELS_PER_TRIANGLE <= (double)pixels;
}

/* ---- the footprints ---- */

/* The float nearest x on the side away from the box's inside. */
static float down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* The faces of box [lo, hi] (camera-relative) that a camera ray can enter it through, two triangles
 * each as (corner, object, -1) per vertex; returns the vertices written. A ray from outside enters
 * through a face whose plane has the eye (perspective) or the rays' start (orthographic: every ray
 * runs along forward) outside it, so those faces alone cover every pixel whose ray meets the box, at
 * half the fragments of all six; an eye inside the box takes all six. Faces in the order x-, x+, y-,
 * y+, z-, z+. */
static int box_triangles(const float lo[3], const float hi[3], float object, const bg_scene_state *state, float *out)
{
    static const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    static const int split[6] = {0, 1, 2, 0, 2, 3};
    bool front[6], any = false;
    for (int a = 0; a < 3; a++) {
        double f = state->camera.forward[a];
        front[2 * a] = state->camera.orthographic ? f > 0.0 : lo[a] > 0.0f;
        front[2 * a + 1] = state->camera.orthographic ? f < 0.0 : hi[a] < 0.0f;
        any = any || front[2 * a] || front[2 * a + 1];
    }
    int written = 0;
    for (int f = 0; f < 6; f++) {
        if (any && !front[f])
            continue;
        for (int k = 0; k < 6; k++) {
            for (int j = 0; j < 3; j++) {
                int c = faces[f][split[k - k % 3 + j]];
                out[3 * j] = c & 1 ? hi[0] : lo[0];
                out[3 * j + 1] = c & 2 ? hi[1] : lo[1];
                out[3 * j + 2] = c & 4 ? hi[2] : lo[2];
            }
            out[9] = object;
            out[10] = -1.0f;
            out[11] = (float)(k % 3);
            out += FLOATS;
        }
        written += 6;
    }
    return written;
}

/* Every analytic tree object's box, camera-relative, into p->boxes. */
static bg_status gather_boxes(bg_renderer *r, gpu_primary *p, const bg_scene_state *state)
{
    const double *eye = &state->camera.camera.position.x;
    uint32_t boxes = 0;
    for (uint32_t k = 0; k < state->tree_count; k++)
        boxes += state->objects[state->tree_objects[k]].mesh ? 0 : 1;
    p->box_vertices = (int)boxes * BOX_VERTICES;
    if (!boxes)
        return BG_OK;
    size_t bytes = (size_t)p->box_vertices * FLOATS * sizeof(float);
    float *v = bgi_alloc(&r->allocator, bytes);
    if (!v)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the primary visibility's boxes (%zu bytes)", bytes);
    float *o = v;
    for (uint32_t k = 0; k < state->tree_count; k++) {
        uint32_t i = state->tree_objects[k];
        const bg_object_data *obj = &state->objects[i];
        if (obj->mesh)
            continue;
        float lo[3], hi[3];
        for (int a = 0; a < 3; a++) {
            lo[a] = down(obj->bounds_min[a] - eye[a]);
            hi[a] = up(obj->bounds_max[a] - eye[a]);
        }
        o += (size_t)box_triangles(lo, hi, (float)i, state, o) * FLOATS;
    }
    p->box_vertices = (int)((o - v) / FLOATS);
    macs_status ms = MACS_OK;
    if (p->boxes && p->box_room >= p->box_vertices) {
        ms = macs_geometry_upload(p->boxes, 0, p->box_vertices, v);
    } else {
        macs_geometry_destroy(p->boxes);
        p->boxes = NULL;
        macs_geometry_desc d = {p->box_vertices, FLOATS, v};
        ms = macs_geometry_create(r->ctx, &d, &p->boxes);
        p->box_room = ms ? 0 : p->box_vertices;
    }
    bgi_free(&r->allocator, v);
    return ms ? bgi_gpu_fail_macs(r, ms, "primary visibility: the boxes' vertices") : BG_OK;
}

/* A mesh's triangles in object space, three vertices each (the triangle's corners, 0, triangle, which). */
static bg_status mesh_geometry(bg_renderer *r, const bg_mesh_data *mesh, primary_mesh *out)
{
    size_t vertices = (size_t)mesh->triangle_count * 3;
    size_t bytes = vertices * FLOATS * sizeof(float);
    if (vertices > (size_t)INT32_MAX / FLOATS)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "primary visibility: a mesh of %u triangles is beyond one vertex buffer",
                            mesh->triangle_count);
    float *v = bgi_alloc(&r->allocator, bytes);
    if (!v)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for a mesh's footprint (%zu bytes)", bytes);
    float *o = v;
    for (uint32_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            for (int c = 0; c < 3; c++)
                memcpy(o + 3 * c, &mesh->positions[3 * (size_t)mesh->indices[3 * (size_t)t + (size_t)c]], 3 * sizeof *o);
            o[9] = 0.0f;
            o[10] = (float)t;
            o[11] = (float)k;
            o += FLOATS;
        }
    macs_geometry_desc d = {(int)vertices, FLOATS, v};
    macs_status ms = macs_geometry_create(r->ctx, &d, &out->geometry);
    bgi_free(&r->allocator, v);
    out->vertices = (int)vertices;
    out->serial = mesh->serial;
    return ms ? bgi_gpu_fail_macs(r, ms, "primary visibility: a mesh's vertices") : BG_OK;
}

static primary_mesh *mesh_of(gpu_primary *p, uint64_t serial)
{
    for (uint32_t k = 0; k < p->mesh_count; k++)
        if (p->meshes[k].serial == serial)
            return &p->meshes[k];
    return NULL;
}

/* A geometry for every mesh a tree object shows, made once per mesh; the others' are dropped. */
static bg_status gather_meshes(bg_renderer *r, gpu_primary *p, const bg_scene_state *state)
{
    for (uint32_t k = 0; k < p->mesh_count; k++)
        p->meshes[k].used = false;
    for (uint32_t k = 0; k < state->tree_count; k++) {
        const bg_mesh_data *mesh = state->objects[state->tree_objects[k]].mesh;
        if (!mesh)
            continue;
        primary_mesh *m = mesh_of(p, mesh->serial);
        if (!m) {
            if (p->mesh_count == p->mesh_room) {
                uint32_t room = p->mesh_room ? 2 * p->mesh_room : 4;
                primary_mesh *grown = bgi_realloc(&r->allocator, p->meshes, p->mesh_room * sizeof *grown,
                                                  room * sizeof *grown);
                if (!grown)
                    return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the meshes' footprints");
                p->meshes = grown;
                p->mesh_room = room;
            }
            m = &p->meshes[p->mesh_count];
            memset(m, 0, sizeof *m);
            bg_status st = mesh_geometry(r, mesh, m);
            if (st != BG_OK)
                return st;
            p->mesh_count++;
        }
        m->used = true;
    }
    uint32_t kept = 0;
    for (uint32_t k = 0; k < p->mesh_count; k++) {
        if (p->meshes[k].used)
            p->meshes[kept++] = p->meshes[k];
        else
            macs_geometry_destroy(p->meshes[k].geometry);
    }
    p->mesh_count = kept;
    return BG_OK;
}

/* ---- the passes ---- */

static const macs_attribute_desc attributes[] = {{"bg_c0", 3}, {"bg_c1", 3}, {"bg_c2", 3}, {"bg_ident", 3}};

/* The program's uniforms: the camera's as the fused pass has them, the viewport, the textures'
 * geometry, the depth scale and the draw's object. */
static int uniforms_of(const gpu_fused_layout *l, macs_uniform_desc *u)
{
    int n = 0;
    u[n++] = (macs_uniform_desc){"bg_size", MACS_UNIFORM_VEC2, 0};
    u[n++] = (macs_uniform_desc){"bg_shift", MACS_UNIFORM_VEC2, 0};
    u[n++] = (macs_uniform_desc){"bg_forward", MACS_UNIFORM_VEC3, 0};
    u[n++] = (macs_uniform_desc){"bg_right", MACS_UNIFORM_VEC3, 0};
    u[n++] = (macs_uniform_desc){"bg_up", MACS_UNIFORM_VEC3, 0};
    u[n++] = (macs_uniform_desc){"bg_tan_half", MACS_UNIFORM_VEC2, 0};
    u[n++] = (macs_uniform_desc){"bg_viewport", MACS_UNIFORM_VEC2, 0};
    u[n++] = (macs_uniform_desc){"bg_object_dims", MACS_UNIFORM_VEC4, 0};
    if (l->kinds.mesh)
        u[n++] = (macs_uniform_desc){"bg_mesh_dims", MACS_UNIFORM_VEC4, 0};
    u[n++] = (macs_uniform_desc){"bg_inv_dmax", MACS_UNIFORM_FLOAT, 0};
    u[n++] = (macs_uniform_desc){"bg_depth_scale", MACS_UNIFORM_FLOAT, 0};
    u[n++] = (macs_uniform_desc){"bg_draw_to_camera", MACS_UNIFORM_MAT4, 0};
    u[n++] = (macs_uniform_desc){"bg_draw_object", MACS_UNIFORM_FLOAT, 0};
    return n;
}

static void passes_release(gpu_primary *p)
{
    macs_pass_destroy(p->depth_pass);
    macs_pass_destroy(p->id_pass);
    p->depth_pass = p->id_pass = NULL;
}

static void targets_release(gpu_primary *p)
{
    macs_texture_destroy(p->map);
    macs_depth_stencil_destroy(p->depth);
    p->map = NULL;
    p->depth = NULL;
    p->width = p->height = 0;
}

static bg_status targets_prepare(bg_renderer *r, gpu_primary *p, int width, int height)
{
    if (p->map && p->width == width && p->height == height)
        return BG_OK;
    passes_release(p); /* their framebuffers hold the old targets */
    targets_release(p);
    bg_status st = bgi_gpu_texture_ensure(r, width, height, MACS_FORMAT_RGBA32F, &p->map, "primary visibility map");
    if (st != BG_OK)
        return st;
    macs_depth_stencil_desc d = {width, height, 0};
    macs_status ms = macs_depth_stencil_create(r->ctx, &d, &p->depth);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "primary visibility: depth buffer");
    p->width = width;
    p->height = height;
    return BG_OK;
}

static bg_status passes_prepare(bg_renderer *r, gpu_primary *p, const gpu_fused_layout *l)
{
    gpu_text functions, main, vertex_functions, vertex, key;
    bgi_gpu_text_init(&functions, &r->allocator);
    bgi_gpu_text_init(&main, &r->allocator);
    bgi_gpu_text_init(&vertex_functions, &r->allocator);
    bgi_gpu_text_init(&vertex, &r->allocator);
    bgi_gpu_text_init(&key, &r->allocator);
    bool ok = bgi_gpu_primary_source(l, &functions, &main, &vertex_functions, &vertex);
    bgi_gpu_text_append(&key, functions.s ? functions.s : "");
    bgi_gpu_text_append(&key, main.s ? main.s : "");
    bgi_gpu_text_append(&key, vertex_functions.s ? vertex_functions.s : "");
    bgi_gpu_text_append(&key, vertex.s ? vertex.s : "");
    bg_status st = BG_OK;
    if (!ok || key.failed)
        st = functions.failed || main.failed || vertex_functions.failed || vertex.failed || key.failed
                 ? bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building the primary visibility shader")
                 : bgi_gpu_fail(r, BG_ERR_GL, "primary visibility shader: a glsl110/ file is missing");
    if (st == BG_OK && !(p->depth_pass && p->key && strcmp(p->key, key.s) == 0)) {
        passes_release(p);
        macs_uniform_desc u[16];
        int un = uniforms_of(l, u);
        macs_input_desc inputs[2] = {{"bg_objects"}, {"bg_mesh_tris"}};
        macs_output_desc output = {"primary", "vec4(bg_it.x, -bg_it.x, bg_it.y, -bg_it.y)"};
        macs_pass_desc d;
        bgi_gpu_pass_desc_init(&d, main.s, inputs, NULL, l->kinds.mesh ? 2 : 1, u, un, &output, &p->map, 1);
        d.functions = functions.s;
        d.vertex_functions = vertex_functions.s;
        d.vertex_main = vertex.s;
        d.varyings = "varying vec4 bg_item;\n";
        d.attributes = attributes;
        d.attribute_count = 4;
        d.depth_stencil = p->depth;
        d.depth = (macs_depth_state){true, true, MACS_COMPARE_LEQUAL};
        d.color_mask = MACS_COLOR_MASK_NONE;
        macs_status ms = macs_pass_create(r->ctx, &d, &p->depth_pass);
        if (!ms) {
            d.depth = (macs_depth_state){true, false, MACS_COMPARE_LEQUAL};
            d.color_mask = 0;
            d.blend = MACS_BLEND_MAX;
            ms = macs_pass_create(r->ctx, &d, &p->id_pass);
        }
        if (ms)
            st = bgi_gpu_fail_macs(r, ms, "primary visibility passes");
        if (st == BG_OK) {
            bgi_free(&r->allocator, p->key);
            p->key = bgi_strdup(&r->allocator, key.s);
            if (!p->key)
                st = bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory caching the primary visibility program");
        }
        if (st != BG_OK)
            passes_release(p);
    }
    bgi_gpu_text_free(&functions);
    bgi_gpu_text_free(&main);
    bgi_gpu_text_free(&vertex_functions);
    bgi_gpu_text_free(&vertex);
    bgi_gpu_text_free(&key);
    return st;
}

/* ---- one frame ---- */

/* 1 / the farthest distance a camera ray may meet a tree object at: the scene box's farthest corner
 * from the eye, with the orthographic view's half-diagonal for rays that start off the eye. Only
 * the depth's resolution depends on it: a hit beyond clamps to 1 and ties there, which walks. */
static float inverse_dmax(const bg_scene_state *state, const float tan_half[2])
{
    const double *eye = &state->camera.camera.position.x;
    double far = 0.0;
    for (int a = 0; a < 3; a++) {
        double d = fmax(fabs(state->bounds_min[a] - eye[a]), fabs(state->bounds_max[a] - eye[a]));
        far += d * d;
    }
    far = sqrt(far);
    if (state->camera.orthographic)
        far += hypot(tan_half[0], tan_half[1]);
    far = far * 1.01 + 1e-30;
    return (float)(1.0 / far);
}

/* The frame's uniforms on one pass. */
static macs_status frame_uniforms(bg_renderer *r, gpu_primary *p, macs_pass *pass, const gpu_fused_layout *l,
                                  const bg_scene_state *state, const gpu_tree_dims *tree, float depth_scale)
{
    const gpu_view *v = &r->view;
    float size[2] = {(float)v->pixels.frame_width, (float)v->pixels.frame_height};
    float viewport[2] = {(float)p->width, (float)p->height};
    float forward[3], right[3], up[3], tan_half[2];
    for (int a = 0; a < 3; a++) {
        forward[a] = (float)state->camera.forward[a];
        right[a] = (float)state->camera.right[a];
        up[a] = (float)state->camera.up[a];
    }
    bgi_gpu_camera_half(state, v, tan_half);
    float inv = inverse_dmax(state, tan_half);
    macs_status ms = macs_pass_set_uniform(pass, "bg_size", size);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_shift", v->shift);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_forward", forward);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_right", right);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_up", up);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_tan_half", tan_half);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_viewport", viewport);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_object_dims", tree->objects);
    if (!ms && l->kinds.mesh)
        ms = macs_pass_set_uniform(pass, "bg_mesh_dims", r->meshes.dims);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_inv_dmax", &inv);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_depth_scale", &depth_scale);
    return ms;
}

/* Object i's object-to-camera transform (column-major): its to_world with the eye taken off the
 * translation, in double. */
static void to_camera(const bg_scene_state *state, uint32_t i, float m16[16])
{
    const double(*m)[4] = state->objects[i].to_world;
    const double *eye = &state->camera.camera.position.x;
    for (int row = 0; row < 4; row++)
        for (int c = 0; c < 4; c++)
            m16[c * 4 + row] = (float)(m[row][c] - (c == 3 && row < 3 ? eye[row] : 0.0));
}

/* Draws one geometry's footprints. */
static macs_status draw_cover(macs_pass *pass, const macs_geometry *g, int vertices)
{
    macs_draw_desc d = {0};
    d.geometry = g;
    d.vertex_count = vertices;
    return macs_pass_draw(pass, &d);
}

/* Every footprint through one pass: the boxes, then each mesh object's triangles. */
static macs_status draw_all(gpu_primary *p, macs_pass *pass, const bg_scene_state *state)
{
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const float none = -1.0f;
    macs_status ms = MACS_OK;
    if (p->box_vertices > 0) {
        ms = macs_pass_set_uniform(pass, "bg_draw_to_camera", identity);
        if (!ms)
            ms = macs_pass_set_uniform(pass, "bg_draw_object", &none);
        if (!ms)
            ms = draw_cover(pass, p->boxes, p->box_vertices);
    }
    for (uint32_t k = 0; k < state->tree_count && !ms; k++) {
        uint32_t i = state->tree_objects[k];
        const bg_mesh_data *mesh = state->objects[i].mesh;
        if (!mesh)
            continue;
        const primary_mesh *m = mesh_of(p, mesh->serial);
        float m16[16], object = (float)i;
        to_camera(state, i, m16);
        ms = macs_pass_set_uniform(pass, "bg_draw_to_camera", m16);
        if (!ms)
            ms = macs_pass_set_uniform(pass, "bg_draw_object", &object);
        if (!ms)
            ms = draw_cover(pass, m->geometry, m->vertices);
    }
    return ms;
}

bg_status bgi_gpu_primary_draw(bg_renderer *r, gpu_primary **pp, const gpu_fused_layout *l, const bg_scene_state *state,
                               const gpu_tree_textures *tree, int width, int height, macs_texture **map)
{
    *map = NULL;
    if (!*pp) {
        *pp = bgi_alloc(&r->allocator, sizeof **pp);
        if (!*pp)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the primary visibility");
        memset(*pp, 0, sizeof **pp);
    }
    gpu_primary *p = *pp;
    bg_status st = targets_prepare(r, p, width, height);
    if (st == BG_OK)
        st = passes_prepare(r, p, l);
    if (st == BG_OK && p->serial != state->serial) {
        p->serial = 0;
        st = gather_boxes(r, p, state);
        if (st == BG_OK)
            st = gather_meshes(r, p, state);
        if (st == BG_OK)
            p->serial = state->serial;
    }
    if (st != BG_OK)
        return st;
    static const float empty[4] = {-1.0f, -1e30f, -2.0f, -1e30f};
    macs_status ms = macs_texture_clear(p->map, empty);
    if (!ms)
        ms = macs_depth_stencil_clear(p->depth, 1.0f, 0, 0);
    for (int k = 0; k < 2 && !ms; k++) {
        macs_pass *pass = k ? p->id_pass : p->depth_pass;
        ms = macs_pass_set_input(pass, 0, tree->objects.texture);
        if (!ms && l->kinds.mesh)
            ms = macs_pass_set_input(pass, 1, r->meshes.triangles);
        if (!ms)
            ms = frame_uniforms(r, p, pass, l, state, &tree->dims, k ? TIE_SCALE : 1.0f);
        if (!ms)
            ms = draw_all(p, pass, state);
    }
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "primary visibility");
    *map = p->map;
    return BG_OK;
}

void bgi_gpu_primary_release(const bg_allocator *a, gpu_primary **pp)
{
    gpu_primary *p = *pp;
    if (!p)
        return;
    passes_release(p);
    targets_release(p);
    macs_geometry_destroy(p->boxes);
    for (uint32_t k = 0; k < p->mesh_count; k++)
        macs_geometry_destroy(p->meshes[k].geometry);
    bgi_free(a, p->meshes);
    bgi_free(a, p->key);
    bgi_free(a, p);
    *pp = NULL;
}
