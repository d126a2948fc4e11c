/* The code of primary visibility by rasterisation (primary.c): the program that draws the tree
 * objects' footprints, and the exact test it shares with the fused program.
 *
 * The footprint only says where an object may be hit; the fragment runs the object's own exact test
 * on the pixel's own camera ray, the function the fused program's walk runs at a leaf (bg_hit_root_*,
 * or for one triangle of a mesh bg_triangle_intersect on the corners the walk reads), and writes the
 * distance as depth. So the map's nearest is the walk's nearest wherever it is unique, and the fused
 * program, which runs the same test again on the object the map names, gets the walk's bits. */
#include <stdio.h>

#include "fused.h"

#define SEEN_CAP 32

/* bg_primary_exact(ro, rd, object, tri, m, t, p_obj, n_obj, first_root, bary): object's test as the
 * tree walk's leaf runs it (m its camera-relative to_object), or for tri >= 0 the test of that one
 * triangle of the mesh object, as the mesh walk's leaf runs it; bary gets a triangle hit's weights. */
void bgi_gpu_primary_exact_source(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "// ---- generated: one tree object's exact test (primary visibility)\n"
                           "bool bg_primary_exact(vec4 ro, vec4 rd, float object, float tri, mat4 m, out float t, "
                           "out vec3 p_obj, out vec3 n_obj, out bool first_root, out vec3 bary)\n{\n"
                           "    t = 0.0;\n    p_obj = vec3(0.0);\n    n_obj = vec3(0.0, 1.0, 0.0);\n"
                           "    first_root = true;\n    bary = vec3(0.0);\n");
    if (l->kinds.mesh)
        bgi_gpu_text_append(t, "    if (tri >= 0.0) {\n"
                               "        vec2 base = bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, object, 4.0).zw;\n"
                               "        vec3 o = (m * vec4(ro.xyz, 1.0)).xyz;\n"
                               "        vec3 d = (m * vec4(rd.xyz, 0.0)).xyz;\n"
                               "        mat3 perm;\n        vec3 shear;\n"
                               "        if (!bg_triangle_setup(d, perm, shear))\n            return false;\n"
                               "        float k = base.y + 6.0 * tri;\n"
                               "        vec3 v0 = bg_mesh_tri(bg_mesh_tris, bg_mesh_dims, k).xyz;\n"
                               "        vec3 v1 = bg_mesh_tri(bg_mesh_tris, bg_mesh_dims, k + 1.0).xyz;\n"
                               "        vec3 v2 = bg_mesh_tri(bg_mesh_tris, bg_mesh_dims, k + 2.0).xyz;\n"
                               "        return bg_triangle_intersect(o, perm, shear, v0, v1, v2, 0.0, 1e38, t, bary, "
                               "first_root);\n    }\n");
    int shapes = 0;
    for (int s = 0; s < BG_SHAPE_COUNT_; s++)
        shapes += l->kinds.shape[s] ? 1 : 0;
    if (shapes == 0) {
        bgi_gpu_text_append(t, "    return false;\n}\n");
        return;
    }
    if (shapes > 1)
        bgi_gpu_text_append(t, "    float shape = bg_tree_fetch(bg_objects, bg_object_dims, BG_OBJECT_TEXELS, object, 3.0).x;\n");
    int seen = 0;
    for (int s = 0; s < BG_SHAPE_COUNT_; s++) {
        if (!l->kinds.shape[s])
            continue;
        const char *suffix = bgi_gpu_shape_suffix((bg_shape)s);
        if (++seen < shapes)
            bgi_gpu_text_printf(t, "    if (shape == %d.0)\n    ", s);
        bgi_gpu_text_printf(t, "    return bg_hit_root_%s(ro, rd, object, m, t, p_obj, n_obj, first_root);\n", suffix);
    }
    bgi_gpu_text_append(t, "}\n");
}

/* The library the exact test calls: the camera, the tree textures, each shape of the tree's and the
 * triangle code of its meshes. */
