/* The fused plan's shader, generated from a layout (gpu_fused_layout) and nothing else: the same
 * structure always gives the same text, which is therefore the key of the cached program (fused.c).
 *
 * On llvmpipe, code inside a branch no pixel takes costs nothing but the branch, while every loop
 * iteration costs (a body run twice costs 3x a straight copy), so the scene is specialised rather
 * than branched on: only the shapes present, texture lookups only for textured parameters, a
 * tangent only for anisotropic materials, refraction and its ray stack only with transparency, no
 * loop at all without bounces, and every object and caster unrolled with its own uniforms (no
 * dynamic indexing, which old hardware lacks), and the lights too unless that would inline too many
 * shadow tests (GPU_FUSED_UNROLLED_SHADOW_TESTS). The functions come from the glsl110/ library
 * (bg_shape_*, bg_hit_root, bg_stage_shadow, bg_uv_*, bg_tangent, bg_stage_spawn, ...), each shape's
 * and mapping's copy renamed by #define as the multipass does (hit_pass.c, light_pass.c). */
#include <stdio.h>
#include <string.h>

#include "../../common/scramble.h"
#include "../../common/shapes.h"
#include "fused.h"

#define FILE_OF_(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = glsl,
static const char *const shape_file[BG_SHAPE_COUNT_] = {BG_SHAPES(FILE_OF_)};
#undef FILE_OF_

const char *bgi_gpu_fused_shape_file(bg_shape shape)
{
    return shape_file[shape];
}

#define SEEN_CAP 64

/* The name of a uniform row for object or material i, in a buffer of the caller's. */
typedef struct name {
    char s[48];
} name;

static name uniform(const gpu_fused_layout *l, int row, uint32_t i)
{
    name n;
    bgi_gpu_fused_uniform_name(l, row, i, n.s, sizeof n.s);
    return n;
}

/* ---- library ---- */

static bool library(const gpu_fused_layout *l, gpu_text *t)
{
    const char *seen[SEEN_CAP];
    int n = 0;
    bool ok = bgi_gpu_text_snippet(t, "bg_stage_camera.glsl", seen, &n, SEEN_CAP) &&
              bgi_gpu_text_snippet(t, "bg_stage_resolve.glsl", seen, &n, SEEN_CAP) &&
              bgi_gpu_text_snippet(t, "bg_stage_hit.glsl", seen, &n, SEEN_CAP);
    static const char *const span[] = {"bg_shape_span", NULL};
    static const char *const root[] = {"bg_shape_span", "bg_hit_root", NULL};
    static const char *const shadow[] = {"bg_shape_span", "bg_segment_blocked", "bg_shadow_visibility", NULL};
    static const char *const uv[] = {"bg_uv_map", NULL};
    bool shape_done[BG_SHAPE_COUNT_] = {false}, caster_done[BG_SHAPE_COUNT_] = {false};
    bool uv_done[BG_UV_COUNT_] = {false};
    for (uint32_t j = 0; j < l->object_count && ok; j++) {
        const gpu_fused_object *o = &l->objects[j];
        if (o->shape == BGI_SHAPE_MESH)
            continue; /* walked from the mesh textures, with bg_triangle.glsl and bg_mesh.glsl */
        if (!shape_done[o->shape]) {
            shape_done[o->shape] = true;
            ok = bgi_gpu_text_snippet_renamed(t, shape_file[o->shape], span, bgi_gpu_shape_suffix(o->shape), seen, &n, SEEN_CAP) &&
                 bgi_gpu_text_snippet_renamed(t, "bg_hit_root.glsl", root, bgi_gpu_shape_suffix(o->shape), seen, &n, SEEN_CAP);
        }
        if (ok && l->shadows && o->casts_shadows && !caster_done[o->shape]) {
            caster_done[o->shape] = true;
            ok = bgi_gpu_text_snippet_renamed(t, "bg_stage_shadow.glsl", shadow, bgi_gpu_shape_suffix(o->shape), seen, &n, SEEN_CAP);
        }
        bool mapped = bgi_gpu_fused_object_uv(l, j) || bgi_gpu_fused_object_tangent(l, j);
        if (ok && mapped && !uv_done[o->uv_mapping]) {
            uv_done[o->uv_mapping] = true;
            ok = bgi_gpu_uv_file(o->uv_mapping) &&
                 bgi_gpu_text_snippet_renamed(t, bgi_gpu_uv_file(o->uv_mapping), uv, bgi_gpu_uv_suffix(o->uv_mapping),
                                              seen, &n, SEEN_CAP);
        }
    }
    if (ok && l->aniso)
        ok = bgi_gpu_text_snippet(t, "bg_tangent.glsl", seen, &n, SEEN_CAP);
    if (ok && (l->tree || l->mesh))
        ok = bgi_gpu_text_snippet(t, "bg_tree_textures.glsl", seen, &n, SEEN_CAP);
    if (ok && l->mesh)
        ok = bgi_gpu_mesh_library(t, seen, &n, SEEN_CAP);
    if (ok && bgi_gpu_fused_layout_lights(l) > 0)
        ok = bgi_gpu_text_snippet(t, "bg_fused_light.glsl", seen, &n, SEEN_CAP);
    if (ok && l->filters)
        ok = bgi_gpu_text_snippet(t, "bg_texture_filter.glsl", seen, &n, SEEN_CAP);
    if (ok && l->srgb)
        ok = bgi_gpu_text_snippet(t, "bg_texture_srgb.glsl", seen, &n, SEEN_CAP);
    if (ok && l->env)
        ok = bgi_gpu_text_snippet(t, "bg_environment.glsl", seen, &n, SEEN_CAP);
    /* The distribution effects' sample points, and the frame pixel's hash they start from. */
    if (ok && bgi_gpu_fused_layout_samples(l)) {
        ok = bgi_gpu_text_snippet(t, "bg_scramble.glsl", seen, &n, SEEN_CAP);
        bgi_gpu_text_append(t, "float bg_ph;\n");
    }
    if (ok && l->glossy)
        ok = bgi_gpu_text_snippet(t, "bg_glossy.glsl", seen, &n, SEEN_CAP);
    if (ok && l->lens)
        ok = bgi_gpu_text_snippet(t, "bg_lens.glsl", seen, &n, SEEN_CAP);
    if (ok && l->area)
        ok = bgi_gpu_text_snippet(t, "bg_area_light.glsl", seen, &n, SEEN_CAP);
    if (ok && l->max_depth > 0)
        ok = bgi_gpu_text_snippet(t, "bg_stage_spawn.glsl", seen, &n, SEEN_CAP);
    return ok && bgi_gpu_text_snippet(t, l->path ? "bg_path.glsl" : "bg_fused_trace.glsl", seen, &n, SEEN_CAP);
}

