/* The GPU renderer's internals (docs/gpu_pipeline.md describes the frame). Every pass is a MACS
 * render pass; only MACS touches GL. */
#ifndef BG_GPU_INTERNAL_H
#define BG_GPU_INTERNAL_H

#include "../../macs/first_error.h"
#include "../scene/scene_internal.h"
#include "../common/render_view.h"

#define GPU_LIGHTS_PER_GROUP 4
/* "No object" in the skip and inside lanes of a ray map (object indices are >= 0). */
#define GPU_NONE -1.0f

/* G-buffer slots. HIT, NORMAL, BASE and ONCE are always written; the others only when some material
 * of the scene needs them (or when specialisation is switched off). */
typedef enum gpu_slot {
    GPU_SLOT_HIT = 0, /* position, hit code (docs/gpu_pipeline.md: object index, side, thin) */
    GPU_SLOT_NORMAL,  /* unit normal facing the ray, base roughness */
    GPU_SLOT_BASE,    /* base reflectance, base isotropy */
    GPU_SLOT_ONCE,    /* path weight x (emission + opaque x ambient), index of refraction */
    GPU_SLOT_XPARENT, /* path weight x opaque, transparency */
    GPU_SLOT_TANGENT, /* unit tangent, coat isotropy */
    GPU_SLOT_COAT,    /* coat reflectance, coat roughness (< 0: no coat) */
    GPU_SLOT_MESH,    /* a mesh hit's offset: the geometric normal towards the ray times the start
                         offset of rays leaving it (docs/shading.md 2.10), and its triangle; w -1 off
                         a mesh, GPU_MESH_SHORT where a walk ran out of steps */
    GPU_SLOT_COUNT
} gpu_slot;

/* What the committed scene (and the settings) make the shaders contain. */
typedef struct gpu_features {
    bool transparent; /* some material may be transparent: XPARENT slot, refraction spawn */
    bool aniso;       /* some layer may have isotropy < 1: TANGENT slot */
    bool coat;        /* some material has a coat: COAT slot */
    bool bounce;      /* some material may reflect or refract: spawn passes */
    bool generic;     /* specialisation off: every slot, every texture lane */
    bool mesh;        /* some object is a mesh: MESH slot, the mesh textures, the marks of short walks */
    bool slot[GPU_SLOT_COUNT];
    int slot_count;
} gpu_features;

/* One set of ray maps: origin (xyz, skip index), direction (xyz, inside index), path weight
 * (rgb, alive 1 / dead 0). */
typedef struct gpu_ray_set {
    macs_texture *origin, *dir, *weight;
} gpu_ray_set;

/* Most objects one intersection or shadow pass tests (docs/gpu_pipeline.md): bounds the shader's
 * length where no GL limit does (instruction counts are not queryable in GL 2.1). */
#define GPU_BATCH_MAX 8
/* Most scene textures (plus the white texel) one object's material samples. */
#define GPU_HIT_MAX_TEXTURES 9

/* One pass over several objects. */
typedef struct gpu_batch {
    macs_pass *pass;
    int first, count; /* intersection: objects first .. first + count - 1, in pass order; shadow:
                         entries first .. of gpu_passes.casters */
    int group;        /* shadow: the light group */
} gpu_batch;

/* Passes built for one scene structure, image size and skip setting. */
typedef struct gpu_passes {
    macs_pass *camera;
    macs_pass *mark;
    macs_pass *background;
    macs_pass *once;          /* ambient and emission, weighted in the G-buffer */
    gpu_batch *hit;           /* intersection batches in pass order */
    int hit_count;
    gpu_batch *shadow;        /* shadow batches, by light group */
    int shadow_count;
    uint32_t *casters;        /* objects of the shadow batches, group by group */
    bool *caster_blocks;      /* false: in the pass without a test (shadow cull switched off) */
    int caster_count;
    macs_pass **light;        /* per light group */
    macs_pass *reflect, *refract;
    macs_pass *resolve;
    macs_pass *resolve_float; /* accumulation to a float target texture; made at the first such frame */
    int object_count, group_count;
} gpu_passes;

/* The key that decides whether cached passes still fit. */
typedef struct gpu_cache_key {
    const bg_scene *scene;
    uint64_t commit_count;
    uint64_t fingerprint; /* bgi_gpu_scene_fingerprint of the committed state */
    uint64_t textures;    /* bgi_gpu_textures_fingerprint of it */
    int width, height;
    unsigned disable_skips;
    bg_output_encoding encoding;
    bool bounces;       /* max_depth > 0 */
    bool background_on; /* a non-black background needs its pass */
    double min_weight;
    bool valid;
} gpu_cache_key;

