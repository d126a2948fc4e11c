/* Every pass of a frame for one scene structure and image size (docs/gpu_pipeline.md), in the
 * order the frame runs them: the ray passes (ray_passes.c), the intersection batches, the shadow
 * casters of each light group and their batches, the light passes, ambient and emission. The top
 * of gpu/'s pass building: it calls the builders (ray_passes.c, hit_pass.c, light_pass.c,
 * batch.c) and none of them calls back. */
#include <string.h>

#include "../../common/alloc.h"
#include "multipass.h"

/* Signed side of point p (w = 1) or direction p (w = 0) relative to the plane of object o. */
static double plane_side(const bg_object_data *o, const double p[3], double w)
{
    const double(*nm)[3] = o->normal_to_world;
    double n[3] = {nm[0][1], nm[1][1], nm[2][1]};
    double q[3] = {o->to_world[0][3], o->to_world[1][3], o->to_world[2][3]};
    return (p[0] - w * q[0]) * n[0] + (p[1] - w * q[1]) * n[1] + (p[2] - w * q[2]) * n[2];
}

/* Whether a plane can block a light of the group from any other object's surface: only if some
 * other object reaches the far side of the plane from that light (or the light is on the plane,
 * or another plane, which reaches everywhere, exists). Points on the plane itself are never tested
 * against it. */
static bool plane_can_shadow(const bg_scene_state *state, uint32_t o, int group)
{
    const bg_object_data *plane = &state->objects[o];
    uint32_t first = (uint32_t)group * GPU_LIGHTS_PER_GROUP;
    for (uint32_t k = first; k < state->light_count && k < first + GPU_LIGHTS_PER_GROUP; k++) {
        const bg_light *l = &state->lights[k];
        double side;
        if (l->type == BG_LIGHT_DIRECTIONAL) {
            double towards[3] = {-l->direction.x, -l->direction.y, -l->direction.z};
            side = plane_side(plane, towards, 0.0);
        } else {
            double at[3] = {l->position.x, l->position.y, l->position.z};
            side = plane_side(plane, at, 1.0);
        }
        if (side == 0.0)
            return true;
        for (uint32_t j = 0; j < state->object_count; j++) {
            const bg_object_data *other = &state->objects[j];
            if (j == o)
                continue;
            if (!other->bounded)
                return true;
            for (int c = 0; c < 8; c++) {
                double p[3] = {(c & 1) ? other->bounds_max[0] : other->bounds_min[0],
                               (c & 2) ? other->bounds_max[1] : other->bounds_min[1],
                               (c & 4) ? other->bounds_max[2] : other->bounds_min[2]};
                if (plane_side(plane, p, 1.0) * side <= 0.0)
                    return true;
            }
        }
    }
    return false;
}

/* Whether object o needs a shadow pass for a light group: it must cast shadows, some other object
 * must exist for it to shadow (a lone convex object can only shadow itself, which is never tested;
 * a mesh shadows itself, docs/shading.md 2.10), and a plane must have something on its far side
 * from one of the group's lights. */
static bool shadow_needed(const bg_scene_state *state, uint32_t o, int group)
{
    if (!state->objects[o].casts_shadows)
        return false;
    if (state->objects[o].shape == BGI_SHAPE_MESH)
        return true;
    if (state->object_count < 2)
        return false;
    return state->objects[o].bounded || plane_can_shadow(state, o, group);
}

/* Room for the most passes the scene can need: one intersection pass per object, one shadow pass
 * per object and light group, one light pass per group. */
static bg_status allocate_pass_lists(bg_renderer *r, const bg_scene_state *state)
{
    gpu_passes *p = &r->multipass->passes;
    int groups = (int)((state->light_count + GPU_LIGHTS_PER_GROUP - 1) / GPU_LIGHTS_PER_GROUP);
    p->object_count = (int)state->object_count;
    p->group_count = groups;
    size_t n_hit = state->object_count ? state->object_count : 1;
    size_t n_shadow = (size_t)state->object_count * (size_t)(groups ? groups : 1);
    if (!n_shadow)
        n_shadow = 1;
    p->hit = bgi_alloc(&r->allocator, n_hit * sizeof *p->hit);
    p->shadow = bgi_alloc(&r->allocator, n_shadow * sizeof *p->shadow);
    p->casters = bgi_alloc(&r->allocator, n_shadow * sizeof *p->casters);
    p->caster_blocks = bgi_alloc(&r->allocator, n_shadow * sizeof *p->caster_blocks);
    p->light = bgi_alloc(&r->allocator, (size_t)(groups ? groups : 1) * sizeof *p->light);
    if (!p->hit || !p->shadow || !p->casters || !p->caster_blocks || !p->light)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for %u objects", state->object_count);
    memset(p->light, 0, (size_t)(groups ? groups : 1) * sizeof *p->light);
    return BG_OK;
}