/* ---- generated functions ---- */

static bool tree_casts(const gpu_fused_layout *l)
{
    if (!bgi_gpu_fused_layout_walks(l) || !l->shadows)
        return false;
    for (int s = 0; s < BG_SHAPE_COUNT_; s++)
        if (l->kinds.caster[s])
            return true;
    return l->kinds.mesh_casts;
}

/* `before` + shape suffix + `after` for the tree object in `meta` (its texel 3: shape first), an
 * if-chain over the shapes in `present` with the last one as the plain else; `mesh` (or NULL: the
 * tree holds no mesh of interest) is the statement for a mesh object, tested first. */
static void emit_shape_dispatch(gpu_text *t, const bool present[BG_SHAPE_COUNT_], const char *indent,
                                const char *before, const char *after, const char *mesh)
{
    int count = 0, position = 0;
    for (int s = 0; s < BG_SHAPE_COUNT_; s++)
        count += present[s] ? 1 : 0;
    /* A mesh object first: meta.x is BGI_SHAPE_MESH, past every shape. */
    if (mesh && count == 0) {
        bgi_gpu_text_printf(t, "%s%s\n", indent, mesh);
        return;
    }
    if (mesh)
        bgi_gpu_text_printf(t, "%sif (meta.x == %d.0)\n%s    %s\n%selse {\n", indent, (int)BGI_SHAPE_MESH, indent, mesh,
                            indent);
    for (int s = 0; s < BG_SHAPE_COUNT_; s++) {
        if (!present[s])
            continue;
        const char *suffix = bgi_gpu_shape_suffix((bg_shape)s);
        if (count == 1)
            bgi_gpu_text_printf(t, "%s%s%s%s\n", indent, before, suffix, after);
        else if (position == count - 1)
            bgi_gpu_text_printf(t, "%selse\n%s    %s%s%s\n", indent, indent, before, suffix, after);
        else
            bgi_gpu_text_printf(t, "%s%sif (meta.x == %d.0)\n%s    %s%s%s\n", indent, position ? "else " : "", s, indent,
                            before, suffix, after);
        position++;
    }
    if (mesh)
        bgi_gpu_text_printf(t, "%s}\n", indent);
}

static int shape_count(const bool present[BG_SHAPE_COUNT_])
{
    int n = 0;
    for (int s = 0; s < BG_SHAPE_COUNT_; s++)
        n += present[s] ? 1 : 0;
    return n;
}

/* The loops of one walk of the tree: `found` (a GLSL bool the leaf code sets, or NULL) ends it
 * early, `t_max` bounds the ray for the box tests, `leaf` is the code run for an entered leaf
 * (object lo.w, its transform m); the walk takes leaf over, and its failure. Every step spends one
 * of the pixel's bg_tree_left steps, so the pixel's walks together stay within what llvmpipe's loop
 * limit leaves them (gpu_fused_layout.walk_budget); the inner loop is at most 255 long, the limit
 * of one loop on SM3-class hardware. A walk that stops before its end without having found what it
 * looks for marks the pixel (bg_tree_short), which the CPU reference then renders (shared/fallback.c). */
static void emit_walk(const gpu_fused_layout *l, gpu_text *t, const char *origin, const char *direction,
                      const char *t_max, const char *found, const char *leaf_test, gpu_text *leaf)
{
    enum { INNER = 255 };
    int outer = (l->walk_budget + INNER - 1) / INNER;
    char done[64] = "";
    if (found)
        snprintf(done, sizeof done, " || %s", found);
    bgi_gpu_text_printf(t, "    vec3 inv = bg_tree_inverse(%s);\n    float node = 0.0;\n", direction);
    const char *stop = "node >= bg_tree_count || bg_tree_left <= 0.0";
    bgi_gpu_text_printf(t, "    for (int outer = 0; outer < %d; outer++) {\n        for (int inner = 0; inner < %d; inner++) {\n",
                    outer > 0 ? outer : 1, INNER);
    bgi_gpu_text_printf(t, "            if (%s%s)\n                break;\n            bg_tree_left -= 1.0;\n", stop, done);
    /* A node's two texels share a row: one address, and the second a texel to the right. */
    bgi_gpu_text_append(t, "            vec2 at = bg_tree_at(bg_tree_dims, node);\n"
                       "            vec4 lo = texture2D(bg_nodes, at);\n"
                       "            vec4 hi = texture2D(bg_nodes, at + vec2(bg_tree_dims.z, 0.0));\n");
    bgi_gpu_text_printf(t, "            bool entered = bg_tree_box(%s, inv, %s, lo.xyz, hi.xyz);\n", origin, t_max);
    bgi_gpu_text_printf(t, "            if (entered && lo.w >= 0.0%s) {\n"
                       "                mat4 m = bg_tree_to_object(bg_objects, bg_object_dims, lo.w);\n",
                    leaf_test);
    bgi_gpu_text_append(t, leaf->s ? leaf->s : "");
    if (leaf->failed)
        t->failed = true;
    bgi_gpu_text_free(leaf);
    bgi_gpu_text_append(t, "            }\n            node = entered && lo.w < 0.0 ? node + 1.0 : hi.w;\n        }\n");
    bgi_gpu_text_printf(t, "        if (%s%s)\n            break;\n    }\n", stop, done);
    if (found)
        bgi_gpu_text_printf(t, "    if (!%s && node < bg_tree_count)\n        bg_tree_short = 1.0;\n", found);
    else
        bgi_gpu_text_append(t, "    if (node < bg_tree_count)\n        bg_tree_short = 1.0;\n");
}

/* The nearest root over the tree's objects, after the unrolled ones (docs/shading.md 2.7): of two
 * equal distances the lower object index wins, as in a loop over the objects in order. */