/* The pixels one pass computes: the window of the frame and the sample (pixels.sample_first, one
 * sample per pass), and what the camera stage adds to gl_FragCoord.xy for it (docs/shading.md 1.1):
 * the window's offset in the frame in GL's bottom-up rows plus the sample's offset from the pixel
 * centre, all multiples of 2^-BGI_SAMPLE_BITS, so the sum is exact in float and a window's rays are
 * bit for bit the full frame's. */
typedef struct gpu_view {
    bgi_render_view pixels;
    float shift[2];
} gpu_view;

struct bg_renderer {
    bg_allocator allocator;
    bg_logger logger;
    macs_first_error error; /* status is a bg_status; fail.c records it */

    macs_context *ctx;
    macs_limits limits; /* effective */
    bool float_depth;
    bool half_gbuffer; /* asked for and found renderable at creation (bgi_gpu_half_probe) */
    bg_render_stats stats;

    /* Size-dependent targets. */
    int width, height;
    macs_texture *gbuffer[GPU_SLOT_COUNT];
    macs_texture *accum, *vis, *encoded;
    macs_depth_stencil *depth;
    gpu_ray_set *sets;
    int set_count;
    float *readback;
    size_t readback_size;

    /* Scene-dependent objects. */
    gpu_cache_key key;
    gpu_features features;
    macs_texture **textures; /* the scene's textures on the GPU */
    uint32_t texture_count;
    macs_texture *white;     /* 1x1 white, NEAREST: the texture lane of an untextured parameter */
    gpu_passes passes;
    gpu_passes retired; /* the previous scene's, alive while passes are built (bgi_gpu_passes_retire) */
    struct gpu_fused *fused; /* the fused plan's cached program and targets (fused.c); NULL until used */
    struct gpu_fused_tree *meshes; /* the multipass's mesh textures and marks (fused_tree.c); NULL until used */
    gpu_view view;           /* of the pass being rendered (frame.c sets it) */
};


/* Where a frame ends: the caller's image, read back with its rows flipped to top-down (image set), or
 * the caller's texture, written on the GPU with GL's rows, bottom row first (texture set). */
typedef struct gpu_frame_out {
    bg_image *image;       /* bg_render_gpu; NULL for a texture */
    size_t stride;         /* the image's checked row stride */
    macs_texture *texture; /* bg_render_gpu_to_texture; NULL for an image */
    int width, height;
    bool as_float;         /* RGBA32F image, RGBA32F or RGBA16F texture: linear radiance; else RGBA8 */
    const char *fn;        /* the entry point, for messages */
} gpu_frame_out;

#if defined(__GNUC__)
#define GPU_PRINTF_(format_arg, first_arg) __attribute__((__format__(__printf__, format_arg, first_arg)))
#else
#define GPU_PRINTF_(format_arg, first_arg)
#endif

/* ---- fail.c: the error sink; calls nothing else in gpu/ ---- */
/* Records the first error with a message and logs it; returns status. */
bg_status bgi_gpu_fail(bg_renderer *r, bg_status status, const char *format, ...) GPU_PRINTF_(3, 4);
/* Turns a MACS failure into a renderer error carrying MACS's message. */
bg_status bgi_gpu_fail_macs(bg_renderer *r, macs_status ms, const char *what);
/* Logs a diagnostic that is not an error (a warning: something worked around; info: a choice made). */
void bgi_gpu_log(const bg_renderer *r, bg_log_level level, const char *format, ...) GPU_PRINTF_(3, 4);

/* ---- renderer.c ---- */
/* Frees every GPU object (passes, targets, textures) so the next render starts afresh. */
void bgi_gpu_release_all(bg_renderer *r);

/* ---- origin.c ---- */
/* Every position the GPU sees is relative to the camera (float bits stay near the scene, not near
 * the world origin): the object's to_object for such points, column-major, and a moved point. */
void bgi_gpu_origin_to_object(const bg_scene_state *state, uint32_t object, float m16[16]);
void bgi_gpu_origin_point(const bg_scene_state *state, const bg_vec3 *p, float out[3]);

/* ---- shader_source.c ---- */
/* A growing string built through the renderer's allocator; a failed append leaves it failed. */
typedef struct gpu_text {
    const bg_allocator *allocator;
    char *s;
    size_t len, cap;
    bool failed;
} gpu_text;
void bgi_gpu_text_init(gpu_text *t, const bg_allocator *a);
void bgi_gpu_text_append(gpu_text *t, const char *s);
void bgi_gpu_text_printf(gpu_text *t, const char *format, ...);
/* Appends a glsl110/ library file with everything its "// requires:" line names first (each file
 * once per text, tracked in seen), without the #version lines. False if a file is missing. */
bool bgi_gpu_text_snippet(gpu_text *t, const char *file, const char **seen, int *seen_count, int seen_cap);
void bgi_gpu_text_free(gpu_text *t);
/* Like bgi_gpu_text_snippet, with each name in the NULL-terminated list renamed to name_suffix by
 * #define around the file, which is then forgotten by seen so that the next suffix inlines it again:
 * one program can hold several shapes' copies of a function (hit_pass.c, shadow batches). */
