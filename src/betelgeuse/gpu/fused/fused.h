/* The fused plans (BG_PLAN_FUSED and its tree variant BG_PLAN_FUSED_TREE): one fragment pass per
 * frame computes the whole image. They use shared/ and nothing else of gpu/. */
#ifndef BG_GPU_FUSED_H
#define BG_GPU_FUSED_H

#include "../shared/shared.h"

/* ---- tree_textures.c ---- */
/* The tree variant's texture geometry: per texture (items per row, its inverse, 1 / width,
 * 1 / height), as bg_tree_textures.glsl reads it, and the node count. */
typedef struct gpu_tree_dims {
    float nodes[4], objects[4];
    float node_count;
} gpu_tree_dims;

/* One texture of the tree variant with the host copy of what it holds (held) and room to build the
 * next frame's (scratch), so that only a change is uploaded. */
typedef struct gpu_held_texture {
    macs_texture *texture;
    float *held, *scratch;
    size_t floats;
} gpu_held_texture;

typedef struct gpu_tree_textures {
    gpu_held_texture nodes, objects;
    gpu_tree_dims dims; /* of the prepared textures */
    uint64_t serial;    /* the commit (bg_scene_state.serial) they hold; 0 none */
} gpu_tree_textures;

/* False, with the reason, when the scene's tree, objects or meshes do not fit the GL's texture size. */
bool bgi_gpu_tree_textures_fit(const bg_renderer *r, const bg_scene_state *state, char *why, size_t size);
/* Makes the textures hold the committed scene's tree and objects, as seen from its camera. The
 * objects' texels hold their meshes' bases: r->meshes is prepared for the same commit first. The
 * caller has checked that they fit (bgi_gpu_tree_textures_fit) before it took the frame. */
bg_status bgi_gpu_tree_textures_prepare(bg_renderer *r, gpu_tree_textures *t, const bg_scene_state *state);
void bgi_gpu_tree_textures_release(const bg_allocator *a, gpu_tree_textures *t);

/* ---- fused.c ---- (with fused_layout.c, fused_uniforms.c, fused_source.c, tree_textures.c) */
/* The fused plan (BG_PLAN_FUSED): one fragment pass per frame computes the whole image. Its program
 * is a function of the scene's structure alone (gpu_fused_layout), so every value the scene or the
 * settings give lives in a uniform of the list below and a value-only re-commit compiles nothing. */

/* When a uniform (or parameter) exists: for every frame, with bounces, with lights, with the object
 * tree; per object unrolled (outside the tree)
 * always, with a tangent, with UVs; per material used, anisotropic, transparent, coated, both. */
typedef enum gpu_fused_need {
    GPU_FUSED_NEED_ALWAYS = 0, GPU_FUSED_NEED_BOUNCE, GPU_FUSED_NEED_LIGHTS, GPU_FUSED_NEED_TREE, GPU_FUSED_NEED_MESH,
    GPU_FUSED_NEED_TANGENT,
    GPU_FUSED_NEED_UV, GPU_FUSED_NEED_USED, GPU_FUSED_NEED_ANISO, GPU_FUSED_NEED_TRANSPARENT,
    GPU_FUSED_NEED_COAT, GPU_FUSED_NEED_COAT_ANISO,
    GPU_FUSED_NEED_SCRAMBLE, GPU_FUSED_NEED_LENS, GPU_FUSED_NEED_AREA, GPU_FUSED_NEED_ENV, GPU_FUSED_NEED_PATH
} gpu_fused_need;

/* Who a uniform belongs to: the frame, the light arrays (one element per light), an object, a material. */
typedef enum gpu_fused_scope { GPU_FUSED_FRAME = 0, GPU_FUSED_LIGHTS, GPU_FUSED_OBJECT, GPU_FUSED_MATERIAL } gpu_fused_scope;

/* Every uniform of the fused shader besides the material parameters (which follow as rows
 * "bg_m<k>_<local>", one per GPU_PARAMS entry): id, scope, GLSL name (%u: the object or
 * material index), type, when it exists, the fused_uniforms.c function that computes its value. The
 * declarations, the uniform budget, the values and the names the generated source uses all come
 * from this list and GPU_PARAMS. */
