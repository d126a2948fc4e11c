/* Services both plans use (the fused plan in fused/, the multipass in multipass/): the renderer
 * object's shared part and its error sink, shader text assembly, pass creation, the camera-relative
 * origin, the read-back, the phase clock, the scene's and the meshes' textures, and the CPU
 * reference for the pixels a walk could not finish. Every pass is a MACS render pass; only MACS
 * touches GL. This room includes nothing of gpu/ outside itself. */
#ifndef BG_GPU_SHARED_H
#define BG_GPU_SHARED_H

#include "../../../macs/first_error.h"
#include "../../scene/scene_internal.h"
#include "../../common/render_view.h"

/* llvmpipe ends a shader invocation silently after 65535 loop iterations in all: the fused plan's
 * trace loop and every pass's tree walks stay within it (a pixel that could need more goes to the
 * multipass or to the CPU reference). */
#define GPU_MAX_LOOP 65535

/* The pixels one pass computes: the window of the frame and the sample (pixels.sample_first, one
 * sample per pass), and what the camera stage adds to gl_FragCoord.xy for it (docs/shading.md 1.1):
 * the window's offset in the frame in GL's bottom-up rows plus the sample's offset from the pixel
 * centre, all multiples of 2^-BGI_SAMPLE_BITS, so the sum is exact in float and a window's rays are
 * bit for bit the full frame's. */
typedef struct gpu_view {
    bgi_render_view pixels;
    float shift[2];
} gpu_view;

/* Where a frame ends: the caller's image, read back with its rows flipped to top-down (image set), or
 * the caller's texture, written on the GPU with GL's rows, bottom row first (texture set). */
typedef struct gpu_frame_out {
    bg_image *image;       /* bg_render_gpu; NULL for a texture */
    size_t stride;         /* the image's checked row stride */
    macs_texture *texture; /* bg_render_gpu_to_texture; NULL for an image */
    int width, height;
    bool as_float;         /* RGBA32F image, RGBA32F or RGBA16F texture: linear radiance; else RGBA8 */
} gpu_frame_out;

/* A row of a data texture (the meshes' here, the object tree's in fused/tree_textures.c) holds at
 * most this many texels, and a node of a tree as the walks read it (common/bvh.h's BG_BVH_NODE_FLOATS)
 * takes two: one rule for both, since bg_tree_textures.glsl and bg_mesh.glsl read both alike. */
enum { GPU_WIDEST_ROW = 4096, GPU_NODE_TEXELS = 2 };

/* The meshes' textures (meshes.c), one copy that every plan reads: every distinct mesh's own tree
 * in one texture, its triangles in the other, each addressed by texel index (bg_mesh.glsl). */
enum { GPU_MESH_KEYS = 3 };

typedef struct gpu_meshes {
    macs_texture *nodes;     /* every distinct mesh's tree; NULL without meshes */
    macs_texture *triangles; /* and its triangles */
    float dims[4];           /* (texels per row, its inverse, 1 / triangle rows, 1 / node rows): bg_mesh_dims */
    float *base;             /* per object: 2 floats, its mesh's root node and first triangle texel */
    uint32_t base_count;     /* objects base has room for */
    uint64_t *keys;          /* per copy the textures hold, in order, GPU_MESH_KEYS each: its mesh's serial,
                              * its filter's key, its tree's order for the camera (meshes.c) */
    uint32_t key_count, key_room;
    uint64_t serial;         /* the commit (bg_scene_state.serial) they were made for; 0 none */
    uint64_t uploads;        /* grows whenever the textures are remade or written: a pass that bound them
                              * when it was another value (the multipass's) binds stale ones */
} gpu_meshes;

