/* The mesh code of the fused plans (docs/gpu_pipeline.md, "Meshes"): when the object tree's walk
 * reaches a mesh object's leaf, or the unrolled code a mesh object, the ray goes into the object's
 * space and walks the mesh's own tree, stackless, from the mesh textures (meshes.c): interior
 * nodes in the object tree's format, leaves holding their triangle's corners, which go through
 * bg_triangle.glsl. Every node step of both levels spends one of the
 * pixel's walk steps (bg_tree_left); a mesh walk that runs out marks the pixel (bg_tree_short) for
 * the CPU reference, as the object tree's walk does.
 *
 * A ray leaving a mesh carries the object in its origin's w lane (the analytic shapes' skip) and
 * -2 - triangle in its direction's w lane, where the analytic shapes keep the object a ray runs
 * inside: no object index is negative, so neither lane confuses an analytic shape, and the mesh
 * walk skips exactly that triangle of that object. */
#include <stdio.h>

#include "shared.h"

/* The loops of one mesh walk, as emit_walk in fused_source.c writes the object tree's: `body` is the
 * leaf's test, `found` ends the walk early (or NULL). */
static void emit_mesh_loop(int walk_budget, gpu_text *t, const char *t_max, const char *found,
                           const char *body)
{
    enum { INNER = 255 };
    int outer = (walk_budget + INNER - 1) / INNER;
    char stop[96];
    snprintf(stop, sizeof stop, "node >= end || bg_tree_left <= 0.0%s%s", found ? " || " : "", found ? found : "");
    bgi_gpu_text_printf(t, "    for (int outer = 0; outer < %d; outer++) {\n        for (int inner = 0; inner < %d; inner++) {\n",
                        outer > 0 ? outer : 1, INNER);
    bgi_gpu_text_printf(t, "            if (%s)\n                break;\n            bg_tree_left -= 1.0;\n", stop);
    /* lo and hi are an interior node's box, or a leaf's first two corners (lo.w its triangle); either
     * way hi.w is the miss link, which a leaf's is too, since nothing follows a leaf but its miss.
     * The step's texels are addressed from one q = node / width (bg_mesh_at). */
    bgi_gpu_text_append(t, "            float q = node * bg_mesh_dims.y;\n"
                           "            vec4 lo = bg_mesh_node_at(bg_mesh_nodes, bg_mesh_dims, q);\n"
                           "            vec4 hi = bg_mesh_node_at(bg_mesh_nodes, bg_mesh_dims, q + bg_mesh_dims.y);\n"
                           "            float next = hi.w;\n"
                           "            if (lo.w < 0.0) {\n");
    bgi_gpu_text_printf(t, "                if (bg_tree_box(o, inv, %s, lo.xyz, hi.xyz))\n"
                           "                    next = node + 2.0;\n"
                           "            } else if (lo.w != skip) {\n", t_max);
    bgi_gpu_text_append(t, "                vec3 v0 = lo.xyz;\n                vec3 v1 = hi.xyz;\n"
                           "                vec3 v2 = bg_mesh_node_at(bg_mesh_nodes, bg_mesh_dims, q + 2.0 * bg_mesh_dims.y).xyz;\n"
                           "                float tt;\n                vec3 b;\n                bool f;\n");
    bgi_gpu_text_append(t, body);
    bgi_gpu_text_append(t, "            }\n            node = next;\n        }\n");
    bgi_gpu_text_printf(t, "        if (%s)\n            break;\n    }\n", stop);
}

/* The object-space ray of a mesh object and the start of its mesh's walk: base is the texel of the
 * mesh's root node and that of its first triangle (from the object's texel 4 in the tree, from its
 * own uniform when unrolled). */
static const char *const mesh_setup =
    "    float node = base.x;\n"
    "    float end = bg_mesh_node(bg_mesh_nodes, bg_mesh_dims, node + 1.0).w;\n"
    "    mat3 perm;\n    vec3 shear;\n"
    "    if (!bg_triangle_setup(d, perm, shear))\n        return false;\n"
    "    vec3 inv = bg_tree_inverse(d);\n"
    "    bg_tree_left -= 3.0; // the iterations that end this walk's loops (fused_layout.c reserves them per walk)\n";