bool bgi_gpu_text_snippet_renamed(gpu_text *t, const char *file, const char *const *names, const char *suffix,
                              const char **seen, int *seen_count, int seen_cap);

/* ---- shape_source.c ---- */
/* The suffix of a shape's functions in a pass (bg_hit_root_sphere): its name in common/shapes.h. */
const char *bgi_gpu_shape_suffix(bg_shape shape);
/* Appends, once per distinct shape of objects[0 .. count - 1] (indices into state->objects), the
 * shape's bg_shape_*.glsl and then stage_file, both with bg_shape_span and the NULL-terminated
 * stage_names renamed by the shape's suffix. False if a file is missing. */
bool bgi_gpu_text_shape_stages(gpu_text *t, const bg_scene_state *state, const uint32_t *objects, int count,
                           const char *stage_file, const char *const *stage_names, const char **seen,
                           int *seen_count, int seen_cap);

/* ---- features.c ---- */
/* Whether a material can spawn a secondary ray somewhere (mirror share or transparency). */
bool bgi_gpu_material_may_bounce(const bg_material *m);
/* Decides slots and shader features from the committed scene; generic switches specialisation off. */
void bgi_gpu_features_detect(const bg_scene_state *state, bool generic, gpu_features *f);

/* ---- fingerprint.c ---- */
/* A hash of every committed value the renderer's passes and textures depend on. */
uint64_t bgi_gpu_scene_fingerprint(const bg_scene_state *state, uint64_t textures);
/* The part of it that the uploaded scene textures depend on (sizes, modes, texels), which the
 * fingerprint takes as its textures argument: a commit that leaves it alone keeps the uploads. */
uint64_t bgi_gpu_textures_fingerprint(const bg_scene_state *state);

/* ---- bounds.c ---- */
/* The dmax of every level 0..max_depth (docs/gpu_pipeline.md); fixed when settings->dmax > 0. */
void bgi_gpu_dmax_levels(const bg_scene_state *state, const bg_render_settings *settings, double *dmax);
/* The pixel rectangle (GL window coordinates, bottom-up) that holds every camera ray able to hit a
 * bounded object; false when the object may cover the whole image (or is behind the camera). */
bool bgi_gpu_object_scissor(const bg_scene_state *state, uint32_t object, const gpu_view *view, int rect[4]);

/* ---- targets.c ---- */
/* Creates *out as a w x h texture of format unless it exists; what names it in a failure. */
bg_status bgi_gpu_texture_ensure(bg_renderer *r, int w, int h, macs_format format, macs_texture **out, const char *what);
/* (Re)creates the size-dependent targets for width x height and the features' G-buffer slots. */
bg_status bgi_gpu_targets_prepare(bg_renderer *r, int width, int height);
/* Whether RGBA16F works as a render target next to RGBA32F (one small pass, read back); false with
 * the reason in why. Leaves no MACS error behind that was not there before. */
bool bgi_gpu_half_probe(bg_renderer *r, char *why, size_t why_size);
/* The texture format of a G-buffer slot under the renderer's half_gbuffer choice. */
macs_format bgi_gpu_slot_format(const bg_renderer *r, gpu_slot slot);
/* Ray set number index from the pool, creating it when needed. */
bg_status bgi_gpu_ray_set_get(bg_renderer *r, int index, gpu_ray_set **out);
/* Uploads the scene's textures (and the white texel) for the hit passes. */
bg_status bgi_gpu_scene_textures_prepare(bg_renderer *r, const bg_scene_state *state);
void bgi_gpu_targets_release(bg_renderer *r);
void bgi_gpu_scene_textures_release(bg_renderer *r);
/* Uploads one scene texture as the samplers read it (RGBA32F, GL_LINEAR, its wrap). */
bg_status bgi_gpu_scene_texture_upload(bg_renderer *r, const bg_texture_data *t, macs_texture **out);

/* ---- pass_create.c: making one pass; calls only shader_source.c and fail.c ---- */
/* Fills the parts of a pass description every pass sets; depth, stencil, blend and colour mask stay
 * zero (off, default) for the caller to set. */
void bgi_gpu_pass_desc_init(macs_pass_desc *d, const char *main, const macs_input_desc *inputs,
                        macs_texture *const *input_tex, int input_count, const macs_uniform_desc *uniforms,
                        int uniform_count, const macs_output_desc *outputs, macs_texture *const *output_tex,
                        int output_count);
/* Creates one pass whose functions are the listed glsl110/ files (plus extra text); reports errors. */
bg_status bgi_gpu_pass_create(bg_renderer *r, const char *what, const char *const *files, const char *extra,
                          macs_pass_desc *desc, macs_pass **out);