/* Builds the planned intersection batches; a batch whose shader GL refuses becomes one pass per
 * object (the order, and so every tie, stays the same). */
static bg_status build_hit_batches(bg_renderer *r, const bg_scene_state *state)
{
    gpu_passes *p = &r->multipass->passes;
    int n = (int)state->object_count;
    gpu_batch *plan = bgi_alloc(&r->allocator, (size_t)(n ? n : 1) * sizeof *plan);
    if (!plan)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for %u objects", state->object_count);
    int planned = bgi_gpu_batch_plan_hits(r, state, plan);
    bg_status st = BG_OK;
    for (int b = 0; b < planned && st == BG_OK; b++) {
        bool rejected = false;
        gpu_batch *out = &p->hit[p->hit_count];
        *out = plan[b];
        st = bgi_gpu_hit_pass_build(r, state, (uint32_t)plan[b].first, plan[b].count, plan[b].count > 1, &out->pass,
                                &rejected);
        if (st == BG_OK && !rejected) {
            p->hit_count++;
            continue;
        }
        for (int j = 0; j < plan[b].count && st == BG_OK; j++) {
            out = &p->hit[p->hit_count];
            *out = (gpu_batch){NULL, plan[b].first + j, 1, 0};
            st = bgi_gpu_hit_pass_build(r, state, (uint32_t)out->first, 1, false, &out->pass, NULL);
            if (st == BG_OK)
                p->hit_count++;
        }
    }
    bgi_free(&r->allocator, plan);
    return st;
}

/* Builds one planned shadow batch, or one pass per object where GL refuses the batched shader. */
static bg_status build_shadow_batch(bg_renderer *r, const bg_scene_state *state, const gpu_batch *planned)
{
    gpu_passes *p = &r->multipass->passes;
    bool rejected = false;
    gpu_batch *out = &p->shadow[p->shadow_count];
    *out = *planned;
    bg_status st = bgi_gpu_shadow_pass_build(r, state, &p->casters[planned->first], &p->caster_blocks[planned->first],
                                         planned->count, planned->group, planned->count > 1, &out->pass, &rejected);
    if (st == BG_OK && !rejected) {
        p->shadow_count++;
        return BG_OK;
    }
    for (int j = 0; j < planned->count && st == BG_OK; j++) {
        out = &p->shadow[p->shadow_count];
        *out = (gpu_batch){NULL, planned->first + j, 1, planned->group};
        st = bgi_gpu_shadow_pass_build(r, state, &p->casters[out->first], &p->caster_blocks[out->first], 1,
                                   planned->group, false, &out->pass, NULL);
        if (st == BG_OK)
            p->shadow_count++;
    }
    return st;
}

/* Appends group g's casters that need (kept) or do not need (!kept) a shadow pass to the caster
 * list, with whether they block; returns how many were added. */
static int collect_casters(gpu_passes *p, const bg_scene_state *state, int g, bool kept)
{
    int first = p->caster_count;
    for (uint32_t o = 0; o < state->object_count; o++) {
        if (shadow_needed(state, o, g) != kept)
            continue;
        p->casters[p->caster_count] = o;
        p->caster_blocks[p->caster_count++] = kept;
    }
    return p->caster_count - first;
}

/* Plans and builds the shadow batches of casters[first .. first + n - 1] in group g. */
static bg_status build_shadow_batches(bg_renderer *r, const bg_scene_state *state, int g, int first, int n)
{
    gpu_batch *plan = bgi_alloc(&r->allocator, (size_t)n * sizeof *plan);
    if (!plan)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for shadow passes");
    int planned = bgi_gpu_batch_plan_shadows(r, state, g, first, n, plan);
    bg_status st = BG_OK;
    for (int b = 0; b < planned && st == BG_OK; b++)
        st = build_shadow_batch(r, state, &plan[b]);
    bgi_free(&r->allocator, plan);
    return st;
}