#define GPU_FUSED_UNIFORMS(X)                                                   \
    X(SIZE, FRAME, "bg_size", VEC2, ALWAYS, image_size)                         \
    X(SHIFT, FRAME, "bg_shift", VEC2, ALWAYS, pixel_shift)                      \
    X(FORWARD, FRAME, "bg_forward", VEC3, ALWAYS, camera_forward)               \
    X(RIGHT, FRAME, "bg_right", VEC3, ALWAYS, camera_right)                     \
    X(UP, FRAME, "bg_up", VEC3, ALWAYS, camera_up)                              \
    X(TAN_HALF, FRAME, "bg_tan_half", VEC2, ALWAYS, camera_tan_half)            \
    X(BACKGROUND, FRAME, "bg_background", VEC3, ALWAYS, background)             \
    X(OUTPUT, FRAME, "bg_output", VEC2, ALWAYS, output_encoding)                \
    X(MIN_WEIGHT, FRAME, "bg_min_weight", FLOAT, BOUNCE, min_weight)            \
    X(TREE_DIMS, FRAME, "bg_tree_dims", VEC4, TREE, tree_node_dims)             \
    X(OBJECT_DIMS, FRAME, "bg_object_dims", VEC4, TREE, tree_object_dims)       \
    X(TREE_NODES, FRAME, "bg_tree_count", FLOAT, TREE, tree_node_count)         \
    X(MESH_DIMS, FRAME, "bg_mesh_dims", VEC4, MESH, tree_mesh_dims)             \
    X(PIXEL_AT, FRAME, "bg_pixel_at", VEC2, SCRAMBLE, pixel_at)                 \
    X(SAMPLE_OF, FRAME, "bg_sample_of", VEC4, SCRAMBLE, sample_of)              \
    X(SAMPLE_PERM, FRAME, "bg_sample_perm", VEC4, SCRAMBLE, sample_perm)        \
    X(LENS, FRAME, "bg_lens", VEC2, LENS, lens)                                 \
    X(ENV_INFO, FRAME, "bg_env_info", VEC4, ENV, env_info)                       \
    X(LIGHT_POS, LIGHTS, "bg_lpos", VEC4, LIGHTS, light_position)               \
    X(LIGHT_RAD, LIGHTS, "bg_lrad", VEC3, LIGHTS, light_radiance)               \
    X(LIGHT_ATT, LIGHTS, "bg_latt", VEC3, LIGHTS, light_attenuation)            \
    X(LIGHT_SPOT, LIGHTS, "bg_lspot", VEC4, LIGHTS, light_spot)                 \
    X(LIGHT_EXP, LIGHTS, "bg_lexp", FLOAT, LIGHTS, light_exponent)              \
    X(LIGHT_EDGE_U, LIGHTS, "bg_ledge_u", VEC4, AREA, light_edge_u)             \
    X(LIGHT_EDGE_V, LIGHTS, "bg_ledge_v", VEC4, AREA, light_edge_v)             \
    X(LIGHT_PATH, LIGHTS, "bg_lpath", VEC4, PATH, light_path)                   \
    X(ID, OBJECT, "bg_o%u_id", FLOAT, ALWAYS, object_id)                        \
    X(TO_OBJECT, OBJECT, "bg_o%u_to_object", MAT4, ALWAYS, object_to_object)    \
    X(NORMAL, OBJECT, "bg_o%u_normal", MAT3, ALWAYS, object_normal)             \
    X(TO_WORLD3, OBJECT, "bg_o%u_to_world3", MAT3, TANGENT, object_to_world3)   \
    X(UV_SCALE, OBJECT, "bg_o%u_uv_scale", VEC2, UV, object_uv_scale)           \
    X(MESH_BASE, OBJECT, "bg_o%u_mesh", VEC2, MESH, object_mesh_base)           \
    X(IOR, MATERIAL, "bg_m%u_ior", FLOAT, TRANSPARENT, material_ior)

typedef enum gpu_fused_uniform {
#define GPU_FUSED_UNIFORM_ENUM_(id, scope, name, type, need, value) GPU_FUSED_U_##id,
    GPU_FUSED_UNIFORMS(GPU_FUSED_UNIFORM_ENUM_)
#undef GPU_FUSED_UNIFORM_ENUM_
    GPU_FUSED_U_COUNT_
} gpu_fused_uniform;

/* The row of material parameter p in the uniform list (after the GPU_FUSED_UNIFORMS rows). */
#define GPU_FUSED_PARAM_ROW(p) (GPU_FUSED_U_COUNT_ + (int)(p))
#define GPU_FUSED_ROW_COUNT (GPU_FUSED_U_COUNT_ + GPU_P_COUNT_)