/* Creates a pass. With trial, a program GL refuses (compile or link) on a context with no earlier
 * error is not an error: *out stays NULL, *refused gets the status and why GL's message, and the
 * MACS error is forgotten; a caller then takes another way and says so. */
bg_status bgi_gpu_pass_create_trial(bg_renderer *r, const char *what, macs_pass_desc *desc, bool trial, macs_pass **out,
                                macs_status *refused, char *why, size_t why_size);
/* Creates a pass from assembled functions. With trial, a shader GL refuses (compile or link) is
 * logged as a warning and forgotten: *out stays NULL, *rejected true, BG_OK returned. */
bg_status bgi_gpu_pass_try(bg_renderer *r, const char *what, const char *functions, macs_pass_desc *desc, bool trial,
                       macs_pass **out, bool *rejected);
/* bgi_gpu_pass_try over assembled texts (desc->main already points into main): fails with a message
 * when a text ran out of memory or a glsl110 file was missing (files_found false); frees both. */
bg_status bgi_gpu_pass_from_texts(bg_renderer *r, const char *what, gpu_text *main, gpu_text *functions, bool files_found,
                              macs_pass_desc *desc, bool trial, macs_pass **out, bool *rejected);

/* ---- ray_passes.c: the passes that make, count, end and spawn rays ---- */
/* The camera, mark, background, reflection, refraction and resolve passes, as the renderer's key
 * decides them (background_on, bounces), over ray set 0's maps and the renderer's targets. */
bg_status bgi_gpu_ray_passes_build(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings);
/* The pass that copies the accumulation's linear radiance, alpha 1, into target (RGBA32F or RGBA16F):
 * the float frame's end in a texture (the RGBA8 one is the resolve pass's). */
bg_status bgi_gpu_resolve_float_pass_build(bg_renderer *r, macs_texture *target);
/* Sets the camera pass's uniforms for the committed camera and r->view (every frame: the view's
 * shift changes with the window and the sample). */
bg_status bgi_gpu_camera_uniforms_set(bg_renderer *r, const bg_scene_state *state);

/* ---- passes.c: every pass of a frame, in the order the frame needs them ---- */
/* Builds every pass of the frame for the scene, with the renderer's targets bound as outputs. */
bg_status bgi_gpu_passes_build(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings);
void bgi_gpu_passes_release(bg_renderer *r);
/* Moves the passes aside instead of destroying them, so that while the next ones are built MACS's
 * program cache still holds every program they share: a commit that changes only values compiles
 * nothing. bgi_gpu_passes_release_retired destroys them once the new passes exist (or failed). */
void bgi_gpu_passes_retire(bg_renderer *r);
void bgi_gpu_passes_release_retired(bg_renderer *r);

/* ---- batch.c ---- */
/* Plans the intersection batches (first, count) into out (room for every object); returns how many. */
int bgi_gpu_batch_plan_hits(const bg_renderer *r, const bg_scene_state *state, gpu_batch *out);
/* Plans the shadow batches of a group over casters[first .. first + n - 1] into out; returns how many. */
int bgi_gpu_batch_plan_shadows(const bg_renderer *r, const bg_scene_state *state, int group, int first, int n,
                           gpu_batch *out);
/* The camera-ray scissor rectangle of a batch (the union of its objects'); false when unbounded.
 * An empty rectangle means every object is off screen. */
bool bgi_gpu_batch_scissor(const bg_scene_state *state, const gpu_batch *b, const gpu_view *view, int rect[4]);
/* Uniform components of the declared uniforms u[0 .. count - 1] as old hardware allocates them
 * (every float, vec2 or vec3 a whole vec4; arrays per element): what batches are planned by. */
int bgi_gpu_uniform_components(const macs_uniform_desc *u, int count);

/* ---- hit_pass.c ---- */
/* The intersection pass of objects first .. first + count - 1 (count <= GPU_BATCH_MAX), writing
 * the G-buffer slots of the features; trial as for bgi_gpu_pass_try. */
bg_status bgi_gpu_hit_pass_build(bg_renderer *r, const bg_scene_state *state, uint32_t first, int count, bool trial,
                             macs_pass **out, bool *rejected);
/* Uniform components (in whole vec4s, as old hardware allocates them) one object adds to an
 * intersection pass, and the scene textures it samples (0 = the white texel). */
int bgi_gpu_hit_object_needs(const bg_renderer *r, const bg_scene_state *state, uint32_t object,
                         uint32_t textures[GPU_HIT_MAX_TEXTURES], int *texture_count);
/* Uniform components every intersection pass has whatever its objects. */
int bgi_gpu_hit_shared_components(void);
/* The lane of a scene texture (0 the white texel) among the distinct lanes[0 .. *lane_count - 1],
 * appended when it is not there yet: how a pass, and the planner, count each texture once. */
