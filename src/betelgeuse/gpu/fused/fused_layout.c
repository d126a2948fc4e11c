/* The structure of a committed scene as the fused plan's program sees it (fused.h,
 * gpu_fused_layout). Invariant: nothing here depends on a value the scene may change without a new
 * structure, except through the material feature classes the multipass specialises on too
 * (shared/material_traits.c, multipass/features.c): transparency > 0, isotropy < 1, roughness < 1/2, a coat, a texture handle. A value
 * that moves a material across one of them changes the program; any other value only a uniform. */
#include <math.h>
#include <string.h>

#include "../../common/alloc.h"
#include "fused.h"

bool bgi_gpu_fused_material_has(const gpu_fused_material *m, gpu_fused_need need)
{
    switch (need) {
    case GPU_FUSED_NEED_USED: return m->used;
    case GPU_FUSED_NEED_ANISO: return m->used && m->aniso;
    case GPU_FUSED_NEED_TRANSPARENT: return m->used && m->transparent;
    case GPU_FUSED_NEED_COAT: return m->used && m->coat;
    case GPU_FUSED_NEED_COAT_ANISO: return m->used && m->coat && m->aniso;
    default: return false;
    }
}

static const gpu_fused_need param_need[GPU_P_COUNT_] = {
#define NEED_(id, local, color, unit, need) GPU_FUSED_NEED_##need,
    GPU_PARAMS(NEED_)
#undef NEED_
};

/* The material's classes and texture lanes; samplers are numbered in order of first use. */
static void describe_material(const bg_material *src, gpu_fused_material *m, gpu_fused_layout *l)
{
    m->transparent = src->transparency.value > 0.0;
    m->glossy = src->glossy;
    m->coat = src->has_coat;
    m->aniso = bgi_gpu_material_may_be_aniso(src);
    m->bounce = bgi_gpu_material_may_bounce(src);
    for (int p = 0; p < GPU_P_COUNT_; p++) {
        double v[3];
        m->sampler[p] = -1;
        m->texture[p] = 0;
        m->channel[p] = 0;
        if (!bgi_gpu_fused_material_has(m, param_need[p]))
            continue;
        bgi_gpu_param_of(src, (gpu_param)p, v, &m->texture[p], &m->channel[p]);
        if (bgi_gpu_param_is_color((gpu_param)p))
            m->channel[p] = 0;
        if (!m->texture[p])
            continue;
        int lane = -1;
        for (int k = 0; k < l->sampler_count; k++)
            if (l->samplers[k] == m->texture[p])
                lane = k;
        if (lane < 0) {
            lane = l->sampler_count++;
            l->samplers[lane] = m->texture[p];
        }
        m->sampler[p] = lane;
        m->textured = true;
    }
}

/* The kinds of objects the tree holds (gpu_fused_tree_kinds). */
static void describe_tree(gpu_fused_layout *l)
{
    gpu_fused_tree_kinds *k = &l->kinds;
    k->all_cast = true;
    for (uint32_t j = 0; j < l->object_count; j++) {
        const gpu_fused_object *o = &l->objects[j];
        if (!o->in_tree)
            continue;
        l->tree_count++;
        k->all_cast &= o->casts_shadows;
        bool uv = bgi_gpu_fused_object_uv(l, j), tangent = bgi_gpu_fused_object_tangent(l, j);
        k->uv |= uv;
        k->tangent |= tangent;
        if (o->shape == BGI_SHAPE_MESH) { /* past the shape tables: its UVs are the mesh's own */
            k->mesh = true;
            k->mesh_casts |= o->casts_shadows;
            continue;
        }
        k->shape[o->shape] = true;
        k->caster[o->shape] |= o->casts_shadows;
        k->mapping[o->uv_mapping] |= uv || tangent;
    }
}

/* Whether some caster can shadow another object: a lone analytic object only ever meets its own
 * surface, which is never tested (docs/shading.md 2.8); a mesh shadows itself (2.10). */
static bool any_shadow(const gpu_fused_layout *l)
{
    for (uint32_t j = 0; j < l->object_count; j++)
        if (l->objects[j].shape == BGI_SHAPE_MESH && l->objects[j].casts_shadows)
            return true;
    if (l->object_count < 2)
        return false;
    for (uint32_t j = 0; j < l->object_count; j++)
        if (l->objects[j].casts_shadows)
            return true;
    return false;
}