static void emit_tree_nearest(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "void bg_tree_nearest(vec4 ro, vec4 rd, inout float t, inout float win, inout vec3 p_obj, "
                       "inout vec3 n_obj, inout bool first_root)\n{\n");
    gpu_text leaf;
    bgi_gpu_text_init(&leaf, t->allocator);
    bgi_gpu_text_append(&leaf, "                float tj;\n                vec3 pj, nj;\n                bool fj, h;\n");
    bool mesh = l->kinds.mesh;
    if (shape_count(l->kinds.shape) + (mesh ? 1 : 0) > 1)
        bgi_gpu_text_append(&leaf, "                vec4 meta = bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, "
                               "lo.w, 3.0);\n");
    if (mesh)
        bgi_gpu_text_append(&leaf, "                bg_mesh_tri_j = -1.0;\n");
    emit_shape_dispatch(&leaf, l->kinds.shape, "                ", "h = bg_hit_root_",
                        "(ro, rd, lo.w, m, tj, pj, nj, fj);",
                        mesh ? "{ h = bg_mesh_nearest(ro, rd, lo.w, m, bg_tree_fetch(bg_objects, bg_object_dims, "
                               "BG_OBJECT_TEXELS, lo.w, 4.0).zw, win >= 0.0 ? t : 1e38, tj, fj); pj = vec3(0.0); "
                               "nj = vec3(0.0, 1.0, 0.0); }" : NULL);
    bgi_gpu_text_append(&leaf, "                if (h && (win < 0.0 || tj < t || (tj == t && lo.w < win))) {\n"
                           "                    t = tj;\n                    win = lo.w;\n                    p_obj = pj;\n"
                           "                    n_obj = nj;\n                    first_root = fj;\n");
    if (mesh)
        bgi_gpu_text_append(&leaf, "                    bg_win_tri = bg_mesh_tri_j;\n"
                               "                    bg_win_bary = bg_mesh_bary_j;\n");
    bgi_gpu_text_append(&leaf, "                }\n");
    emit_walk(l, t, "ro.xyz", "rd.xyz", "win >= 0.0 ? t : 1e38", NULL, "", &leaf);
    bgi_gpu_text_append(t, "}\n");
}

/* Whether a caster of the tree other than `self` meets the shadow segment (docs/shading.md 2.8). */
static void emit_tree_blocked(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "bool bg_tree_blocked(vec3 p, vec3 l, float dist, float self)\n{\n    bool blocked = false;\n");
    gpu_text leaf;
    bgi_gpu_text_init(&leaf, t->allocator);
    bool ask = !l->kinds.all_cast;
    bool mesh = l->kinds.mesh_casts;
    if (ask || shape_count(l->kinds.caster) + (mesh ? 1 : 0) > 1)
        bgi_gpu_text_append(&leaf, "                vec4 meta = bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, "
                               "lo.w, 3.0);\n");
    if (ask)
        bgi_gpu_text_append(&leaf, "                if (meta.w > 0.5) {\n");
    emit_shape_dispatch(&leaf, l->kinds.caster, ask ? "                    " : "                ",
                        "blocked = bg_segment_blocked_", "(p, l, dist, m);",
                        mesh ? "blocked = bg_mesh_blocked(p, l, dist, m, bg_tree_fetch(bg_objects, bg_object_dims, "
                               "BG_OBJECT_TEXELS, lo.w, 4.0).zw, lo.w == self ? bg_win_tri : -1.0);" : NULL);
    if (ask)
        bgi_gpu_text_append(&leaf, "                }\n");
    /* A mesh shadows itself: only the triangle the point lies on is skipped (docs/shading.md 2.10). */
    emit_walk(l, t, "p", "l", "dist < 0.0 ? 1e38 : dist", "blocked",
              mesh ? " && (lo.w != self || bg_win_tri >= 0.0)" : " && lo.w != self", &leaf);
    bgi_gpu_text_append(t, "    return blocked;\n}\n");
}

/* The walks and the per-pixel step count they share. */
static void emit_tree_walks(const gpu_fused_layout *l, gpu_text *t)
{
    if (!bgi_gpu_fused_layout_budgeted(l) && !l->mesh)
        return;
    bgi_gpu_text_append(t, "// ---- generated: walks of the object tree and the meshes\n");
    bgi_gpu_walk_globals(t);
    if (l->mesh)
        bgi_gpu_mesh_walks(l->walk_budget, l->mesh_filters, t);
    if (!bgi_gpu_fused_layout_walks(l))
        return;
    emit_tree_nearest(l, t);
    if (tree_casts(l))
        emit_tree_blocked(l, t);
}

/* A camera ray's tree hit from the rasterised map (primary.c): none, or the one object (and
 * triangle) it names, tested again here with the walk's own test and merged by the walk's rule
 * (lower object index on equal distances); a tie in the map, or a test that disagrees with the
 * map's, walks as every other ray does. The map is of the output's size, so the pixel's texel is
 * macs_uv. */
static void emit_primary_lookup(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "    bool walk = true;\n"
                           "    if (bg_primary_pending) {\n"
                           "        bg_primary_pending = false;\n"
                           "        vec4 seen = texture2D(bg_primary, macs_uv);\n"
                           "        if (seen.x < -0.5)\n"
                           "            walk = false;\n"
                           "        else if (seen.x == -seen.y && seen.z == -seen.w) {\n"
                           "            float tq;\n            vec3 pq, nq, bq;\n            bool fq;\n"
                           "            mat4 m = bg_tree_to_object(bg_objects, bg_object_dims, seen.x);\n"
                           "            if (bg_primary_exact(ro, rd, seen.x, seen.z, m, tq, pq, nq, fq, bq)) {\n"
                           "                walk = false;\n"
                           "                if (win < 0.0 || tq < t || (tq == t && seen.x < win)) {\n"
                           "                    t = tq;\n                    win = seen.x;\n                    p_obj = pq;\n"
                           "                    n_obj = nq;\n                    first_root = fq;\n");
    if (l->mesh)
        bgi_gpu_text_append(t, "                    bg_win_tri = seen.z >= 0.0 ? seen.z : -1.0;\n"
                               "                    bg_win_bary = bq;\n");
    bgi_gpu_text_append(t, "                }\n            }\n        }\n    }\n"
                           "    if (walk)\n        bg_tree_nearest(ro, rd, t, win, p_obj, n_obj, first_root);\n");
}