int bgi_gpu_hit_texture_lane(uint32_t *lanes, int *lane_count, uint32_t texture);
/* Sets the per-frame uniforms of an object's intersection pass (dmax of the level). */
bg_status bgi_gpu_hit_pass_set_dmax(bg_renderer *r, macs_pass *pass, double dmax);

/* ---- light_pass.c ---- */
/* The shadow pass of a batch: objects casters[0 .. count - 1] (blocks[i] false: no test) against
 * the segments of light group `group`; trial as for bgi_gpu_pass_try. */
bg_status bgi_gpu_shadow_pass_build(bg_renderer *r, const bg_scene_state *state, const uint32_t *casters,
                                const bool *blocks, int count, int group, bool trial, macs_pass **out,
                                bool *rejected);
/* Uniform components of a shadow pass (as bgi_gpu_uniform_components counts them, from what the pass
 * declares): per object, and shared for a group of 1 .. GPU_LIGHTS_PER_GROUP lights. */
int bgi_gpu_shadow_object_components(void);
int bgi_gpu_shadow_shared_components(int lights);
/* The light pass of a group of up to four lights (vis: read the visibility texture); a group past
 * the last light makes the ambient and emission pass instead. */
bg_status bgi_gpu_light_pass_build(bg_renderer *r, const bg_scene_state *state, int group, bool vis, macs_pass **out);
/* Fills the uniform arrays of lights first .. first + count - 1 into a pass. */
bg_status bgi_gpu_set_light_uniforms(bg_renderer *r, macs_pass *pass, const bg_scene_state *state, int first, int count);

/* Fixed input positions of the ray maps, rebound for every ray set. */
#define GPU_HIT_IN_ORIGIN 0
#define GPU_HIT_IN_DIR 1
#define GPU_HIT_IN_WEIGHT 2
#define GPU_LIGHT_IN_DIR 3
#define GPU_LIGHT_IN_WEIGHT 4 /* only without the XPARENT slot */
#define GPU_SPAWN_IN_DIR 0
#define GPU_SPAWN_IN_WEIGHT 1
#define GPU_MARK_IN_WEIGHT 0
#define GPU_BACKGROUND_IN_WEIGHT 0

/* ---- phase_clock.c ---- */
/* Milliseconds of a monotonic clock. */
double bgi_gpu_now_ms(void);
/* With timing, drains the GPU and starts *clock; without, does nothing. */
void bgi_gpu_phase_start(bg_renderer *r, bool timing, double *clock);
/* With timing, drains the GPU, adds the time since *clock to the phase and restarts *clock. */
void bgi_gpu_phase_end(bg_renderer *r, bool timing, double *clock, bg_phase phase);

/* ---- read_back.c ---- */
/* Copies a finished RGBA8 or RGBA32F texture of the image's size into the caller's image, rows
 * flipped to top-down; with opaque, alpha 1 for float images (else the texture's, for the caller to
 * read and then set). */
bg_status bgi_gpu_read_back(bg_renderer *r, macs_texture *texture, bg_image *image, size_t stride, bool opaque);
/* The renderer's read-back buffer, grown to at least bytes; NULL (the failure reported) when out of
 * memory. */
void *bgi_gpu_read_back_buffer(bg_renderer *r, size_t bytes);

/* ---- rect.c ---- */
/* Grows a to the smallest rectangle holding a and b ({x, y, width, height}; empty ones add nothing). */
void bgi_gpu_rect_union(int a[4], const int b[4]);

/* ---- frame.c ---- */
/* Stencil bits Betelgeuse owns (MACS keeps 0x80): a live ray, and a hit in the current set. */
#define GPU_STENCIL_LIVE 0x1u
#define GPU_STENCIL_HIT 0x2u
/* One frame of the committed scene into out (whose arguments the entry point checked, view their
 * window and samples): progress at 0, the one pass of a single sample, or samples.c's passes,
 * progress at 1; fills the renderer's statistics. */
bg_status bgi_gpu_frame_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view);
/* One pass of the frame for r->view (one sample): the fused plan where it runs, else the multipass;
 * resets and fills the renderer's statistics. */
bg_status bgi_gpu_frame_pass(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                             const gpu_frame_out *out);

/* ---- tiles.c ---- */
/* bg_render_gpu's frame into out->image: in one piece through bgi_gpu_frame_render, or as tiles of
 * the frame when the image exceeds max_texture_size or the settings' GPU memory budget; sets
 * stats.tiles. */
bg_status bgi_gpu_tiles_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view);

/* ---- samples.c ---- */
/* The gpu_view of sample s of view: that one sample, and its camera shift (docs/shading.md 1.1). */
void bgi_gpu_view_for_sample(const bgi_render_view *view, int s, gpu_view *out);
/* A frame of view->samples > 1: one pass per sample into a float image on the host, summed there in
 * sample order and divided by the count, then encoded into out's image or uploaded into its
 * texture; progress after each pass, cancelling between passes leaves out untouched. */