/* The scene's textures (scene_textures.c), one copy that every plan samples. */
typedef struct gpu_scene_textures {
    macs_texture **texture; /* per scene texture (handle - 1) */
    uint32_t count;
    macs_texture *srgb_table; /* bgi_srgb_table as 256 x 1 RGBA32F, while some held texture is 8-bit
                               * sRGB sampled through it (bgi_gpu_srgb_table); else NULL */
    uint64_t bytes;           /* texel bytes of the held textures and the table, as uploaded */
    uint64_t key;           /* what they hold: a hash of the textures' sizes, modes and texels */
    bool held;              /* they hold key's textures (an upload that failed leaves it false) */
    uint64_t serial;        /* the last commit found to hold key's textures; 0 none */
    uint64_t uploads;       /* grows whenever they are remade: a pass that bound them when it was
                             * another value (the multipass's) binds stale ones */
} gpu_scene_textures;

/* The marks of a frame's pixels whose walks ran out of steps, for a frame that ended in the
 * caller's texture (fallback.c): each plan that walks keeps its own. */
typedef struct gpu_marks {
    macs_texture *texture; /* a frame's marked pixels, 32 to an RGBA8 texel */
    macs_pass *pass;       /* writes texture from a frame of its height */
} gpu_marks;

struct gpu_fused;     /* fused/fused.h: the fused plan's cached program and targets */
struct gpu_multipass; /* multipass/multipass.h: the multipass's targets, passes and cache key */

/* The environment's importance tables on the GPU (environment_tables.c). */
typedef struct gpu_env_tables {
    macs_texture *marginal, *conditional;
    uint64_t id; /* bg_environment_data.tables_id of what they hold; 0 none */
} gpu_env_tables;

/* phase_clock.c: a stretch of GL commands timed for a phase (or between phases: -1, not kept). */
typedef struct gpu_phase_span {
    macs_timer *timer; /* made the first time the pool reaches it, kept for the next calls */
    int phase;
} gpu_phase_span;

/* The phase timing of the entry call running (settings.gpu_timing). */
typedef struct gpu_phase_timing {
    bool on;     /* the call asked for timing */
    bool timers; /* GPU timers; else the wall clock between glFinish calls */
    gpu_phase_span *spans;
    int used, capacity;
    bool running;            /* spans[used] is begun */
    macs_status failed;      /* the first timer failure, reported at the call's end */
    bool out_of_memory;      /* ... which was the span pool's allocation */
    double start, clock;     /* wall clock: the call's start, the running phase's start */
    double wall_ms[BG_PHASE_COUNT_];
} gpu_phase_timing;

struct bg_renderer {
    bg_allocator allocator;
    bg_logger logger;
    macs_first_error error; /* status is a bg_status; fail.c records it */

    macs_context *ctx;
    macs_limits limits; /* effective */
    bool float_depth;
    bool half_gbuffer; /* asked for and found renderable at creation (bgi_gpu_half_probe) */
    bg_render_stats stats;
    const char *entry; /* the public call running (set at its start): every message of it begins so */

    float *readback; /* read_back.c's buffer */
    size_t readback_size;
    /* tiles.c's deferred read: while defer_reads is set, a frame's last read into the image is not
     * made but parked here (read_back.c), for the tile loop to queue once the next tile is under way. */
    bool defer_reads;
    macs_texture *parked;  /* the finished texture of the frame just rendered; NULL none */
    bool parked_opaque;    /* bgi_gpu_read_back's opaque for it */
    gpu_view view; /* of the pass being rendered (the driver sets it) */
    gpu_phase_timing timing;
    /* Set by the driver while a pass renders one of several samples summed on the GPU (accumulate.c):
     * a plan then leaves its run-out marks (alpha 0) in its float output for the sum's alpha to count,
     * instead of reading them back each pass, and sets marks_left; the sum's end renders them. */
    bool marks_deferred;
    bool marks_left;

    gpu_meshes meshes;                 /* meshes.c: both plans read it; the driver frees it */
    struct bg_accumulation *frame_sum; /* the sum of bg_render_gpu's multi-sample frames (samples.c),
                                          kept between frames with its add pass, so that the pass's
                                          program stays in MACS's cache; NULL until one */
    gpu_marks frame_marks;             /* the marks of such a frame into an RGBA8 texture (samples.c) */
    gpu_scene_textures scene_textures; /* scene_textures.c: likewise */
    gpu_env_tables env_tables;         /* environment_tables.c: likewise */