/* The nearest root: a strict < keeps the object added first on a tie (docs/shading.md 2.7). */
static void emit_nearest(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "// ---- generated: nearest hit over the scene's objects\n"
                       "bool bg_fused_nearest(vec4 ro, vec4 rd, out float t, out float win, out vec3 p_obj, "
                       "out vec3 n_obj, out bool first_root)\n{\n"
                       "    t = 0.0;\n    win = -1.0;\n    p_obj = vec3(0.0);\n    n_obj = vec3(0.0, 1.0, 0.0);\n"
                       "    first_root = true;\n");
    if (l->mesh)
        bgi_gpu_text_append(t, "    bg_win_tri = -1.0;\n");
    if (l->unrolled_count > 0)
        bgi_gpu_text_append(t, "    float tj;\n    vec3 pj, nj;\n    bool fj;\n");
    int emitted = 0;
    for (uint32_t j = 0; j < l->object_count; j++) {
        if (l->objects[j].in_tree)
            continue;
        name id = uniform(l, GPU_FUSED_U_ID, j), to_object = uniform(l, GPU_FUSED_U_TO_OBJECT, j);
        const char *nearer = emitted++ ? " && (win < 0.0 || tj < t)" : "";
        /* An unrolled mesh walks its own tree with its uniforms; its search stops at the best
         * distance so far (docs/shading.md 2.10). */
        if (l->objects[j].shape == BGI_SHAPE_MESH)
            bgi_gpu_text_printf(t,
                            "    if (bg_mesh_nearest(ro, rd, %s, %s, %s, win >= 0.0 ? t : 1e38, tj, fj)%s) {\n"
                            "        t = tj;\n        win = %s;\n        p_obj = vec3(0.0);\n"
                            "        n_obj = vec3(0.0, 1.0, 0.0);\n        first_root = fj;\n"
                            "        bg_win_tri = bg_mesh_tri_j;\n        bg_win_bary = bg_mesh_bary_j;\n    }\n",
                            id.s, to_object.s, uniform(l, GPU_FUSED_U_MESH_BASE, j).s, nearer, id.s);
        else
            bgi_gpu_text_printf(t,
                            "    if (bg_hit_root_%s(ro, rd, %s, %s, tj, pj, nj, fj)%s) {\n"
                            "        t = tj;\n        win = %s;\n        p_obj = pj;\n        n_obj = nj;\n"
                            "        first_root = fj;\n%s    }\n",
                            bgi_gpu_shape_suffix(l->objects[j].shape), id.s, to_object.s, nearer, id.s,
                            l->mesh ? "        bg_win_tri = -1.0;\n" : "");
    }
    if (l->primary)
        emit_primary_lookup(l, t);
    else if (bgi_gpu_fused_layout_walks(l))
        bgi_gpu_text_append(t, "    bg_tree_nearest(ro, rd, t, win, p_obj, n_obj, first_root);\n");
    if (l->mesh)
        bgi_gpu_text_append(t, "    bg_hit_p = ro.xyz + t * rd.xyz;\n");
    bgi_gpu_text_append(t, "    return win >= 0.0;\n}\n");
}

/* Shadow segments against every caster but the object the point lies on (docs/shading.md 2.8). */
static void emit_blocked(const gpu_fused_layout *l, gpu_text *t)
{
    if (bgi_gpu_fused_layout_lights(l) == 0)
        return;
    bgi_gpu_text_append(t, "// ---- generated: shadow casters\n"
                       "bool bg_fused_blocked(vec3 p, vec3 l, float dist, float self)\n{\n");
    if (l->mesh)
        bgi_gpu_text_append(t, "    if (bg_win_tri >= 0.0)\n"
                               "        p += (dot(l, bg_hit_ng) >= 0.0 ? bg_hit_off : -bg_hit_off) * bg_hit_ng;\n");
    for (uint32_t j = 0; j < l->object_count && l->shadows; j++) {
        if (!l->objects[j].casts_shadows || l->objects[j].in_tree)
            continue;
        name id = uniform(l, GPU_FUSED_U_ID, j), to_object = uniform(l, GPU_FUSED_U_TO_OBJECT, j);
        /* A mesh shadows itself: only the triangle the point lies on is skipped (docs/shading.md 2.10). */
        if (l->objects[j].shape == BGI_SHAPE_MESH)
            bgi_gpu_text_printf(t, "    if (bg_mesh_blocked(p, l, dist, %s, %s, self == %s ? bg_win_tri : -1.0))\n"
                                   "        return true;\n",
                                to_object.s, uniform(l, GPU_FUSED_U_MESH_BASE, j).s, id.s);
        else
            bgi_gpu_text_printf(t, "    if (self != %s && bg_segment_blocked_%s(p, l, dist, %s))\n        return true;\n",
                                id.s, bgi_gpu_shape_suffix(l->objects[j].shape), to_object.s);
    }
    if (tree_casts(l))
        bgi_gpu_text_append(t, "    if (bg_tree_blocked(p, l, dist, self))\n        return true;\n");
    bgi_gpu_text_append(t, "    return false;\n}\n");
}

/* One branch of an if-chain over `count` cases, the last one the plain else: var == value. */
static void branch(gpu_text *t, const char *var, const char *value, int position, int count)
{
    if (count == 1)
        bgi_gpu_text_append(t, "    {\n");
    else if (position == count - 1)
        bgi_gpu_text_append(t, "    else {\n");
    else
        bgi_gpu_text_printf(t, "    %sif (%s == %s) {\n", position ? "else " : "", var, value);
}

/* A mesh hit's attributes (docs/shading.md 2.10): closed, entering on the front side; its UVs are
 * the mesh's own, scaled, and its tangent follows their u direction. The expressions name where
 * the object's values are: its first triangle texel, normal matrix, linear part, UV scale (NULL:
 * no UVs wanted), index and material. */
typedef struct mesh_values {
    const char *tris, *normal, *to_world3, *uv_scale, *id, *mat;
    bool tangent;
    bool open; /* some mesh is open (BG_SIDES_BOTH): its filter record says which, and its hits are thin */
} mesh_values;

static void emit_mesh_attributes(gpu_text *t, const mesh_values *v)
{
    char thin[160];
    snprintf(thin, sizeof thin, v->open ? "bg_mesh_open(bg_mesh_tris, bg_mesh_dims, %s)" : "false", v->tris);
    bgi_gpu_text_printf(t, "        bg_mesh_attributes(bg_mesh_tris, bg_mesh_dims, %s + 6.0 * bg_win_tri, bg_win_bary, first_root, "
                           "%s, %s, bg_hit_p, d, %.1f, bg_hit_ng, n, uv, dpdu, bg_hit_off);\n"
                           "        entering = first_root;\n        code = bg_hit_code(%s, %s, entering);\n"
                           "        mat = %s;\n",
                        v->tris, v->normal, v->to_world3, GPU_MESH_OFFSET_ULPS, v->id, thin, v->mat);
    if (v->uv_scale)
        bgi_gpu_text_printf(t, "        uv *= %s;\n", v->uv_scale);
    if (v->tangent)
        bgi_gpu_text_printf(t, "        tg = bg_tangent(%s * dpdu, n);\n", v->to_world3);
    else
        bgi_gpu_text_append(t, "        tg = n;\n");
}