bg_status bgi_gpu_samples_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                                 const gpu_frame_out *out, const bgi_render_view *view);

/* ---- fused.c ---- (with fused_layout.c, fused_uniforms.c, fused_source.c) */
/* The fused plan (BG_PLAN_FUSED): one fragment pass per frame computes the whole image. Its program
 * is a function of the scene's structure alone (gpu_fused_layout), so every value the scene or the
 * settings give lives in a uniform of the list below and a value-only re-commit compiles nothing. */

/* Material parameters the fused shader evaluates at a hit (docs/shading.md 5): id, the GLSL local
 * and uniform suffix, vec3 (true) or float, whether the value is clamped to [0, 1] (true) or to
 * >= 0 after texturing, and which materials have it (a gpu_fused_need). */
#define GPU_FUSED_PARAMS(X)                                   \
    X(BASE_C, "base_c", true, true, USED)                     \
    X(BASE_R, "base_r", false, true, USED)                    \
    X(BASE_P, "base_p", false, true, ANISO)                   \
    X(AMBIENT, "ambient", true, false, USED)                  \
    X(EMISSION, "emission", true, false, USED)                \
    X(TRANSPARENCY, "transparency", false, true, TRANSPARENT) \
    X(COAT_C, "coat_c", true, true, COAT)                     \
    X(COAT_R, "coat_r", false, true, COAT)                    \
    X(COAT_P, "coat_p", false, true, COAT_ANISO)

typedef enum gpu_fused_param {
#define GPU_FUSED_PARAM_ENUM_(id, local, color, unit, need) GPU_FUSED_P_##id,
    GPU_FUSED_PARAMS(GPU_FUSED_PARAM_ENUM_)
#undef GPU_FUSED_PARAM_ENUM_
    GPU_FUSED_P_COUNT_
} gpu_fused_param;

/* When a uniform (or parameter) exists: for every frame, with bounces, with lights, with the object
 * tree; per object unrolled (outside the tree)
 * always, with a tangent, with UVs; per material used, anisotropic, transparent, coated, both. */
typedef enum gpu_fused_need {
    GPU_FUSED_NEED_ALWAYS = 0, GPU_FUSED_NEED_BOUNCE, GPU_FUSED_NEED_LIGHTS, GPU_FUSED_NEED_TREE, GPU_FUSED_NEED_MESH,
    GPU_FUSED_NEED_TANGENT,
    GPU_FUSED_NEED_UV, GPU_FUSED_NEED_USED, GPU_FUSED_NEED_ANISO, GPU_FUSED_NEED_TRANSPARENT,
    GPU_FUSED_NEED_COAT, GPU_FUSED_NEED_COAT_ANISO
} gpu_fused_need;

/* Who a uniform belongs to: the frame, the light arrays (one element per light), an object, a material. */
typedef enum gpu_fused_scope { GPU_FUSED_FRAME = 0, GPU_FUSED_LIGHTS, GPU_FUSED_OBJECT, GPU_FUSED_MATERIAL } gpu_fused_scope;

/* Every uniform of the fused shader besides the material parameters (which follow as rows
 * "bg_m<k>_<local>", one per GPU_FUSED_PARAMS entry): id, scope, GLSL name (%u: the object or
 * material index), type, when it exists, the fused_uniforms.c function that computes its value. The
 * declarations, the uniform budget, the values and the names the generated source uses all come
 * from this list and GPU_FUSED_PARAMS. */
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
    X(LIGHT_POS, LIGHTS, "bg_lpos", VEC4, LIGHTS, light_position)               \
    X(LIGHT_RAD, LIGHTS, "bg_lrad", VEC3, LIGHTS, light_radiance)               \
    X(LIGHT_ATT, LIGHTS, "bg_latt", VEC3, LIGHTS, light_attenuation)            \
    X(LIGHT_SPOT, LIGHTS, "bg_lspot", VEC4, LIGHTS, light_spot)                 \
    X(LIGHT_EXP, LIGHTS, "bg_lexp", FLOAT, LIGHTS, light_exponent)              \
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
#define GPU_FUSED_ROW_COUNT (GPU_FUSED_U_COUNT_ + GPU_FUSED_P_COUNT_)