    /* Each plan's own objects, NULL until the plan first runs; each plan frees only its own. */
    struct gpu_fused *fused;
    struct gpu_multipass *multipass;
};

/* ---- the plan interface: what the driver's choice (plan.c) calls, and nothing else does ---- */
/* One pass of a frame (one sample; r->view is set) as a plan receives it. */
typedef struct gpu_plan_frame {
    const bg_scene *scene;              /* the multipass's cache key names it */
    const bg_scene_state *state;        /* its committed state, read once per frame */
    const bg_render_settings *settings;
    const gpu_frame_out *out;
    bool forced;                        /* the settings name this plan: it may not decline */
} gpu_plan_frame;

/* A way to render a frame on the GPU. A new plan is one more of these and one more case in the
 * driver's choice (docs/architecture.md, "Where to add a plan"). */
typedef struct gpu_plan {
    bg_gpu_plan id;   /* what stats.plan says after the plan rendered */
    const char *name; /* for messages */
    /* Renders f into f->out and fills the statistics (the driver sets plan and programs_compiled).
     * Unless forced it may decline: BG_OK with the reason in why, nothing rendered; why is "" when
     * it rendered. A failure frees the plan's own objects, so its next frame starts afresh. */
    bg_status (*render)(bg_renderer *r, const gpu_plan_frame *f, char *why, size_t why_size);
    /* Frees every object of the plan. */
    void (*release)(bg_renderer *r);
} gpu_plan;

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
/* Records a message of the argument checks the CPU renderer shares (common/render_args.c,
 * render_settings.c, render_view.c), which begin with the entry's name themselves. */
bg_status bgi_gpu_fail_checked(bg_renderer *r, bg_status status, const char *message);
/* Logs a diagnostic that is not an error (a warning: something worked around; info: a choice made). */
void bgi_gpu_log(const bg_renderer *r, bg_log_level level, const char *format, ...) GPU_PRINTF_(3, 4);

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

/* The glsl110/ file of a UV mapping (NULL for none) and the suffix of its bg_uv_map_ function. */
const char *bgi_gpu_uv_file(bg_uv_mapping mapping);
const char *bgi_gpu_uv_suffix(bg_uv_mapping mapping);

/* ---- material_traits.c ---- */
/* Whether a material can spawn a secondary ray somewhere (mirror share or transparency). */
bool bgi_gpu_material_may_bounce(const bg_material *m);
/* Whether some layer of a material may have isotropy < 1 (a tangent is needed). */
bool bgi_gpu_material_may_be_aniso(const bg_material *m);

/* ---- material_params.c: the material parameters as both plans' shaders read them ---- */
/* Material parameters a shader evaluates at a hit (docs/shading.md 5): id, the GLSL local and
 * uniform suffix, vec3 (true) or float, whether the value is clamped to [0, 1] (true) or to >= 0
 * after texturing, and which materials the fused plan declares it for (a gpu_fused_need). */
#define GPU_PARAMS(X)                                         \
    X(BASE_C, "base_c", true, true, USED)                     \
    X(BASE_R, "base_r", false, true, USED)                    \
    X(BASE_P, "base_p", false, true, ANISO)                   \
    X(AMBIENT, "ambient", true, false, USED)                  \
    X(EMISSION, "emission", true, false, USED)                \
    X(TRANSPARENCY, "transparency", false, true, TRANSPARENT) \
    X(COAT_C, "coat_c", true, true, COAT)                     \
    X(COAT_R, "coat_r", false, true, COAT)                    \
    X(COAT_P, "coat_p", false, true, COAT_ANISO)

typedef enum gpu_param {
#define GPU_PARAM_ENUM_(id, local, color, unit, need) GPU_P_##id,
    GPU_PARAMS(GPU_PARAM_ENUM_)
#undef GPU_PARAM_ENUM_
    GPU_P_COUNT_
} gpu_param;