/* The hit attributes of object j (docs/shading.md 3): normal facing the ray, hit code, UV, tangent. */
static void emit_object_attributes(const gpu_fused_layout *l, gpu_text *t, uint32_t j)
{
    const gpu_fused_object *o = &l->objects[j];
    if (o->shape == BGI_SHAPE_MESH) {
        char tris[64], mat[16];
        name normal = uniform(l, GPU_FUSED_U_NORMAL, j), to_world3 = uniform(l, GPU_FUSED_U_TO_WORLD3, j);
        name uv_scale = uniform(l, GPU_FUSED_U_UV_SCALE, j), id = uniform(l, GPU_FUSED_U_ID, j);
        snprintf(tris, sizeof tris, "%s.y", uniform(l, GPU_FUSED_U_MESH_BASE, j).s);
        snprintf(mat, sizeof mat, "%u.0", (unsigned)o->material);
        mesh_values v = {tris, normal.s, to_world3.s, bgi_gpu_fused_object_uv(l, j) ? uv_scale.s : NULL, id.s, mat,
                         bgi_gpu_fused_object_tangent(l, j), (l->mesh_filters & GPU_MESH_OPEN) != 0};
        emit_mesh_attributes(t, &v);
        return;
    }
    const char *thin = bg_shape_thin(o->shape) ? "true" : "false";
    bgi_gpu_text_printf(t, "        n = bg_hit_normal(%s, n_obj, d, %s, first_root, entering);\n",
                    uniform(l, GPU_FUSED_U_NORMAL, j).s, thin);
    bgi_gpu_text_printf(t, "        code = bg_hit_code(%s, %s, entering);\n        mat = %u.0;\n",
                    uniform(l, GPU_FUSED_U_ID, j).s, thin, (unsigned)o->material);
    bool want_uv = bgi_gpu_fused_object_uv(l, j), want_tangent = bgi_gpu_fused_object_tangent(l, j);
    if (want_uv || want_tangent)
        bgi_gpu_text_printf(t, "        uv = bg_uv_map_%s(p_obj, dpdu);\n", bgi_gpu_uv_suffix(o->uv_mapping));
    if (want_uv)
        bgi_gpu_text_printf(t, "        uv *= %s;\n", uniform(l, GPU_FUSED_U_UV_SCALE, j).s);
    /* An isotropic layer's azimuth factor is exactly 1 whatever the tangent (bg_brdf.glsl). */
    if (want_tangent)
        bgi_gpu_text_printf(t, "        tg = bg_tangent(%s * dpdu, n);\n", uniform(l, GPU_FUSED_U_TO_WORLD3, j).s);
    else
        bgi_gpu_text_append(t, "        tg = n;\n");
}

static const char *const channel_lane[4] = {"r", "g", "b", "a"};

/* Material k's parameters at the hit (docs/shading.md 5): constant x texel, clamped to its range. */
static void emit_material(const gpu_fused_layout *l, gpu_text *t, uint32_t k)
{
    const gpu_fused_material *m = &l->materials[k];
    for (int p = 0; p < GPU_P_COUNT_; p++) {
        if (!bgi_gpu_fused_uniform_present(l, GPU_FUSED_PARAM_ROW(p), k))
            continue;
        char value[320], sampler[24], texel[192];
        name u = uniform(l, GPU_FUSED_PARAM_ROW(p), k);
        if (m->sampler[p] >= 0) {
            snprintf(sampler, sizeof sampler, "bg_tex%d", m->sampler[p]);
            if (!bgi_gpu_texture_lookup(texel, sizeof texel, sampler, "uv", l->sampler_modes[m->sampler[p]]))
                t->failed = true; /* cannot happen: every name above is short */
            snprintf(value, sizeof value, "%s * %s.%s", u.s, texel,
                     bgi_gpu_param_is_color((gpu_param)p) ? "rgb" : channel_lane[m->channel[p] & 3]);
        } else
            snprintf(value, sizeof value, "%s", u.s);
        if (bgi_gpu_param_is_unit((gpu_param)p))
            bgi_gpu_text_printf(t, "        %s = clamp(%s, 0.0, 1.0);\n", bgi_gpu_param_local((gpu_param)p), value);
        else
            bgi_gpu_text_printf(t, "        %s = max(%s, vec3(0.0));\n", bgi_gpu_param_local((gpu_param)p), value);
    }
    if (bgi_gpu_fused_uniform_present(l, GPU_FUSED_U_IOR, k))
        bgi_gpu_text_printf(t, "        ior = %s;\n", uniform(l, GPU_FUSED_U_IOR, k).s);
    /* A glossy material marks itself by a negative ior (positive in every material), which the
     * spawn reads back as its absolute value. */
    if (m->glossy)
        bgi_gpu_text_append(t, "        ior = -ior;\n");
}

/* The hit attributes of a tree object, as emit_object_attributes writes them from uniforms, here
 * from the object's texels. */
static void emit_tree_attributes(const gpu_fused_layout *l, gpu_text *t)
{
    const gpu_fused_tree_kinds *k = &l->kinds;
    bgi_gpu_text_append(t, "        mat4 m = bg_tree_to_object(bg_objects, bg_object_dims, win);\n"
                       "        vec4 meta = bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, win, 3.0);\n");
    int thin = 0, shapes = shape_count(k->shape);
    char test[256] = "";
    for (int s = 0; s < BG_SHAPE_COUNT_; s++) {
        if (!k->shape[s] || !bg_shape_thin((bg_shape)s))
            continue;
        size_t used = strlen(test);
        snprintf(test + used, sizeof test - used, "%smeta.x == %d.0", thin++ ? " || " : "", s);
    }
    if (k->mesh) {
        bgi_gpu_text_append(t, "        if (bg_win_tri >= 0.0) {\n"
                               "        vec4 bases = bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, win, 4.0);\n");
        mesh_values v = {"bases.w", "bg_tree_normal_matrix(m)", "bg_tree_to_world3(bg_objects, bg_object_dims, win)",
                         k->uv ? "bases.xy" : NULL, "win", "meta.y", k->tangent, (l->mesh_filters & GPU_MESH_OPEN) != 0};
        emit_mesh_attributes(t, &v);
        bgi_gpu_text_append(t, "        } else {\n");
    }
    bgi_gpu_text_printf(t, "        bool thin = %s;\n", thin == 0 ? "false" : thin == shapes ? "true" : test);
    bgi_gpu_text_append(t, "        n = bg_hit_normal(bg_tree_normal_matrix(m), n_obj, d, thin, first_root, entering);\n"
                       "        code = bg_hit_code(win, thin, entering);\n        mat = meta.y;\n");
    if (k->uv || k->tangent) {
        int count = 0, position = 0;
        for (int u = 0; u < BG_UV_COUNT_; u++)
            count += k->mapping[u] ? 1 : 0;
        for (int u = 0; u < BG_UV_COUNT_; u++) {
            if (!k->mapping[u])
                continue;
            if (count == 1)
                bgi_gpu_text_printf(t, "        uv = bg_uv_map_%s(p_obj, dpdu);\n", bgi_gpu_uv_suffix(u));
            else if (position == count - 1)
                bgi_gpu_text_printf(t, "        else\n            uv = bg_uv_map_%s(p_obj, dpdu);\n", bgi_gpu_uv_suffix(u));
            else
                bgi_gpu_text_printf(t, "        %sif (meta.z == %d.0)\n            uv = bg_uv_map_%s(p_obj, dpdu);\n",
                                position ? "else " : "", u, bgi_gpu_uv_suffix(u));
            position++;
        }
    }
    if (k->uv)
        bgi_gpu_text_append(t, "        uv *= bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, win, 4.0).xy;\n");
    if (k->tangent)
        bgi_gpu_text_append(t, "        tg = bg_tangent(bg_tree_to_world3(bg_objects, bg_object_dims, win) * dpdu, n);\n");
    else
        bgi_gpu_text_append(t, "        tg = n;\n");
    if (k->mesh)
        bgi_gpu_text_append(t, "        }\n");
}