/* A material as the fused shader specialises it; only used materials get code and uniforms. */
typedef struct gpu_fused_material {
    bool used, aniso, coat, transparent;
    bool bounce;                          /* may spawn a secondary ray (bgi_gpu_material_may_bounce) */
    bool textured;                        /* some parameter samples a texture: its objects need UVs */
    uint32_t texture[GPU_FUSED_P_COUNT_]; /* scene texture (1-based) of each parameter, 0 none */
    int channel[GPU_FUSED_P_COUNT_];      /* the texel channel of a textured scalar */
    int sampler[GPU_FUSED_P_COUNT_];      /* the shader's sampler of that texture, -1 none */
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
    int sampler_count;
    bool transparent, aniso, coat, shadows; /* some used material is / some caster can shadow another */
    int max_depth;       /* bounce levels traced: settings.max_depth, 0 when no material bounces */
    int stack;           /* pending rays the shader holds: max_depth with transparency, else 0 */
    bool light_loop;     /* lights in a loop rather than unrolled (GPU_FUSED_UNROLLED_SHADOW_TESTS) */
    int loop_rays;       /* the trace loop's bound: every ray of the full tree, within GPU_FUSED_MAX_LOOP */
    double rays_needed;  /* the most rays a pixel can follow, min_weight's pruning counted */
    bool tree;           /* BG_PLAN_FUSED_TREE: the bounded objects are walked from the tree's textures */
    uint32_t *unrolled;  /* the objects outside the tree, ascending (unrolled_count of them) */
    uint32_t unrolled_count;
    uint32_t tree_count; /* objects in the tree (not part of the program) */
    gpu_fused_tree_kinds kinds;
    bool mesh;           /* some object is a mesh, in the tree or unrolled: the mesh textures are bound */
    uint32_t unrolled_meshes; /* mesh objects outside the tree, each walked with its own uniforms */
    int walk_budget;     /* tree steps one pixel may take in all its walks: what the loop limit leaves */
} gpu_fused_layout;

/* llvmpipe ends a shader invocation silently after 65535 loop iterations in all, so the trace loop
 * never runs longer: a pixel that could need more rays renders with the multipass. */
#define GPU_FUSED_MAX_LOOP 65535
/* Shadow tests (lights x casters) up to which lights are unrolled. Each unrolled light inlines its
 * own copy of every caster's test: at 2 lights x 17 casters (many_spheres) the program took 14 s
 * to compile on a loaded llvmpipe, 5.6 s with a loop over the lights, which renders 15-35 % slower
 * (many_spheres, many_lights, glass at 256x256). */
#define GPU_FUSED_UNROLLED_SHADOW_TESTS 16

/* The tree variant's texture geometry: per texture (items per row, its inverse, 1 / width,
 * 1 / height), as bg_fused_tree.glsl reads it, and the node count. */
typedef struct gpu_fused_tree_dims {
    float nodes[4], objects[4];
    float node_count;
    float meshes[4]; /* the mesh textures' (texels per row, its inverse, 1 / triangle rows, 1 / node rows) */
} gpu_fused_tree_dims;

/* The values of one render, for the uniforms. */
typedef struct gpu_fused_values {
    const bg_scene_state *state;
    const bg_render_settings *settings;
    const gpu_fused_tree_dims *tree; /* NULL without the tree and the meshes */
    const float *mesh_base;          /* per object: its mesh's root and first triangle texel (meshes only) */
    int width, height;
    bool float_output;
    const gpu_view *view; /* the frame size, the window and the sample */
} gpu_fused_values;

/* Renders the frame with the fused plan when settings (and, for BG_PLAN_AUTO, the scene and the GL
 * limits) choose it: *done true. Otherwise *done is false with BG_OK and the caller runs the
 * multipass (stats.plan says so). */
bg_status bgi_gpu_fused_render(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings,
                           const gpu_frame_out *out, bool *done);
/* Frees the fused plan's program, textures and cache. */
void bgi_gpu_fused_release(bg_renderer *r);

/* ---- fused_tree.c ---- */
/* One texture of the tree variant with the host copy of what it holds (held) and room to build the
 * next frame's (scratch), so that only a change is uploaded. */
typedef struct gpu_fused_tree_texture {
    macs_texture *texture;
    float *held, *scratch;
    size_t floats;
} gpu_fused_tree_texture;

typedef struct gpu_fused_tree {
    gpu_fused_tree_texture nodes, objects;
    gpu_fused_tree_texture mesh_nodes; /* every distinct mesh's tree (fused_tree.c); none without meshes */
    gpu_fused_tree_texture mesh_tris;  /* and its triangles */
    float *mesh_base;              /* per object: 2 floats, its mesh's root node and first triangle texel */
    uint32_t mesh_base_count;      /* objects mesh_base has room for */
    uint64_t *mesh_keys;           /* the serials of the distinct meshes the mesh textures hold, in order */
    uint32_t mesh_key_count, mesh_key_room;
    gpu_fused_tree_dims dims; /* of the prepared textures */
    uint64_t serial;          /* the commit (bg_scene_state.serial) they hold; 0 none */
    bool walks;               /* whether they were made for a layout that walks the tree */
    macs_texture *marks;      /* fused_tree_target.c: a frame's marked pixels, 32 to an RGBA8 texel */
    macs_pass *mark_pass;     /* writes marks from a frame of the marks' height */
} gpu_fused_tree;