/* The GLSL local (and uniform suffix) of parameter p, and whether it is a colour (vec3). */
const char *bgi_gpu_param_local(gpu_param p);
bool bgi_gpu_param_is_color(gpu_param p);
/* Whether parameter p is clamped to [0, 1] after texturing (else to >= 0). */
bool bgi_gpu_param_is_unit(gpu_param p);
/* The constant and texture of material parameter p of m (rgb for colours; value in v[0] for scalars). */
void bgi_gpu_param_of(const bg_material *m, gpu_param p, double v[3], uint32_t *texture, int *channel);
/* The uniform value of parameter p of m: the constant, with the scene's ambient light folded into
 * the ambient colour, and a material without a coat given the values of no coat (reflectance 0,
 * roughness -1, isotropy 1). A scalar's value is out[0]. */
void bgi_gpu_param_value(const bg_scene_state *state, const bg_material *m, gpu_param p, float out[3]);

/* ---- light_pack.c ---- */
/* One light as bg_light.glsl reads it (the uniforms bg_lpos, bg_lrad, bg_latt, bg_lspot, bg_lexp),
 * and as bg_area_light.glsl reads an area light's shape (bg_ledge_u, bg_ledge_v). */
typedef struct gpu_packed_light {
    float pos[4], rad[3], att[3], spot[4], exponent;
    float edge_u[4], edge_v[4];
} gpu_packed_light;
/* The camera stage's function for the projection (camera.c): bg_camera_ray or bg_camera_ray_parallel. */
const char *bgi_gpu_camera_function(bool orthographic);
/* bg_tan_half, the view's half extents that the camera stage scales the window point by: at unit
 * distance (perspective) or in world units (orthographic), the horizontal one times the aspect. */
void bgi_gpu_camera_half(const bg_scene_state *state, const gpu_view *view, float out[2]);
/* Whether the committed scene has an area light (a sphere of radius > 0 or a rectangle). */
bool bgi_gpu_scene_has_area_lights(const bg_scene_state *state);
/* The distribution uniforms of a pass (docs/shading.md 1.3 and 1.4): bg_pixel_at, the frame column
 * of the window's first pixel and the frame row of its bottom GL row; bg_sample_of, (s, n,
 * columns, rows) of the view's sample (s the pattern's sample that the view takes sample_first-th,
 * bgi_sample_order); bg_lens, (aperture_radius, focus). */
void bgi_gpu_pixel_at(const gpu_view *view, float out[2]);
void bgi_gpu_sample_of(const gpu_view *view, float out[4]);
/* bg_sample_perm: the cell permutation's constants for the view's sample count (bg_scramble.glsl). */
void bgi_gpu_sample_perm(const gpu_view *view, float out[4]);
void bgi_gpu_lens(const bg_scene_state *state, float out[2]);
gpu_packed_light bgi_gpu_light_pack(const bg_scene_state *state, uint32_t k);

/* ---- environment_tables.c ---- */
/* Makes r->env_tables hold the committed environment's importance tables (one value per texel, in
 * R: the marginal as one row of height texels, the conditional as width x height), uploading them
 * only when the scene's tables changed; nothing without importance sampling. */
bg_status bgi_gpu_env_tables_prepare(bg_renderer *r, const bg_scene_state *state);
void bgi_gpu_env_tables_release(bg_renderer *r);
/* The environment's uniform bg_env_info: (intensity, width, height, 1 with importance tables). */
void bgi_gpu_env_info(const bg_scene_state *state, float out[4]);

/* ---- scene_textures.c ---- */
/* Makes r->scene_textures hold the committed scene's textures, uploading them only when what they
 * hold changed. */
bg_status bgi_gpu_scene_textures_prepare(bg_renderer *r, const bg_scene_state *state);
void bgi_gpu_scene_textures_release(bg_renderer *r);
/* One step of the hash that keys them, which the multipass's cache key mixes with too. */
uint64_t bgi_gpu_hash_mix(uint64_t h, uint64_t v);

/* ---- texture_upload.c ---- */
/* Creates *out as a w x h texture of format unless it exists; what names it in a failure. */
bg_status bgi_gpu_texture_ensure(bg_renderer *r, int w, int h, macs_format format, macs_texture **out, const char *what);
/* Creates *out as a w x h RGBA32F texture holding texels (GL row order) with the filter and wrap;
 * what names it in a failure. */