/* The winner's attributes by object, then its material by material: objects of one material share
 * the material's code. */
static void emit_surface(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "// ---- generated: hit attributes and materials\n"
                       "void bg_fused_surface(float win, vec3 p_obj, vec3 n_obj, bool first_root, vec3 d, out float code, "
                       "out vec4 nrm, out vec4 base, out vec4 coat, out vec4 tangent, out vec3 once, out vec2 xparent)\n{\n"
                       "    bool entering = true;\n    vec3 n = -d;\n    float mat = 0.0;\n    vec2 uv = vec2(0.0);\n"
                       "    vec3 dpdu = vec3(0.0);\n    vec3 tg = -d;\n    code = 0.0;\n");
    int cases = (int)l->unrolled_count + (bgi_gpu_fused_layout_walks(l) ? 1 : 0), position = 0;
    for (uint32_t j = 0; j < l->object_count; j++) {
        if (l->objects[j].in_tree)
            continue;
        branch(t, "win", uniform(l, GPU_FUSED_U_ID, j).s, position++, cases);
        emit_object_attributes(l, t, j);
        bgi_gpu_text_append(t, "    }\n");
    }
    if (bgi_gpu_fused_layout_walks(l)) {
        branch(t, "win", "", position, cases);
        emit_tree_attributes(l, t);
        bgi_gpu_text_append(t, "    }\n");
    }
    /* Parameters a material lacks keep the values that make them vanish: isotropic, opaque, no coat. */
    bgi_gpu_text_append(t, "    vec3 base_c = vec3(0.0), ambient = vec3(0.0), emission = vec3(0.0), coat_c = vec3(0.0);\n"
                       "    float base_r = 1.0, base_p = 1.0, transparency = 0.0, ior = 1.0, coat_r = -1.0, "
                       "coat_p = 1.0;\n");
    int used = 0;
    position = 0;
    for (uint32_t k = 0; k < l->material_count; k++)
        used += l->materials[k].used ? 1 : 0;
    if (l->visible_lights)
        bgi_gpu_text_append(t, "    bg_path_light = -1.0;\n");
    for (uint32_t k = 0; k < l->material_count; k++) {
        if (!l->materials[k].used)
            continue;
        char value[16];
        snprintf(value, sizeof value, "%u.0", (unsigned)k);
        branch(t, "mat", value, position++, used);
        emit_material(l, t, k);
        /* Under the path integrator a visible area light's object glows with the light's own Le on
         * its front (docs/shading.md 13.1), which bg_fused_path_emitted adds, in place of its
         * material's emission. */
        if (l->visible_lights && l->materials[k].light)
            bgi_gpu_text_printf(t, "        emission = vec3(0.0);\n        bg_path_light = %u.0;\n",
                                (unsigned)(l->materials[k].light - 1));
        bgi_gpu_text_append(t, "    }\n");
    }
    /* The path integrator adds the ambient term only when asked to (settings.path_ambient). */
    bgi_gpu_text_printf(t, "    nrm = vec4(n, base_r);\n    base = vec4(base_c, base_p);\n    coat = vec4(coat_c, coat_r);\n"
                           "    tangent = vec4(tg, coat_p);\n    once = emission%s;\n"
                           "    xparent = vec2(transparency, ior);\n}\n",
                        !l->path || l->path_ambient ? " + (1.0 - transparency) * ambient" : "");
}

/* One light's term, the light given by its index into the light arrays (a number or the loop's).
 * With area lights, each light is its point at this sample (docs/shading.md 7), of the light's own
 * dimension of the scramble. */
static void emit_light_term(const gpu_fused_layout *l, gpu_text *t, const char *i, const char *indent)
{
    if (!l->area) {
        bgi_gpu_text_printf(t,
                        "%sradiance += lw * bg_fused_light(p, nrm, base, coat, tangent, view, self, bg_lpos[%s], bg_lrad[%s], "
                        "bg_latt[%s], bg_lspot[%s], bg_lexp[%s]);\n",
                        indent, i, i, i, i, i);
        return;
    }
    bgi_gpu_text_printf(t,
                    "%s{\n%s    vec4 q = bg_area_light_pos(p, bg_lpos[%s], bg_ledge_u[%s], bg_ledge_v[%s], "
                    "bg_sample_square(bg_ph, %d.0 + %d.0 * float(%s), bg_sample_of, bg_sample_perm));\n"
                    "%s    radiance += lw * bg_fused_light(p, nrm, base, coat, tangent, view, self, q, "
                    "bg_area_light_radiance(p, q, bg_ledge_u[%s], bg_ledge_v[%s], bg_lrad[%s]), bg_latt[%s], bg_lspot[%s], "
                    "bg_lexp[%s]);\n%s}\n",
                    indent, indent, i, i, i, BGI_DIMENSION_LIGHT(0), BGI_DIMENSION_LIGHT(1) - BGI_DIMENSION_LIGHT(0), i, indent, i, i, i, i, i, i, indent);
}

