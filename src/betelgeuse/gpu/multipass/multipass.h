/* The multipass plan (BG_PLAN_MULTIPASS, docs/gpu_pipeline.md): the paper's frame of ray maps, a
 * G-buffer and one pass per object batch, light group and ray set. It uses shared/ and nothing else
 * of gpu/; its objects live in one gpu_multipass behind bg_renderer.multipass. */
#ifndef BG_GPU_MULTIPASS_H
#define BG_GPU_MULTIPASS_H

#include "../shared/shared.h"

#define GPU_LIGHTS_PER_GROUP 4

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
    bool lens;        /* the camera has an aperture: the camera pass samples the lens */
    bool orthographic; /* the camera's rays are parallel (docs/shading.md 1.5) */
    bool area;        /* some light is an area light: shadow and light passes sample its point */
    bool glossy;      /* some material is glossy: ONCE's ior lane marks it (negative), and the
                         reflection pass draws its rays from the lobe */
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
    uint64_t textures;    /* r->scene_textures.key: what the scene's textures hold */
    uint64_t texture_uploads; /* r->scene_textures.uploads: the passes bind the textures when built */
    uint64_t mesh_uploads; /* r->meshes.uploads: the passes bind the mesh textures when they are built */
    int width, height;
    unsigned disable_skips;
    bg_output_encoding encoding;
    bool bounces;       /* max_depth > 0 */
    bool background_on; /* a non-black background needs its pass */
    double min_weight;
    bool valid;
} gpu_cache_key;

/* Everything the multipass keeps between frames, made at its first frame (bgi_gpu_multipass_render)
 * and freed by bgi_gpu_multipass_release. */
typedef struct gpu_multipass {
    /* Size-dependent targets. */
    int width, height;
    macs_texture *gbuffer[GPU_SLOT_COUNT];
    macs_texture *accum, *vis, *encoded;
    macs_depth_stencil *depth;
    gpu_ray_set *sets;
    int set_count;

    /* Scene-dependent objects. */
    gpu_cache_key key;
    gpu_features features;
    macs_texture **textures; /* the scene's textures as the passes bind them: the plans' one copy
                              * (r->scene_textures.texture) when the passes were built */
    macs_texture *white;     /* 1x1 white, NEAREST: the texture lane of an untextured parameter */
    gpu_passes passes;
    gpu_passes retired; /* the previous scene's, alive while passes are built (bgi_gpu_passes_retire) */
    macs_pass *resolve_float_retired; /* the previous float resolve, alive until the next is built:
                                         that one is made at a texture frame's end, after the rest */
    gpu_marks marks;    /* of a texture frame's short mesh walks (shared/fallback.c) */
} gpu_multipass;

/* ---- multipass_frame.c ---- */
/* Stencil bits Betelgeuse owns (MACS keeps 0x80): a live ray, and a hit in the current set. */
#define GPU_STENCIL_LIVE 0x1u
#define GPU_STENCIL_HIT 0x2u
/* The write mask of the multipass's stencil clears: every bit, though only the two above carry
 * anything. The buffer is the multipass's own, so no other bit has a value to keep, and a clear of
 * the whole stencil is the one every driver does as a plain clear: Mesa turns a masked one into a
 * draw, and zink (Mesa 22.3 over lavapipe) drops a masked stencil clear altogether, which left the
 * last level's marks in place and blacked out the multipass there (tests/probe_stencil_clear.c). */
#define GPU_STENCIL_CLEAR_MASK 0xFFu
/* The multipass plan: it renders every frame (it never declines). */
extern const gpu_plan bgi_gpu_multipass_plan;
/* Frees every object of the multipass (passes, targets, textures, meshes) and the gpu_multipass. */
void bgi_gpu_multipass_release(bg_renderer *r);

/* ---- features.c ---- */
/* Decides slots and shader features from the committed scene; generic switches specialisation off. */
void bgi_gpu_features_detect(const bg_scene_state *state, bool generic, gpu_features *f);

/* ---- fingerprint.c ---- */
/* A hash of every committed value the renderer's passes depend on; textures is the key of the
 * scene's textures (r->scene_textures.key), which hashes their texels. */
uint64_t bgi_gpu_scene_fingerprint(const bg_scene_state *state, uint64_t textures);

/* ---- bounds.c ---- */
/* The dmax of every level 0..max_depth (docs/gpu_pipeline.md); fixed when settings->dmax > 0. */
void bgi_gpu_dmax_levels(const bg_scene_state *state, const bg_render_settings *settings, const gpu_view *view,
                         double *dmax);
/* The pixel rectangle (GL window coordinates, bottom-up) that holds every camera ray able to hit a
 * bounded object; false when the object may cover the whole image (or is behind the camera). */
bool bgi_gpu_object_scissor(const bg_scene_state *state, uint32_t object, const gpu_view *view, int rect[4]);

/* ---- targets.c ---- */
/* (Re)creates the size-dependent targets for width x height and the features' G-buffer slots. */
bg_status bgi_gpu_targets_prepare(bg_renderer *r, int width, int height);
/* Whether RGBA16F works as a render target next to RGBA32F (one small pass, read back); false with
 * the reason in why. Leaves no MACS error behind that was not there before. */
bool bgi_gpu_half_probe(bg_renderer *r, char *why, size_t why_size);
/* The texture format of a G-buffer slot under the renderer's half_gbuffer choice. */
macs_format bgi_gpu_slot_format(const bg_renderer *r, gpu_slot slot);
/* Ray set number index from the pool, creating it when needed. */
bg_status bgi_gpu_ray_set_get(bg_renderer *r, int index, gpu_ray_set **out);
/* Makes the white texel of the hit passes unless it exists. */
bg_status bgi_gpu_white_prepare(bg_renderer *r);
void bgi_gpu_targets_release(bg_renderer *r);

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
int bgi_gpu_shadow_shared_components(int lights, bool area);
/* Sets the uniforms that follow the view's sample (bg_pixel_at, bg_sample_of) on every pass that
 * samples the lens or an area light; every frame, like the camera's shift. */
bg_status bgi_gpu_sample_uniforms_set(bg_renderer *r);
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

/* ---- rect.c ---- */
/* Grows a to the smallest rectangle holding a and b ({x, y, width, height}; empty ones add nothing). */
void bgi_gpu_rect_union(int a[4], const int b[4]);


#endif