bg_status bgi_gpu_float_texture(bg_renderer *r, int w, int h, macs_filter filter, macs_wrap wrap, const float *texels,
                                const char *what, macs_texture **out);
/* The texture units a context needs before 8-bit sRGB textures go up as RGBA8 and are decoded
 * through the table, which takes a unit of its own in every pass that samples one: the multipass's
 * hit pass holds 3 ray maps and 2 mesh textures, so 8 leave it the table and two material textures.
 * Below (the gl21 profile's 2 units) they go up decoded to RGBA32F, 16 bytes a texel as before; the
 * values a shader filters are the same floats either way (docs/shading.md 5.2). */
enum { GPU_SRGB_TABLE_MIN_UNITS = 8 };
/* Whether this renderer samples 8-bit sRGB textures through the table (GPU_SRGB_TABLE_MIN_UNITS). */
bool bgi_gpu_srgb_table(const bg_renderer *r);
/* Uploads one scene texture as the samplers read it, GL_NEAREST whatever its filter (a GL_LINEAR
 * texture is filtered in the shader, bgi_gpu_texture_lookup), with its wrap: RGBA32F texels as they
 * are, RGBA8 bytes as RGBA8 (decoded to RGBA32F for an sRGB one when table is false); *bytes gets
 * the bytes its texels take. */
bg_status bgi_gpu_scene_texture_upload(bg_renderer *r, const bg_texture_data *t, bool table, macs_texture **out,
                                       uint64_t *bytes);
/* Creates *out as the 256 x 1 RGBA32F table of bgi_srgb_table (bg_texture_srgb.glsl). */
bg_status bgi_gpu_srgb_table_upload(bg_renderer *r, macs_texture **out);

/* How a program samples one scene texture: what it bakes into its text (docs/shading.md 5.1). */
typedef struct gpu_texture_mode {
    int width, height;
    bool linear; /* BG_FILTER_LINEAR: bg_texture_linear's four fetches; else one NEAREST fetch */
    bool repeat; /* BG_WRAP_REPEAT, else CLAMP */
    bool srgb;   /* 8-bit sRGB texels decoded through the table bg_srgb_table (bg_texture_srgb.glsl) */
} gpu_texture_mode;
/* The mode of t, sampled through the sRGB table where table says so (bgi_gpu_srgb_table); NULL (the
 * multipass's white texel) is 1 x 1 NEAREST. */
gpu_texture_mode bgi_gpu_texture_mode(const bg_texture_data *t, bool table);
/* Writes into out (size bytes, 192 are enough for any sampler and uv names up to 40 characters) the
 * GLSL vec4 of the texture of mode m bound to sampler at uv: texture2D for NEAREST, else
 * bg_texture_linear (glsl110/bg_texture_filter.glsl, which the program must then hold) with the
 * size and wrap as constants; for an sRGB mode bg_srgb_decode of the fetch, or
 * bg_texture_linear_srgb (glsl110/bg_texture_srgb.glsl, likewise), reading the sampler
 * bg_srgb_table. False when it does not fit. */
bool bgi_gpu_texture_lookup(char *out, size_t size, const char *sampler, const char *uv, gpu_texture_mode m);

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
/* Uniform components of one element of type t, and of the declared uniforms u[0 .. count - 1], as
 * old hardware allocates them (every float, vec2 or vec3 a whole vec4; arrays per element): the one
 * count every plan's uniform budget is planned by. */
int bgi_gpu_uniform_type_components(macs_uniform_type t);
int bgi_gpu_uniform_components(const macs_uniform_desc *u, int count);
/* bgi_gpu_pass_try over assembled texts (desc->main already points into main): fails with a message
 * when a text ran out of memory or a glsl110 file was missing (files_found false); frees both. */
bg_status bgi_gpu_pass_from_texts(bg_renderer *r, const char *what, gpu_text *main, gpu_text *functions, bool files_found,
                              macs_pass_desc *desc, bool trial, macs_pass **out, bool *rejected);