void bgi_gpu_fused_each_light(const gpu_fused_layout *l, gpu_text *t, gpu_fused_light_term term)
{
    if (l->light_loop) {
        bgi_gpu_text_printf(t, "    for (int i = 0; i < %u; i++)\n", (unsigned)l->light_count);
        term(l, t, "i", "        ");
        return;
    }
    for (uint32_t i = 0; i < l->light_count; i++) {
        char k[16];
        snprintf(k, sizeof k, "%u", (unsigned)i);
        term(l, t, k, "    ");
    }
}

/* Every light in the scene's order (docs/shading.md 8). */
static void emit_direct(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "// ---- generated: lights\n"
                       "void bg_fused_direct(vec3 p, vec4 nrm, vec4 base, vec4 coat, vec4 tangent, vec3 view, float self, "
                       "vec3 lw, inout vec3 radiance)\n{\n");
    bgi_gpu_fused_each_light(l, t, emit_light_term);
    /* The environment last, as a directional light of its direction at this sample (7.1). */
    if (l->env_light)
        bgi_gpu_text_printf(t, "    vec3 env_l, env_e;\n"
                               "    if (bg_env_light(bg_sample_square(bg_ph, %d.0, bg_sample_of, bg_sample_perm), bg_tex%d, %s, %s, bg_env_info, "
                               "env_l, env_e))\n"
                               "        radiance += lw * bg_fused_light(p, nrm, base, coat, tangent, view, self, vec4(-env_l, 1.0), "
                               "env_e, vec3(1.0, 0.0, 0.0), vec4(0.0, 0.0, 0.0, -2.0), 0.0);\n",
                            BGI_DIMENSION_LIGHT((int)l->light_count), l->env_sampler,
                            l->env_importance ? "bg_env_marginal" : "bg_tex0", l->env_importance ? "bg_env_conditional" : "bg_tex0");
    bgi_gpu_text_append(t, "}\n");
}

/* With an environment, a miss sees it: the ray function of the other scenes, called with a black
 * background, and the environment added on a miss. */
static void emit_environment_ray(const gpu_fused_layout *l, gpu_text *t)
{
    if (!l->env)
        return;
    char sampler[24], texel[192];
    snprintf(sampler, sizeof sampler, "bg_tex%d", l->env_sampler);
    if (!bgi_gpu_texture_lookup(texel, sizeof texel, sampler, "bg_env_uv(rd.xyz, bg_env_info)",
                                l->sampler_modes[l->env_sampler]))
        t->failed = true; /* cannot happen: every name above is short */
    bgi_gpu_text_printf(t, "// ---- generated: the environment on a miss\n"
                           "bool bg_fused_ray_env(vec4 ro, vec4 rd, vec3 w, inout vec3 radiance, out vec4 hit, out vec4 nrm, "
                           "out vec4 base, out vec4 coat, out vec2 xparent)\n{\n"
                           "    if (bg_fused_ray(ro, rd, w, vec3(0.0), radiance, hit, nrm, base, coat, xparent))\n"
                           "        return true;\n"
                           "    radiance += w * (bg_env_info.x * %s.rgb);\n"
                           "    return false;\n}\n",
                        texel);
}

/* ---- main ---- */

static const char *trace_call_of(const gpu_fused_layout *l)
{
    return l->env ? "bg_fused_ray_env(bg_ro, bg_rd, bg_cw.rgb, bg_radiance, bg_hit, bg_nrm, bg_base, bg_coat, bg_xp)"
                  : "bg_fused_ray(bg_ro, bg_rd, bg_cw.rgb, bg_background, bg_radiance, bg_hit, bg_nrm, bg_base, bg_coat, bg_xp)";
}

/* The children of the hit just traced (docs/shading.md 9), by the multipass spawn function. */
static void emit_spawn(const gpu_fused_layout *l, gpu_text *t, bool transmitted, int child)
{
    bgi_gpu_text_printf(t,
                    "        bg_spawn(%s, bg_hit, bg_nrm, bg_base, bg_coat, bg_xp.x, %s, bg_rd, vec4(bg_cw.rgb, 1.0), "
                    "bg_min_weight, bg_o%d, bg_d%d, bg_w%d);\n",
                    transmitted ? "true" : "false", l->glossy ? "abs(bg_xp.y)" : "bg_xp.y", child, child, child);
    /* A glossy material's reflected child, from the lobe's dimension of its level (bg_cw.a). */
    if (l->glossy && !transmitted)
        bgi_gpu_text_printf(t, "        if (bg_xp.y < 0.0)\n            bg_glossy_child(bg_rd.xyz, bg_nrm, bg_coat, "
                               "bg_sample_square(bg_ph, %d.0 + %d.0 * bg_cw.a, bg_sample_of, bg_sample_perm), bg_d%d, bg_w%d);\n",
                            BGI_DIMENSION_GLOSSY(0), BGI_DIMENSION_GLOSSY(1) - BGI_DIMENSION_GLOSSY(0), child, child);
    if (l->mesh)
        bgi_gpu_text_printf(t, "        bg_mesh_leave(bg_hit, bg_o%d, bg_d%d);\n", child, child);
}

/* Makes child `c` the next ray (its level is the current one plus 1). */
static void emit_follow(gpu_text *t, int c, const char *indent)
{
    bgi_gpu_text_printf(t, "%sbg_ro = bg_o%d;\n%sbg_rd = bg_d%d;\n%sbg_cw = vec4(bg_w%d.rgb, bg_cw.a + 1.0);\n", indent, c,
                    indent, c, indent, c);
}

/* A chain of reflections: one child per hit, no stack. */
static void emit_chain(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_printf(t, "for (int bg_i = 0; bg_i < %d; bg_i++) {\n", l->loop_rays);
    bgi_gpu_text_printf(t, "    if (!%s || bg_cw.a >= %d.0)\n        break;\n", trace_call_of(l), l->max_depth);
    bgi_gpu_text_append(t, "    vec4 bg_o1, bg_d1, bg_w1;\n    {\n");
    emit_spawn(l, t, false, 1);
    bgi_gpu_text_append(t, "    }\n    if (bg_w1.a <= 0.0)\n        break;\n");
    emit_follow(t, 1, "    ");
    bgi_gpu_text_append(t, "}\n");
}

/* The whole tree depth-first: the reflected child is followed and the transmitted one pushed. The
 * pending rays are right siblings of the rays on the current path, at most one per level, so a stack
 * of max_depth entries holds them; it lives in separate variables shifted on push and pop, which on
 * llvmpipe measured faster than an indexed local array. (Tracing the camera ray before the loop
 * instead, so that pixels without bounces never enter it, measured slower: 12 % on glass, 50 % on
 * mirror, with twice the code to compile.) */