/* A material as the fused shader specialises it; only used materials get code and uniforms. */
typedef struct gpu_fused_material {
    bool used, aniso, coat, transparent;
    bool glossy;                          /* its reflected ray is drawn from its lobe (bg_glossy.glsl) */
    bool bounce;                          /* may spawn a secondary ray (bgi_gpu_material_may_bounce) */
    uint32_t light;                       /* the material of a visible area light's object: 1 + the
                                             light's index (bg_object_data.light), else 0 */
    bool textured;                        /* some parameter samples a texture: its objects need UVs */
    uint32_t texture[GPU_P_COUNT_]; /* scene texture (1-based) of each parameter, 0 none */
    int channel[GPU_P_COUNT_];      /* the texel channel of a textured scalar */
    int sampler[GPU_P_COUNT_];      /* the shader's sampler of that texture, -1 none */
} gpu_fused_material;

typedef struct gpu_fused_object {
    bg_shape shape;
    uint32_t material;
    bg_uv_mapping uv_mapping;
    bool casts_shadows;
    bool in_tree; /* walked from the tree's textures rather than unrolled with its own uniforms */
    uint32_t slot; /* outside the tree: its place among those objects, which names its uniforms (the
                      object's index is a uniform too, so the program does not change when objects
                      before it come and go) */
} gpu_fused_object;

/* What the tree variant's code depends on: which shapes, mappings and needs its objects have (never
 * how many objects or which), so that adding or moving objects of those kinds compiles nothing. */
typedef struct gpu_fused_tree_kinds {
    bool shape[BG_SHAPE_COUNT_];    /* shapes of tree objects */
    bool caster[BG_SHAPE_COUNT_];   /* shapes of tree objects that cast shadows */
    bool mapping[BG_UV_COUNT_];     /* UV mappings some tree object needs (for UVs or a tangent) */
    bool uv, tangent;               /* some tree object needs UVs / a tangent */
    bool all_cast;                  /* every tree object casts shadows: the walk need not ask */
    bool mesh, mesh_casts;          /* some tree object is a mesh / a mesh that casts shadows */
} gpu_fused_tree_kinds;

/* Everything the fused program depends on: the scene's structure and the bounce depth. Values
 * never enter the program; rays_needed, the one field a value (min_weight) sets, only decides
 * whether the program may run. */
typedef struct gpu_fused_layout {
    uint32_t object_count, material_count, light_count;
    gpu_fused_object *objects;
    gpu_fused_material *materials;
    uint32_t *samplers;  /* scene textures (1-based) in sampler order */
    gpu_texture_mode *sampler_modes; /* how each is sampled: its size, wrap and filter are in the text */
    int sampler_count;
    bool filters;        /* some sampler is GL_LINEAR: the program holds bg_texture_filter.glsl */
    bool srgb;           /* some sampler decodes 8-bit sRGB: the program holds bg_texture_srgb.glsl and
                            samples the table bg_srgb_table, its last input */
    bool transparent, aniso, coat, shadows; /* some used material is / some caster can shadow another */
    int max_depth;       /* bounce levels traced: settings.max_depth, 0 when no material bounces */
    int stack;           /* pending rays the shader holds: max_depth with transparency, else 0 */
    bool light_loop;     /* lights in a loop rather than unrolled (GPU_FUSED_UNROLLED_SHADOW_TESTS) */
    int loop_rays;       /* the trace loop's bound: every ray of the full tree, within GPU_MAX_LOOP */
    double rays_needed;  /* the most rays a pixel can follow, min_weight's pruning counted */
    bool tree;           /* BG_PLAN_FUSED_TREE: the bounded objects are walked from the tree's textures */
    uint32_t *unrolled;  /* the objects outside the tree, ascending (unrolled_count of them) */
    uint32_t unrolled_count;
    uint32_t tree_count; /* objects in the tree (not part of the program) */
    gpu_fused_tree_kinds kinds;
    bool mesh;           /* some object is a mesh, in the tree or unrolled: the mesh textures are bound */
    uint32_t unrolled_meshes; /* mesh objects outside the tree, each walked with its own uniforms */
    int mesh_filters;    /* bgi_gpu_meshes_filters: what the mesh walks and hits test */
    int walk_budget;     /* tree steps one pixel may take in all its walks: what the loop limit leaves */
    bool lens;           /* the camera has an aperture (docs/shading.md 1.4) */
    bool orthographic;   /* the camera's rays are parallel (docs/shading.md 1.5) */
    bool area;           /* some light is an area light (docs/shading.md 7) */
    bool glossy;         /* some used material is glossy (docs/shading.md 9.1) */
    bool env;            /* misses see the environment (docs/shading.md 7.1) */
    bool env_light;      /* the environment lights the scene too, after the lights */
    bool env_importance; /* ... drawn from its importance tables (two more inputs) */
    int env_sampler;     /* the environment texture's sampler, -1 none */
    bool path;           /* BG_INTEGRATOR_PATH (docs/shading.md 13): a chain of one ray per hit, with
                            next-event estimation and the way on drawn at each hit */
    bool path_ambient;   /* ... adding the ambient term at each hit (settings.path_ambient) */
    bool visible_lights; /* ... and some visible area light's object may be met by chance */
    bool primary;        /* camera rays take their tree hit from the rasterised map (primary.c): the
                            program samples it as its last input, bg_primary */
} gpu_fused_layout;
/* Shadow tests (lights x casters) up to which lights are unrolled. Each unrolled light inlines its
 * own copy of every caster's test: at 2 lights x 17 casters (many_spheres) the program took 14 s
 * to compile on a loaded llvmpipe, 5.6 s with a loop over the lights, which renders 15-35 % slower
 * (many_spheres, many_lights, glass at 256x256). */