/* Shadow casters group by group. With the cull switched off the objects it would drop are in too,
 * without a test and in batches of their own, so that the pass count shows the saving. *any_shadow
 * says whether some shadow pass exists (the light passes then read the visibility texture). */
static bg_status build_shadow_passes(bg_renderer *r, const bg_scene_state *state, bool *any_shadow)
{
    gpu_passes *p = &r->multipass->passes;
    bool cull = !(r->multipass->key.disable_skips & BG_SKIP_SHADOW_CULL);
    bg_status st = BG_OK;
    *any_shadow = false;
    for (int g = 0; g < p->group_count && st == BG_OK; g++) {
        for (int kept = 1; kept >= 0 && st == BG_OK; kept--) {
            if (!kept && cull)
                break;
            int first = p->caster_count;
            int n = collect_casters(p, state, g, kept == 1);
            if (n == 0)
                continue;
            *any_shadow = true;
            st = build_shadow_batches(r, state, g, first, n);
        }
    }
    return st;
}

/* Ambient and emission get a pass of their own rather than riding on the first light pass: the
 * addition order into the accumulation (and so every rounding) then never depends on whether the
 * light pass's inputs fit the texture units, and generic and specialised shaders agree. */
static bg_status build_light_passes(bg_renderer *r, const bg_scene_state *state, bool any_shadow)
{
    gpu_passes *p = &r->multipass->passes;
    bg_status st = BG_OK;
    for (int g = 0; g < p->group_count && st == BG_OK; g++)
        st = bgi_gpu_light_pass_build(r, state, g, any_shadow, &p->light[g]);
    if (st == BG_OK)
        st = bgi_gpu_light_pass_build(r, state, p->group_count, false, &p->once);
    return st;
}

bg_status bgi_gpu_passes_build(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings)
{
    bool any_shadow = false;
    bg_status st = allocate_pass_lists(r, state);
    if (st == BG_OK)
        st = bgi_gpu_ray_passes_build(r, state, settings);
    if (st == BG_OK)
        st = build_hit_batches(r, state);
    if (st == BG_OK)
        st = build_shadow_passes(r, state, &any_shadow);
    if (st == BG_OK)
        st = build_light_passes(r, state, any_shadow);
    return st;
}

static void release(bg_renderer *r, gpu_passes *p)
{
    macs_pass_destroy(p->camera);
    macs_pass_destroy(p->mark);
    macs_pass_destroy(p->background);
    macs_pass_destroy(p->once);
    macs_pass_destroy(p->reflect);
    macs_pass_destroy(p->refract);
    macs_pass_destroy(p->resolve);
    macs_pass_destroy(p->resolve_float);
    int groups = p->group_count;
    for (int b = 0; p->hit && b < p->hit_count; b++)
        macs_pass_destroy(p->hit[b].pass);
    for (int b = 0; p->shadow && b < p->shadow_count; b++)
        macs_pass_destroy(p->shadow[b].pass);
    for (int g = 0; p->light && g < groups; g++)
        macs_pass_destroy(p->light[g]);
    bgi_free(&r->allocator, p->hit);
    bgi_free(&r->allocator, p->shadow);
    bgi_free(&r->allocator, p->casters);
    bgi_free(&r->allocator, p->caster_blocks);
    bgi_free(&r->allocator, p->light);
    memset(p, 0, sizeof *p);
}

void bgi_gpu_passes_release(bg_renderer *r)
{
    release(r, &r->multipass->passes);
    release(r, &r->multipass->retired);
}

void bgi_gpu_passes_retire(bg_renderer *r)
{
    release(r, &r->multipass->retired);
    r->multipass->retired = r->multipass->passes;
    memset(&r->multipass->passes, 0, sizeof r->multipass->passes);
}

void bgi_gpu_passes_release_retired(bg_renderer *r)
{
    /* The float resolve is built lazily at a texture frame's end (multipass_frame.c), after this:
     * its old pass stays until then, so that MACS's program cache hands its program over and a
     * camera move compiles nothing there either. */
    if (r->multipass->retired.resolve_float) {
        macs_pass_destroy(r->multipass->resolve_float_retired);
        r->multipass->resolve_float_retired = r->multipass->retired.resolve_float;
        r->multipass->retired.resolve_float = NULL;
    }
    release(r, &r->multipass->retired);
}