static void emit_tree(const gpu_fused_layout *l, gpu_text *t)
{
    int n = l->stack;
    for (int k = 0; k < n; k++)
        bgi_gpu_text_printf(t, "vec4 bg_s%d_o = vec4(0.0), bg_s%d_d = vec4(0.0), bg_s%d_w = vec4(0.0);\n", k, k, k);
    bgi_gpu_text_append(t, "int bg_pending = 0;\n");
    bgi_gpu_text_printf(t, "for (int bg_i = 0; bg_i < %d; bg_i++) {\n    bool bg_next = false;\n", l->loop_rays);
    bgi_gpu_text_printf(t, "    if (%s && bg_cw.a < %d.0) {\n", trace_call_of(l), l->max_depth);
    bgi_gpu_text_append(t, "        vec4 bg_o1, bg_d1, bg_w1, bg_o2, bg_d2, bg_w2;\n");
    emit_spawn(l, t, false, 1);
    emit_spawn(l, t, true, 2);
    bgi_gpu_text_append(t, "        if (bg_w1.a > 0.0 && bg_w2.a > 0.0) {\n");
    for (int k = n - 1; k > 0; k--)
        bgi_gpu_text_printf(t, "            bg_s%d_o = bg_s%d_o;\n            bg_s%d_d = bg_s%d_d;\n"
                           "            bg_s%d_w = bg_s%d_w;\n",
                        k, k - 1, k, k - 1, k, k - 1);
    bgi_gpu_text_append(t, "            bg_s0_o = bg_o2;\n            bg_s0_d = bg_d2;\n"
                       "            bg_s0_w = vec4(bg_w2.rgb, bg_cw.a + 1.0);\n            bg_pending++;\n");
    bgi_gpu_text_append(t, "        }\n        if (bg_w1.a > 0.0) {\n");
    emit_follow(t, 1, "            ");
    bgi_gpu_text_append(t, "            bg_next = true;\n        } else if (bg_w2.a > 0.0) {\n");
    emit_follow(t, 2, "            ");
    bgi_gpu_text_append(t, "            bg_next = true;\n        }\n    }\n"
                       "    if (!bg_next) {\n        if (bg_pending == 0)\n            break;\n"
                       "        bg_ro = bg_s0_o;\n        bg_rd = bg_s0_d;\n        bg_cw = bg_s0_w;\n");
    for (int k = 0; k + 1 < n; k++)
        bgi_gpu_text_printf(t, "        bg_s%d_o = bg_s%d_o;\n        bg_s%d_d = bg_s%d_d;\n        bg_s%d_w = bg_s%d_w;\n", k,
                        k + 1, k, k + 1, k, k + 1);
    bgi_gpu_text_append(t, "        bg_pending--;\n    }\n}\n");
}

static void emit_main(const gpu_fused_layout *l, gpu_text *t)
{
    /* The eye is the origin of the camera-relative frame (origin.c). bg_cw is the path weight and,
     * in a, the ray's level. */
    bgi_gpu_text_printf(t, "vec4 bg_ro, bg_rd, bg_w0;\n"
                       "%s(gl_FragCoord.xy + bg_shift, bg_size, vec3(0.0), bg_forward, bg_right, bg_up, "
                       "bg_tan_half, bg_ro, bg_rd, bg_w0);\n", bgi_gpu_camera_function(l->orthographic));
    bgi_gpu_text_append(t, ""
                       "vec4 bg_cw = vec4(1.0, 1.0, 1.0, 0.0);\nvec3 bg_radiance = vec3(0.0);\n"
                       "vec4 bg_hit, bg_nrm, bg_base, bg_coat;\nvec2 bg_xp;\n");
    if (bgi_gpu_fused_layout_samples(l))
        bgi_gpu_text_append(t, "bg_ph = bg_pixel_hash(gl_FragCoord.xy, bg_pixel_at);\n");
    if (l->lens)
        bgi_gpu_text_printf(t, "bg_lens_ray(bg_sample_disc(bg_sample_square(bg_ph, %d.0, bg_sample_of, bg_sample_perm)), bg_lens.x, bg_lens.y, "
                               "bg_forward, bg_right, bg_up, bg_ro, bg_rd);\n", BGI_DIMENSION_LENS);
    if (bgi_gpu_fused_layout_budgeted(l))
        bgi_gpu_text_printf(t, "bg_tree_left = %d.0;\nbg_tree_short = 0.0;\n", l->walk_budget);
    if (l->primary)
        bgi_gpu_text_append(t, "bg_primary_pending = true;\n");
    if (l->path)
        bgi_gpu_fused_path_main(l, t);
    else if (l->max_depth == 0)
        bgi_gpu_text_printf(t, "%s;\n", trace_call_of(l));
    else if (l->stack == 0)
        emit_chain(l, t);
    else
        emit_tree(l, t);
    /* The output encoding (docs/shading.md 10) is a uniform: RGBA8 in either encoding and RGBA32F
     * share the program. */
    /* Alpha 0 marks a pixel whose tree walks ran out of steps (shared/fallback.c renders it again). */
    bgi_gpu_text_printf(t, "float bg_alpha = %s;\nvec4 bg_out = vec4(bg_radiance, bg_alpha);\n"
                       "if (bg_output.x > 0.5)\n    bg_out = vec4(bg_encode(bg_radiance, bg_output.y > 0.5), bg_alpha);\n",
                    bgi_gpu_fused_layout_budgeted(l) ? "1.0 - bg_tree_short" : "1.0");
}

bool bgi_gpu_fused_source(const gpu_fused_layout *l, gpu_text *functions, gpu_text *main, const char **output)
{
    bool ok = library(l, functions);
    emit_tree_walks(l, functions);
    if (l->primary) {
        bgi_gpu_primary_exact_source(l, functions);
        bgi_gpu_text_append(functions, "bool bg_primary_pending; // the camera ray's tree hit is the map's\n");
    }
    emit_nearest(l, functions);
    emit_blocked(l, functions);
    if (l->visible_lights)
        bgi_gpu_text_append(functions, "float bg_path_light; // the visible area light whose object the ray met, or -1\n");
    emit_surface(l, functions);
    if (l->path) {
        bgi_gpu_fused_path_functions(l, functions);
    } else {
        emit_direct(l, functions);
        emit_environment_ray(l, functions);
    }
    emit_main(l, main);
    *output = "bg_out";
    return ok && !functions->failed && !main->failed;
}