#define GPU_FUSED_UNROLLED_SHADOW_TESTS 16

/* The values of one render, for the uniforms. */
typedef struct gpu_fused_values {
    const bg_scene_state *state;
    const bg_render_settings *settings;
    const gpu_tree_dims *tree;   /* NULL without the tree */
    const gpu_meshes *meshes;    /* the mesh textures' geometry and every mesh object's bases */
    int width, height;
    bool float_output;
    const gpu_view *view; /* the frame size, the window and the sample */
} gpu_fused_values;

/* The fused plan, unrolled (BG_PLAN_FUSED) and with the object tree (BG_PLAN_FUSED_TREE). Under
 * BG_PLAN_AUTO either declines a frame beyond the GL limits, beyond the bounds it was measured
 * within, or whose program GL refuses. */
extern const gpu_plan bgi_gpu_fused_plan;
extern const gpu_plan bgi_gpu_fused_tree_plan;
/* Frees the fused plan's program, textures and cache. */
void bgi_gpu_fused_release(bg_renderer *r);

/* ---- fused_layout.c ---- */
/* Fills the layout of the committed scene for the settings (arrays from the renderer's allocator),
 * with tree the objects of the scene's object tree walked from textures and srgb_table whether 8-bit
 * sRGB textures are decoded through the table (bgi_gpu_srgb_table); false when out of memory. */
bool bgi_gpu_fused_layout_build(const bg_allocator *a, const bg_scene_state *state, const bg_render_settings *settings,
                            bool tree, bool srgb_table, gpu_fused_layout *out);
void bgi_gpu_fused_layout_free(const bg_allocator *a, gpu_fused_layout *layout);
/* Whether a material has what a per-material uniform or parameter needs (the "need" columns). */
bool bgi_gpu_fused_material_has(const gpu_fused_material *m, gpu_fused_need need);
/* Whether an object of the layout's material samples textures / needs a shading tangent. */
bool bgi_gpu_fused_object_uv(const gpu_fused_layout *l, uint32_t object);
/* Lights the shader evaluates at a hit: the scene's, and the environment when it lights. */
uint32_t bgi_gpu_fused_layout_lights(const gpu_fused_layout *l);
/* Whether the program walks a tree: the tree variant with some object in the scene's tree. */
bool bgi_gpu_fused_layout_walks(const gpu_fused_layout *l);
/* Whether the program computes the sample points of docs/shading.md 1.3 (the scramble uniforms):
 * for a distribution effect, or for the path integrator, whose every hit draws its own. */
bool bgi_gpu_fused_layout_samples(const gpu_fused_layout *l);
/* Whether the program's walks (the object tree's or a mesh's) share a step budget per pixel, so
 * that a pixel may run out and go to the CPU reference. */
bool bgi_gpu_fused_layout_budgeted(const gpu_fused_layout *l);
bool bgi_gpu_fused_object_tangent(const gpu_fused_layout *l, uint32_t object);

