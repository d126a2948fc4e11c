/* Groups objects into batches: several objects tested in one intersection or shadow pass
 * (docs/gpu_pipeline.md). On llvmpipe a pass costs its scissor area whatever the ray set holds (writing
 * gl_FragDepth moves the stencil test after the shader), so fewer, longer passes save most where
 * few rays are live; what bounds a batch is the hardware (uniform components, texture units), the
 * shader length (GPU_BATCH_MAX) and, for camera rays, the area a merged scissor would add.
 *
 * Intersection batches are runs of consecutive objects: ties between objects go to the one drawn
 * first, and a run keeps that order both inside the pass (hit_pass.c) and between passes.
 * Shadow batches may take any casters of a group: visibility is a product of 0s and 1s. */
#include "multipass.h"

/* Per-pass cost on llvmpipe in pixel-object tests: what a pass costs beyond its pixels (draw,
 * framebuffer binding, uniform upload, tile setup). An estimate, not a measurement: on the paper's
 * sphere-and-plane scene the merge it allows is 2-5 % slower (docs/gpu_pipeline.md, Batching). */
#define PASS_COST_PIXELS 4096.0

static bool batching(const bg_renderer *r)
{
    return !(r->multipass->key.disable_skips & BG_SKIP_BATCH);
}

bool bgi_gpu_batch_scissor(const bg_scene_state *state, const gpu_batch *b, const gpu_view *view, int rect[4])
{
    rect[0] = rect[1] = rect[2] = rect[3] = 0;
    for (int j = 0; j < b->count; j++) {
        int one[4];
        if (!bgi_gpu_object_scissor(state, (uint32_t)(b->first + j), view, one))
            return false;
        bgi_gpu_rect_union(rect, one);
    }
    return true;
}

/* Camera-ray pixels of a run (the whole image when some object is unbounded or the scissor is off). */
static double camera_area(const bg_renderer *r, const bg_scene_state *state, int first, int count)
{
    double full = (double)r->multipass->width * (double)r->multipass->height;
    if (r->multipass->key.disable_skips & BG_SKIP_SCISSOR)
        return full;
    gpu_batch b = {NULL, first, count, 0};
    int rect[4];
    if (!bgi_gpu_batch_scissor(state, &b, &r->view, rect))
        return full;
    return (double)rect[2] * (double)rect[3];
}

/* Whether adding object `next` to the run first .. first + count - 1 costs camera rays no more than
 * it saves. A scene whose rays bounce always merges: every secondary set covers the same rectangle
 * for all objects (multipass_frame.c), where one pass fewer is a pure saving, and those sets outnumber the
 * camera's one. Otherwise the cost of a pass is its overhead plus its area times (1 + objects): the
 * per-pixel work that does not depend on the objects counts once. */
static bool merge_pays(const bg_renderer *r, const bg_scene_state *state, int first, int count)
{
    bool bounces = r->multipass->key.bounces && (r->multipass->features.bounce || (r->multipass->key.disable_skips & BG_SKIP_BOUNCE_CULL));
    if (bounces)
        return true;
    double run = camera_area(r, state, first, count);
    double alone = camera_area(r, state, first + count, 1);
    double merged = camera_area(r, state, first, count + 1);
    return merged * (double)(count + 2) <= run * (double)(count + 1) + alone * 2.0 + PASS_COST_PIXELS;
}

/* Whether some texture of the scene is sampled through the sRGB table. */
static bool srgb_table(const bg_renderer *r, const bg_scene_state *state)
{
    bool table = bgi_gpu_srgb_table(r);
    for (uint32_t i = 0; i < state->texture_count && table; i++)
        if (bgi_gpu_texture_mode(&state->textures[i], table).srgb)
            return true;
    return false;
}

int bgi_gpu_batch_plan_hits(const bg_renderer *r, const bg_scene_state *state, gpu_batch *out)
{
    int n = (int)state->object_count, batches = 0;
    /* The ray maps take three, the mesh textures two, the sRGB table one where the scene has an
     * 8-bit sRGB texture decoded through it (counted whether or not the batch samples it). */
    int units = r->limits.max_texture_units - 3 - (r->multipass->features.mesh ? 2 : 0) - (srgb_table(r, state) ? 1 : 0);
    int budget = macs_context_max_uniform_components(r->ctx) - bgi_gpu_hit_shared_components();
    for (int o = 0; o < n;) {
        uint32_t textures[GPU_BATCH_MAX * GPU_HIT_MAX_TEXTURES];
        int texture_count = 0, comps = 0, count = 0;
        while (o + count < n && count < GPU_BATCH_MAX) {
            uint32_t own[GPU_HIT_MAX_TEXTURES];
            int own_count = 0;
            int c = bgi_gpu_hit_object_needs(r, state, (uint32_t)(o + count), own, &own_count);
            /* Its textures join the run's on trial: kept only if the object goes in. */
            int with_own = texture_count;
            for (int i = 0; i < own_count; i++)
                bgi_gpu_hit_texture_lane(textures, &with_own, own[i]);
            /* The first object always goes in: its one-object pass is what exists without batching. */
            if (count > 0 && (!batching(r) || comps + c > budget || with_own > units ||
                              !merge_pays(r, state, o, count)))
                break;
            comps += c;
            texture_count = with_own;
            count++;
        }
        out[batches++] = (gpu_batch){NULL, o, count, 0};
        o += count;
    }
    return batches;
}

int bgi_gpu_batch_plan_shadows(const bg_renderer *r, const bg_scene_state *state, int group, int first, int n,
                           gpu_batch *out)
{
    int lights = (int)state->light_count - group * GPU_LIGHTS_PER_GROUP;
    if (lights > GPU_LIGHTS_PER_GROUP)
        lights = GPU_LIGHTS_PER_GROUP;
    int per_batch = (macs_context_max_uniform_components(r->ctx) - bgi_gpu_shadow_shared_components(lights, r->multipass->features.area)) /
                    bgi_gpu_shadow_object_components();
    if (per_batch > GPU_BATCH_MAX)
        per_batch = GPU_BATCH_MAX;
    if (per_batch < 1 || !batching(r))
        per_batch = 1;
    int batches = 0;
    for (int i = 0; i < n; i += per_batch)
        out[batches++] = (gpu_batch){NULL, first + i, n - i < per_batch ? n - i : per_batch, group};
    return batches;
}