void bgi_gpu_mesh_walks(int walk_budget, int filters, gpu_text *t)
{
    /* A filtered scene reads a copy's filter record once per walk and asks each hit that would count
     * whether its point is there: the side alone (a flag of the record) where no mesh cuts out, the
     * whole of bg_mesh_keeps where one does. A shadow segment runs from the point to the light, and
     * light travels it the other way, so for it the side that counts is the one the light sees. A
     * scene without front-only or cut-out meshes keeps the walk of before, text for text. */
    const char *keeps = "", *keeps_light = "";
    if (filters & GPU_MESH_CUT_OUT) {
        keeps = " &&\n                    bg_mesh_keeps(bg_mesh_tris, bg_mesh_dims, record, base.y, lo.w, b, f)";
        keeps_light = " &&\n                    bg_mesh_keeps(bg_mesh_tris, bg_mesh_dims, record, base.y, lo.w, b, !f)";
    } else if (filters & GPU_MESH_FRONT_ONLY) {
        keeps = " && (f || record.x != 1.0)";
        keeps_light = " && (!f || record.x != 1.0)";
    }
    const char *setup = filters & (GPU_MESH_CUT_OUT | GPU_MESH_FRONT_ONLY)
                            ? "    vec4 record = bg_mesh_tri(bg_mesh_tris, bg_mesh_dims, base.y - 3.0);\n"
                            : "";
    bgi_gpu_text_append(t, "// ---- generated: mesh objects\n"
                           "float bg_mesh_tri_j;  // the triangle of bg_mesh_nearest's hit, -1 none\n"
                           "vec3 bg_mesh_bary_j;  // and its weights\n"
                           "float bg_win_tri;     // the nearest hit's triangle (-1: not a mesh)\n"
                           "vec3 bg_win_bary;\n"
                           "vec3 bg_hit_p;        // the nearest hit's point\n"
                           "vec3 bg_hit_ng;       // a mesh hit's geometric normal, towards the ray\n"
                           "float bg_hit_off;     // and the offset a ray leaving it starts at\n");
    /* Nearest: t_limit is the best distance so far; equal distances go to the lower triangle, and the
     * test's range is widened past t_limit by a few ulps so that a tie with another object reaches
     * the caller's rule (lower object index). */
    bgi_gpu_text_append(t, "bool bg_mesh_nearest(vec4 ro, vec4 rd, float index, mat4 m, vec2 base, float t_limit, out float t, "
                           "out bool front)\n{\n"
                           "    t = 0.0;\n    front = false;\n    bg_mesh_tri_j = -1.0;\n    bg_mesh_bary_j = vec3(0.0);\n"
                           "    float skip = ro.w == index && rd.w <= -2.0 ? -2.0 - rd.w : -1.0;\n"
                           "    vec3 o = (m * vec4(ro.xyz, 1.0)).xyz;\n    vec3 d = (m * vec4(rd.xyz, 0.0)).xyz;\n");
    bgi_gpu_text_append(t, mesh_setup);
    bgi_gpu_text_append(t, setup);
    bgi_gpu_text_append(t, "    float best = t_limit;\n");
    char body[1024];
    snprintf(body, sizeof body,
             "                if (bg_triangle_intersect(o, perm, shear, v0, v1, v2, 0.0, best * 1.0000003, tt, b, f) &&\n"
             "                    (bg_mesh_tri_j < 0.0 || tt < best || (tt == best && lo.w < bg_mesh_tri_j))%s) {\n"
             "                    best = tt;\n                    t = tt;\n                    front = f;\n"
             "                    bg_mesh_tri_j = lo.w;\n                    bg_mesh_bary_j = b;\n"
             "                }\n", keeps);
    emit_mesh_loop(walk_budget, t, "best", NULL, body);
    bgi_gpu_text_append(t, "    if (node < end)\n        bg_tree_short = 1.0;\n    return bg_mesh_tri_j >= 0.0;\n}\n");

    bgi_gpu_text_append(t, "bool bg_mesh_blocked(vec3 p, vec3 l, float dist, mat4 m, vec2 base, float skip)\n{\n"
                           "    vec3 o = (m * vec4(p, 1.0)).xyz;\n    vec3 d = (m * vec4(l, 0.0)).xyz;\n"
                           "    float t_max = dist < 0.0 ? 1e38 : dist;\n    bool blocked = false;\n");
    bgi_gpu_text_append(t, mesh_setup);
    bgi_gpu_text_append(t, setup);
    snprintf(body, sizeof body,
             "                blocked = bg_triangle_intersect(o, perm, shear, v0, v1, v2, 0.0, t_max, tt, b, f)%s;\n",
             keeps_light);
    emit_mesh_loop(walk_budget, t, "t_max", "blocked", body);
    bgi_gpu_text_append(t, "    if (!blocked && node < end)\n        bg_tree_short = 1.0;\n    return blocked;\n}\n");

    /* A ray spawned at a mesh hit leaves its triangle: origin offset to the side it goes to, and the
     * lanes that name object and triangle. */
    bgi_gpu_text_append(t, "void bg_mesh_leave(vec4 hit, inout vec4 o, inout vec4 d)\n{\n"
                           "    if (bg_win_tri < 0.0)\n        return;\n"
                           "    float side = dot(d.xyz, bg_hit_ng) >= 0.0 ? bg_hit_off : -bg_hit_off;\n"
                           "    o = vec4(o.xyz + side * bg_hit_ng, bg_hit_index(hit.w));\n"
                           "    d.w = -2.0 - bg_win_tri;\n}\n");
}

void bgi_gpu_walk_globals(gpu_text *t)
{
    bgi_gpu_text_append(t, "float bg_tree_left;  // steps the pixel's walks may still take\n"
                           "float bg_tree_short; // 1.0 once a walk ran out of them\n");
}

int bgi_gpu_mesh_pass_budget(int walks)
{
    return GPU_MAX_LOOP - 64 - 3 * walks;
}

void bgi_gpu_mesh_pass_walks(int walks, int filters, gpu_text *t)
{
    bgi_gpu_walk_globals(t);
    bgi_gpu_mesh_walks(bgi_gpu_mesh_pass_budget(walks), filters, t);
}

bool bgi_gpu_mesh_library(gpu_text *t, const char **seen, int *seen_count, int seen_cap)
{
    return bgi_gpu_text_snippet(t, "bg_triangle.glsl", seen, seen_count, seen_cap) &&
           bgi_gpu_text_snippet(t, "bg_mesh.glsl", seen, seen_count, seen_cap);
}
