/* The shapes' GLSL in a pass over several objects. Every shape file defines the same function,
 * bg_shape_span, and every stage over it (a root, a shadow test) calls it by that name; a pass holds
 * one copy of the pair per distinct shape, both renamed by the shape's suffix (common/shapes.h), so
 * that bg_hit_root_sphere calls bg_shape_span_sphere. */
#include "../../common/shapes.h"
#include "shared.h"

#define SUFFIX_OF(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = name,
static const char *const shape_suffix[BG_SHAPE_COUNT_] = {BG_SHAPES(SUFFIX_OF)};
#undef SUFFIX_OF

#define FILE_OF(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = glsl,
static const char *const shape_file[BG_SHAPE_COUNT_] = {BG_SHAPES(FILE_OF)};
#undef FILE_OF

/* The most names a stage renames besides bg_shape_span. */
#define MAX_STAGE_NAMES 7

const char *bgi_gpu_shape_suffix(bg_shape shape)
{
    return shape_suffix[shape];
}

bool bgi_gpu_text_shape_stages(gpu_text *t, const bg_scene_state *state, const uint32_t *objects, int count,
                           const char *stage_file, const char *const *stage_names, const char **seen,
                           int *seen_count, int seen_cap)
{
    static const char *const span[] = {"bg_shape_span", NULL};
    const char *renamed[MAX_STAGE_NAMES + 2] = {"bg_shape_span"};
    int n = 1;
    for (int i = 0; stage_names[i]; i++) {
        if (n > MAX_STAGE_NAMES)
            return false;
        renamed[n++] = stage_names[i];
    }
    renamed[n] = NULL;

    bool done[BG_SHAPE_COUNT_] = {false};
    bool ok = true;
    for (int j = 0; j < count && ok; j++) {
        bg_shape shape = state->objects[objects[j]].shape;
        if (shape == BGI_SHAPE_MESH || done[shape]) /* a mesh's walk is generated (mesh_source.c) */
            continue;
        done[shape] = true;
        ok = bgi_gpu_text_snippet_renamed(t, shape_file[shape], span, shape_suffix[shape], seen, seen_count, seen_cap) &&
             bgi_gpu_text_snippet_renamed(t, stage_file, renamed, shape_suffix[shape], seen, seen_count, seen_cap);
    }
    return ok;
}

/* The library's file and function suffix per UV mapping (bg_uv_map_<suffix>; none has no file). */
static const char *const uv_file[BG_UV_COUNT_] = {NULL, "bg_uv_spherical.glsl", "bg_uv_planar.glsl",
                                                  "bg_uv_box.glsl", "bg_uv_cylindrical.glsl"};
static const char *const uv_suffix[BG_UV_COUNT_] = {"none", "spherical", "planar", "box", "cylindrical"};

const char *bgi_gpu_uv_file(bg_uv_mapping mapping)
{
    return uv_file[mapping];
}

const char *bgi_gpu_uv_suffix(bg_uv_mapping mapping)
{
    return uv_suffix[mapping];
}