/* Shadow tests the shader inlines per light: one per unrolled caster, one walk for the tree's. */
static uint32_t casters(const gpu_fused_layout *l)
{
    uint32_t n = 0;
    bool tree_casts = false;
    for (uint32_t j = 0; j < l->object_count && l->shadows; j++) {
        if (l->objects[j].in_tree)
            tree_casts |= l->objects[j].casts_shadows;
        else
            n += l->objects[j].casts_shadows ? 1 : 0;
    }
    return n + (tree_casts ? 1 : 0);
}

/* Of llvmpipe's loop iterations, what the trace and light loops do not take goes to the tree walks.
 * A pixel makes at most one nearest walk per ray and one shadow walk per light and ray; each walk
 * may also spend a few iterations that end its loops, reserved here. */
static int walk_budget(const gpu_fused_layout *l)
{
    int loops = l->loop_rays * (1 + (l->light_loop ? (int)l->light_count : 0));
    /* Per ray and light: the tree's walk and one per unrolled mesh. */
    long walks = (long)l->loop_rays * (1 + (long)bgi_gpu_fused_layout_lights(l)) * (1 + (long)l->unrolled_meshes);
    long left = GPU_MAX_LOOP - loops - 3 * walks - 64;
    return left > 0 ? (int)left : 0;
}

/* The most rays one pixel can follow down to `depth` levels: a chain without transparency, else
 * the binary tree, pruned by min_weight when given (> 0). The children's weights never sum to more
 * than their parent's in any channel (opaque m + T F + T (1 - F) <= opaque + T = 1, as m <= 1), so
 * the rays of one level weigh at most 3 summed over their channels, and each ray followed has a
 * channel of at least min_weight: at most 3 / min_weight rays per level. Saturates at 2^40. */
static double rays_bound(int depth, bool tree, double min_weight)
{
    if (!tree)
        return depth + 1.0;
    double per_level = min_weight > 0.0 ? floor(3.0 / min_weight) : 1e300;
    double total = 1.0, level = 1.0;
    for (int k = 1; k <= depth && total < 0x1p40; k++) {
        level *= 2.0;
        total += level < per_level ? level : per_level;
    }
    return total < 0x1p40 ? total : 0x1p40;
}