/* ---- phase_clock.c ---- */
/* Milliseconds of a monotonic clock. */
double bgi_gpu_now_ms(void);
/* An entry call's start: on is settings.gpu_timing; picks GPU timers where the context has them. */
void bgi_gpu_timing_begin(bg_renderer *r, bool on);
/* With timing, a phase starts: the time since the last phase's end is nobody's. */
void bgi_gpu_phase_start(bg_renderer *r);
/* With timing, the running phase ends as phase, and the next starts at once. */
void bgi_gpu_phase_end(bg_renderer *r, bg_phase phase);
/* An entry call's end, after its last GL command: with timing and st BG_OK, reads the timers and
 * fills stats.phase_ms, timed, timing and total_ms; returns st, or the timers' own failure. */
bg_status bgi_gpu_timing_end(bg_renderer *r, bg_status st);
/* Destroys the timers. */
void bgi_gpu_timing_release(bg_renderer *r);

/* ---- read_back.c ---- */
/* Copies a finished RGBA8 or RGBA32F texture of the image's size into the caller's image, rows
 * flipped to top-down; with opaque, alpha 1 for float images (else the texture's, for the caller to
 * read and then set). */
bg_status bgi_gpu_read_back(bg_renderer *r, macs_texture *texture, bg_image *image, size_t stride, bool opaque);
/* The renderer's read-back buffer, grown to at least bytes; NULL (the failure reported) when out of
 * memory. */
void *bgi_gpu_read_back_buffer(bg_renderer *r, size_t bytes);
/* A frame's last write into the caller's image (nothing changes the image after it): while tiles.c
 * defers reads (r->defer_reads), the texture is parked and true returned, for the tile loop to read
 * later; else false, and the caller reads now. */
bool bgi_gpu_read_park(bg_renderer *r, macs_texture *texture, bool opaque);
/* bgi_gpu_read_back as a frame's last write: parked while reads are deferred, else read now. */
bg_status bgi_gpu_read_back_last(bg_renderer *r, macs_texture *texture, bg_image *image, size_t stride, bool opaque);
/* Copies rows [y0, y0 + count) and texels [x0, x0 + width) of texels (a texture's read, bottom row first,
 * src_stride bytes apart, height rows) into dst (top row first, stride apart, starting at the first
 * row and texel copied), as bgi_gpu_read_back writes them; texel is 4 or 16 bytes. */
void bgi_gpu_copy_rows(const unsigned char *texels, size_t src_stride, int height, int x0, int width, int y0,
                       int count, size_t texel, bool opaque, unsigned char *dst, size_t stride);


/* ---- meshes.c: the meshes' textures ---- */
/* False, with the reason, when the scene's meshes do not fit the mesh textures. */
bool bgi_gpu_meshes_fit(const bg_renderer *r, const bg_scene_state *state, char *why, size_t size);
/* Makes r->meshes hold the committed scene's distinct meshes and every mesh object's bases. The
 * caller has checked that they fit (bgi_gpu_meshes_fit, or the fused tree's fit, which includes
 * it): each plan checks once, before it takes the frame. */
bg_status bgi_gpu_meshes_prepare(bg_renderer *r, const bg_scene_state *state);
void bgi_gpu_meshes_release(bg_renderer *r);
/* What the scene's mesh filters need of the shaders (a program depends on it, never on the values):
 * a front-only mesh (the walks test the side), a cut-out (they sample the coverage), an open mesh
 * (its hits are thin). 0 for a scene that filters nothing, whose programs are those of before. */
enum { GPU_MESH_FRONT_ONLY = 1, GPU_MESH_CUT_OUT = 2, GPU_MESH_OPEN = 4 };
int bgi_gpu_meshes_filters(const bg_scene_state *state);

/* Renders every pixel the shader marked (alpha 0: its walks ran out of steps) with the CPU reference
 * for the view's samples (several: bgi_gpu_fallback_sum's sum, averaged as samples.c averages);
 * returns how many there were. */