/* ---- fused_uniforms.c ---- */
/* The GLSL name of row `row` (a gpu_fused_uniform or GPU_FUSED_PARAM_ROW) for object or material i
 * (an object's uniforms are named by its slot). */
void bgi_gpu_fused_uniform_name(const gpu_fused_layout *l, int row, uint32_t i, char *name, size_t size);
/* Whether row exists for object or material i (frame and light rows: i is ignored). */
bool bgi_gpu_fused_uniform_present(const gpu_fused_layout *l, int row, uint32_t i);
/* Uniform components the layout declares, counted in whole vec4s as old hardware allocates them. */
int bgi_gpu_fused_uniform_components(const gpu_fused_layout *l);
/* The uniform declarations of the layout into a new array (names kept in *names, both freed with
 * bgi_gpu_fused_uniforms_free); false when out of memory. */
bool bgi_gpu_fused_uniforms_declare(const bg_allocator *a, const gpu_fused_layout *l, macs_uniform_desc **out,
                                int *count, char **names);
void bgi_gpu_fused_uniforms_free(const bg_allocator *a, macs_uniform_desc *desc, char *names);
/* Sets every uniform of the layout in the pass from the render's values; reports errors. */
bg_status bgi_gpu_fused_uniforms_set(bg_renderer *r, macs_pass *pass, const gpu_fused_layout *l, const gpu_fused_values *v);

/* ---- primary.c ---- (with primary_source.c) */
/* Primary visibility by rasterisation: per pixel, which tree object (and which of a mesh's
 * triangles) the camera ray meets first, or that none does, or that two tie. */
typedef struct gpu_primary gpu_primary;

/* Why the layout's frames cannot rasterise their camera rays on this GL (into why), or true. */
bool bgi_gpu_primary_supported(const bg_renderer *r, const gpu_fused_layout *l, char *why, size_t size);
/* Whether BG_PRIMARY_AUTO rasterises a frame of `pixels` pixels of the scene (the layout supports it). */
bool bgi_gpu_primary_pays(const bg_scene_state *state, const gpu_fused_layout *l, uint64_t pixels);
/* Draws the frame's map (of the output's size, for the view's sample and window) into *map. */
bg_status bgi_gpu_primary_draw(bg_renderer *r, gpu_primary **p, const gpu_fused_layout *l, const bg_scene_state *state,
                               const gpu_tree_textures *tree, int width, int height, macs_texture **map);
void bgi_gpu_primary_release(const bg_allocator *a, gpu_primary **p);

/* primary_source.c: the exact test of one tree object (and triangle) that the map's fragments and the
 * fused program's camera rays share, so that both see the same bits: bg_primary_exact. */
void bgi_gpu_primary_exact_source(const gpu_fused_layout *l, gpu_text *t);
/* The rasterising program: its fragment functions and main, its vertex functions and main. */
bool bgi_gpu_primary_source(const gpu_fused_layout *l, gpu_text *functions, gpu_text *main, gpu_text *vertex_functions,
                            gpu_text *vertex);
/* The GLSL file of an analytic shape (BG_SHAPES). */
const char *bgi_gpu_fused_shape_file(bg_shape shape);

/* ---- fused_source.c ---- */
/* The fused shader of a layout: its functions (the glsl110/ library and the generated scene code)
 * into functions, its main into main, and the expression written to the output. False when a
 * library file is missing or memory ran out. */
bool bgi_gpu_fused_source(const gpu_fused_layout *l, gpu_text *functions, gpu_text *main, const char **output);
/* Writes one light's term, the light given by its index into the light arrays (a number, or the
 * loop's i), at an indent. */
typedef void (*gpu_fused_light_term)(const gpu_fused_layout *l, gpu_text *t, const char *i, const char *indent);
/* Every light in the scene's order: unrolled, or a loop of the scene's exact size over the light
 * arrays where unrolling would inline too many shadow tests (layout.light_loop). */
void bgi_gpu_fused_each_light(const gpu_fused_layout *l, gpu_text *t, gpu_fused_light_term term);

/* ---- fused_path_source.c ---- */
/* The path integrator's generated functions (after bg_fused_surface): the environment's radiance,
 * the miss, the visible lights met by chance, the lights sampled towards a hit. */
void bgi_gpu_fused_path_functions(const gpu_fused_layout *l, gpu_text *functions);
/* The path integrator's main after the camera ray: its chain of hits. */
void bgi_gpu_fused_path_main(const gpu_fused_layout *l, gpu_text *main);


#endif