static bool library(const gpu_fused_layout *l, gpu_text *t)
{
    const char *seen[SEEN_CAP];
    int n = 0;
    static const char *const span[] = {"bg_shape_span", NULL};
    static const char *const root[] = {"bg_shape_span", "bg_hit_root", NULL};
    bool ok = bgi_gpu_text_snippet(t, "bg_stage_camera.glsl", seen, &n, SEEN_CAP) &&
              bgi_gpu_text_snippet(t, "bg_tree_textures.glsl", seen, &n, SEEN_CAP);
    for (int s = 0; s < BG_SHAPE_COUNT_ && ok; s++)
        if (l->kinds.shape[s])
            ok = bgi_gpu_text_snippet_renamed(t, bgi_gpu_fused_shape_file((bg_shape)s), span,
                                              bgi_gpu_shape_suffix((bg_shape)s), seen, &n, SEEN_CAP) &&
                 bgi_gpu_text_snippet_renamed(t, "bg_hit_root.glsl", root, bgi_gpu_shape_suffix((bg_shape)s), seen,
                                              &n, SEEN_CAP);
    if (ok && l->kinds.mesh)
        ok = bgi_gpu_mesh_library(t, seen, &n, SEEN_CAP);
    return ok;
}

bool bgi_gpu_primary_source(const gpu_fused_layout *l, gpu_text *functions, gpu_text *main, gpu_text *vertex_functions,
                            gpu_text *vertex)
{
    bool ok = library(l, functions);
    bgi_gpu_primary_exact_source(l, functions);
    const char *seen[SEEN_CAP];
    int n = 0;
    ok = ok && bgi_gpu_text_snippet(vertex_functions, "bg_primary_cover.glsl", seen, &n, SEEN_CAP);
    /* Indices travel as two varyings of 12 bits each: a whole number interpolated across a triangle
     * keeps a relative error of some float ulps, which reaches 0.5 past a few million; floor(x + 0.5)
     * of a part below 4096 is always the number. */
    bgi_gpu_text_printf(vertex,
                        "vec3 p0 = (bg_draw_to_camera * vec4(bg_c0, 1.0)).xyz;\n"
                        "vec3 p1 = (bg_draw_to_camera * vec4(bg_c1, 1.0)).xyz;\n"
                        "vec3 p2 = (bg_draw_to_camera * vec4(bg_c2, 1.0)).xyz;\n"
                        "vec2 win = bg_cover_corner(p0, p1, p2, bg_ident.z, bg_forward, bg_right, bg_up, bg_tan_half, "
                        "bg_size, bg_shift, bg_viewport, %s);\n"
                        "gl_Position = vec4(2.0 * win / bg_viewport - 1.0, 0.5, 1.0);\n"
                        "vec2 item = vec2(bg_draw_object >= 0.0 ? bg_draw_object : bg_ident.x, bg_ident.y);\n"
                        "vec2 high = floor(item / 4096.0);\n"
                        "bg_item = vec4(high.x, item.x - 4096.0 * high.x, high.y, item.y - 4096.0 * high.y);\n",
                        l->orthographic ? "true" : "false");
    bgi_gpu_text_printf(main,
                        "vec4 bg_whole = floor(bg_item + 0.5);\n"
                        "vec2 bg_it = vec2(bg_whole.x * 4096.0 + bg_whole.y, bg_whole.z * 4096.0 + bg_whole.w);\n"
                        "vec4 bg_ro, bg_rd, bg_w0;\n"
                        "%s(gl_FragCoord.xy + bg_shift, bg_size, vec3(0.0), bg_forward, bg_right, bg_up, bg_tan_half, "
                        "bg_ro, bg_rd, bg_w0);\n"
                        "mat4 bg_m = bg_tree_to_object(bg_objects, bg_object_dims, bg_it.x);\n"
                        "float bg_t;\nvec3 bg_p, bg_n, bg_b;\nbool bg_f;\n"
                        "if (!bg_primary_exact(bg_ro, bg_rd, bg_it.x, bg_it.y, bg_m, bg_t, bg_p, bg_n, bg_f, bg_b))\n"
                        "    discard;\n"
                        "gl_FragDepth = clamp(bg_t * bg_inv_dmax * bg_depth_scale, 0.0, 1.0);\n",
                        bgi_gpu_camera_function(l->orthographic));
    return ok && !functions->failed && !main->failed && !vertex_functions->failed && !vertex->failed;
}