uint64_t bgi_gpu_fallback_image(const bg_scene_state *state, const bg_render_settings *settings,
                                 const bgi_render_view *view, const bg_image *image, size_t stride);

/* ---- fallback.c ---- */
/* The same for a frame that ended in a texture: finds the marked pixels (alpha below 0.5) from a
 * one-bit-a-pixel read-back, renders them with the CPU reference for the view's samples and uploads
 * them into target; *count gets how many there were. */
bg_status bgi_gpu_fallback_texture(bg_renderer *r, gpu_marks *m, const bg_scene_state *state,
                                   const bg_render_settings *settings, const bgi_render_view *view,
                                   macs_texture *target, uint64_t *count);
/* Runs m's pass over target (a pixel is marked where its alpha is below whole - 0.5) and reads the
 * marks into the read-back buffer, followed by spare bytes: *marks points at its rows (the
 * texture's, bottom first, bgi_gpu_marks_row_bytes apart), *room at the spare bytes. One wait. */
bg_status bgi_gpu_marks_read(bg_renderer *r, gpu_marks *m, macs_texture *target, float whole, size_t spare,
                             const unsigned char **marks, unsigned char **room);
size_t bgi_gpu_marks_row_bytes(int width);
/* Whether pixel x of a marks row is marked. */
bool bgi_gpu_marked(const unsigned char *mark_row, int x);
/* Adds samples [first, first + count) of pixel (x, y) (image rows, top first) of the view's frame,
 * each the CPU reference's one-sample RGBA32F texel (alpha 1), onto sum in the order taken, with the
 * accumulation's float additions (sample 0 starts the sum): the sum the GPU would hold had every
 * sample of the pixel been the CPU's. */
void bgi_gpu_fallback_sum(const bg_scene_state *state, const bg_render_settings *settings,
                          const bgi_render_view *view, int x, int y, int first, int count, float sum[4]);
/* The texel of a sum of samples as bg_render_gpu writes it: the mean in float, RGBA32F (alpha 1) or
 * the host's RGBA8 bytes of the encoding (alpha 255). */
void bgi_gpu_mean_texel(const float sum[4], int samples, bool as_float, bg_output_encoding encoding, void *texel);
/* Frees the marks texture and its pass. */
void bgi_gpu_marks_release(gpu_marks *m);

/* ---- mesh_source.c ---- */
/* The float offset of a ray leaving a mesh, in ulps of the point's magnitude (docs/shading.md 2.10):
 * 4 leave no start behind a neighbour triangle; more moves cast shadow edges (256 gave dark speckles
 * between thin parts), so 16 keeps a factor 4 and no more. */
#define GPU_MESH_OFFSET_ULPS 16.0
/* The fused plans' mesh code for layouts with meshes: the globals a mesh hit leaves
 * (its triangle, weights, point, geometric normal and offset), the walks of a mesh's own tree for the
 * nearest triangle and a shadow segment, both spending the pixel's walk steps, and bg_mesh_leave,
 * which turns a spawned ray into one leaving the triangle. */
void bgi_gpu_mesh_walks(int walk_budget, int filters, gpu_text *t);
/* The mesh slot's w where a walk of the pixel ran out of steps: the multipass marks the pixel for
 * the CPU reference (multipass_frame.c). */
#define GPU_MESH_SHORT (-2.0)
/* What a multipass pass that walks `walks` meshes per pixel leaves its walks of llvmpipe's loop
 * limit (each walk's loop ends take 3 iterations). */
int bgi_gpu_mesh_pass_budget(int walks);
/* The step count the walks share and the flag of one that ran out (set by the caller's main). */
void bgi_gpu_walk_globals(gpu_text *t);
/* The walk globals and the mesh walks of a multipass pass with `walks` mesh walks per pixel. */
void bgi_gpu_mesh_pass_walks(int walks, int filters, gpu_text *t);
/* bg_triangle.glsl and bg_mesh.glsl into t. */
bool bgi_gpu_mesh_library(gpu_text *t, const char **seen, int *seen_count, int seen_cap);


#endif