bool bgi_gpu_fused_layout_build(const bg_allocator *a, const bg_scene_state *state, const bg_render_settings *settings,
                            bool tree, bool srgb_table, gpu_fused_layout *out)
{
    gpu_fused_layout l;
    memset(&l, 0, sizeof l);
    l.object_count = state->object_count;
    l.material_count = state->material_count;
    l.light_count = state->light_count;
    l.lens = state->camera.camera.aperture_radius > 0.0;
    l.orthographic = state->camera.orthographic;
    l.area = bgi_gpu_scene_has_area_lights(state);
    l.objects = bgi_alloc(a, (l.object_count ? l.object_count : 1) * sizeof *l.objects);
    l.materials = bgi_alloc(a, (l.material_count ? l.material_count : 1) * sizeof *l.materials);
    l.samplers = bgi_alloc(a, (state->texture_count ? state->texture_count : 1) * sizeof *l.samplers);
    l.sampler_modes = bgi_alloc(a, (state->texture_count ? state->texture_count : 1) * sizeof *l.sampler_modes);
    l.unrolled = bgi_alloc(a, (l.object_count ? l.object_count : 1) * sizeof *l.unrolled);
    if (!l.objects || !l.materials || !l.samplers || !l.sampler_modes || !l.unrolled) {
        bgi_gpu_fused_layout_free(a, &l);
        return false;
    }
    memset(l.materials, 0, (l.material_count ? l.material_count : 1) * sizeof *l.materials);
    for (uint32_t j = 0; j < l.object_count; j++) {
        const bg_object_data *o = &state->objects[j];
        l.objects[j] = (gpu_fused_object){o->shape, o->material, o->uv_mapping, o->casts_shadows, false, 0};
        l.materials[o->material].used = true;
        l.materials[o->material].light = o->light;
        l.mesh |= o->shape == BGI_SHAPE_MESH;
    }
    l.mesh_filters = l.mesh ? bgi_gpu_meshes_filters(state) : 0;
    l.tree = tree;
    for (uint32_t i = 0; i < state->tree_count && tree; i++)
        l.objects[state->tree_objects[i]].in_tree = true;
    for (uint32_t j = 0; j < l.object_count; j++)
        if (!l.objects[j].in_tree) {
            l.objects[j].slot = l.unrolled_count;
            l.unrolled[l.unrolled_count++] = j;
            l.unrolled_meshes += l.objects[j].shape == BGI_SHAPE_MESH ? 1 : 0;
        }
    bool bounce = false;
    for (uint32_t k = 0; k < l.material_count; k++) {
        gpu_fused_material *m = &l.materials[k];
        if (!m->used)
            continue;
        describe_material(&state->materials[k], m, &l);
        l.visible_lights |= m->light > 0;
        l.transparent |= m->transparent;
        l.glossy |= m->glossy;
        l.aniso |= m->aniso;
        l.coat |= m->coat;
        bounce |= m->bounce;
    }
    if (tree)
        describe_tree(&l);
    const bg_environment_data *env = &state->environment;
    l.env = env->on;
    l.env_light = env->on && env->lights;
    l.env_importance = l.env_light && env->marginal;
    l.env_sampler = -1;
    for (int k = 0; k < l.sampler_count && l.env; k++)
        if (l.samplers[k] == env->texture)
            l.env_sampler = k;
    if (l.env && l.env_sampler < 0) {
        l.env_sampler = l.sampler_count++;
        l.samplers[l.env_sampler] = env->texture;
    }
    for (int k = 0; k < l.sampler_count; k++) {
        l.sampler_modes[k] = bgi_gpu_texture_mode(&state->textures[l.samplers[k] - 1], srgb_table);
        l.filters |= l.sampler_modes[k].linear;
        l.srgb |= l.sampler_modes[k].srgb;
    }
    l.shadows = any_shadow(&l) && bgi_gpu_fused_layout_lights(&l) > 0;
    /* A path is a chain whatever its materials: every surface with a non-Dirac part bounces. */
    l.path = settings->integrator == BG_INTEGRATOR_PATH;
    l.path_ambient = l.path && settings->path_ambient;
    l.visible_lights &= l.path;
    l.max_depth = bounce || l.path ? settings->max_depth : 0;
    l.stack = l.transparent && !l.path ? l.max_depth : 0;
    uint32_t tests = bgi_gpu_fused_layout_lights(&l) * (casters(&l) ? casters(&l) : 1);
    l.light_loop = l.light_count > 1 && tests > GPU_FUSED_UNROLLED_SHADOW_TESTS;
    /* The loop bound is a constant of the program, so it cannot depend on min_weight; the pruned
     * bound only tells whether that constant is enough (bgi_gpu_fused_render). Each ray runs the light
     * loop too, where there is one, and every iteration counts against llvmpipe's limit. */
    double full = rays_bound(l.max_depth, l.transparent && !l.path, 0.0);
    int most = GPU_MAX_LOOP / (1 + (l.light_loop ? (int)l.light_count : 0));
    l.loop_rays = full < most ? (int)full : most;
    l.rays_needed = rays_bound(l.max_depth, l.transparent && !l.path, settings->min_weight);
    l.walk_budget = tree || l.mesh ? walk_budget(&l) : 0;
    *out = l;
    return true;
}

void bgi_gpu_fused_layout_free(const bg_allocator *a, gpu_fused_layout *l)
{
    bgi_free(a, l->objects);
    bgi_free(a, l->unrolled);
    bgi_free(a, l->materials);
    bgi_free(a, l->samplers);
    bgi_free(a, l->sampler_modes);
    memset(l, 0, sizeof *l);
}

bool bgi_gpu_fused_object_uv(const gpu_fused_layout *l, uint32_t object)
{
    return l->materials[l->objects[object].material].textured;
}

bool bgi_gpu_fused_object_tangent(const gpu_fused_layout *l, uint32_t object)
{
    return l->materials[l->objects[object].material].aniso;
}

uint32_t bgi_gpu_fused_layout_lights(const gpu_fused_layout *l)
{
    return l->light_count + (l->env_light ? 1u : 0u);
}

bool bgi_gpu_fused_layout_samples(const gpu_fused_layout *l)
{
    return l->lens || l->area || l->glossy || l->env_light || l->path;
}

bool bgi_gpu_fused_layout_walks(const gpu_fused_layout *l)
{
    return l->tree && l->tree_count > 0;
}

bool bgi_gpu_fused_layout_budgeted(const gpu_fused_layout *l)
{
    return bgi_gpu_fused_layout_walks(l) || l->unrolled_meshes > 0;
}