/* False, with the reason, when the scene's tree or objects do not fit the GL's texture size. */
bool bgi_gpu_fused_tree_fits(const bg_renderer *r, const bg_scene_state *state, char *why, size_t size);
/* False, with the reason, when the scene's meshes do not fit the mesh textures (part of _fits). */
bool bgi_gpu_fused_tree_meshes_fit(const bg_renderer *r, const bg_scene_state *state, char *why, size_t size);
/* Makes the textures hold the committed scene's tree and objects, as seen from its camera (with
 * walks: the layout walks the tree), and the meshes' nodes and triangles where it has meshes. */
bg_status bgi_gpu_fused_tree_prepare(bg_renderer *r, gpu_fused_tree *t, const bg_scene_state *state, bool walks);
void bgi_gpu_fused_tree_release(const bg_allocator *a, gpu_fused_tree *t);
/* Renders every pixel the shader marked (alpha 0: its walks ran out of steps) with the CPU reference;
 * returns how many there were. */
uint64_t bgi_gpu_fused_tree_fallback(const bg_scene_state *state, const bg_render_settings *settings,
                                 const bgi_render_view *view, const bg_image *image, size_t stride);

/* ---- fused_tree_target.c ---- */
/* The same for a frame that ended in the caller's texture: finds the marked pixels from a one-bit-a-
 * pixel read-back, renders them with the CPU reference and uploads them into target; *count gets
 * how many there were. */
bg_status bgi_gpu_fused_tree_fallback_texture(bg_renderer *r, gpu_fused_tree *t, const bg_scene_state *state,
                                          const bg_render_settings *settings, macs_texture *target, uint64_t *count);
/* Frees the marks texture and its pass. */
void bgi_gpu_fused_tree_marks_release(gpu_fused_tree *t);

/* ---- mesh_source.c ---- */
/* The float offset of a ray leaving a mesh, in ulps of the point's magnitude (docs/shading.md 2.10). */
#define GPU_MESH_OFFSET_ULPS 256.0
/* The fused plans' mesh code for layouts with meshes: the globals a mesh hit leaves
 * (its triangle, weights, point, geometric normal and offset), the walks of a mesh's own tree for the
 * nearest triangle and a shadow segment, both spending the pixel's walk steps, and bg_mesh_leave,
 * which turns a spawned ray into one leaving the triangle. */
void bgi_gpu_mesh_walks(int walk_budget, gpu_text *t);
/* The mesh slot's w where a walk of the pixel ran out of steps: the multipass marks the pixel for
 * the CPU reference (frame.c). */
#define GPU_MESH_SHORT (-2.0)
/* What a multipass pass that walks `walks` meshes per pixel leaves its walks of llvmpipe's loop
 * limit (each walk's loop ends take 3 iterations). */
int bgi_gpu_mesh_pass_budget(int walks);
/* The step count the walks share and the flag of one that ran out (set by the caller's main). */
void bgi_gpu_walk_globals(gpu_text *t);
/* The walk globals and the mesh walks of a multipass pass with `walks` mesh walks per pixel. */
void bgi_gpu_mesh_pass_walks(int walks, gpu_text *t);
/* bg_triangle.glsl and bg_mesh.glsl into t. */
bool bgi_gpu_mesh_library(gpu_text *t, const char **seen, int *seen_count, int seen_cap);

/* ---- fused_layout.c ---- */
/* Fills the layout of the committed scene for the settings (arrays from the renderer's allocator),
 * with tree the objects of the scene's object tree walked from textures; false when out of memory. */
bool bgi_gpu_fused_layout_build(const bg_allocator *a, const bg_scene_state *state, const bg_render_settings *settings,
                            bool tree, gpu_fused_layout *out);
void bgi_gpu_fused_layout_free(const bg_allocator *a, gpu_fused_layout *layout);
/* The constant and texture of material parameter p of m (rgb for colours; value in v[0] for scalars). */
void bgi_gpu_fused_param_of(const bg_material *m, gpu_fused_param p, double v[3], uint32_t *texture, int *channel);
/* Whether a material has what a per-material uniform or parameter needs (the "need" columns). */
bool bgi_gpu_fused_material_has(const gpu_fused_material *m, gpu_fused_need need);
/* Whether an object of the layout's material samples textures / needs a shading tangent. */
bool bgi_gpu_fused_object_uv(const gpu_fused_layout *l, uint32_t object);
/* Whether the program walks a tree: the tree variant with some object in the scene's tree. */
bool bgi_gpu_fused_layout_walks(const gpu_fused_layout *l);
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

/* ---- fused_source.c ---- */
/* The fused shader of a layout: its functions (the glsl110/ library and the generated scene code)
 * into functions, its main into main, and the expression written to the output. False when a
 * library file is missing or memory ran out. */
bool bgi_gpu_fused_source(const gpu_fused_layout *l, gpu_text *functions, gpu_text *main, const char **output);

#endif
