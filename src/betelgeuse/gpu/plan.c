/* The plan choice: the one place that decides which plan renders a pass of a frame, and falls back.
 * BG_PLAN_MULTIPASS, BG_PLAN_FUSED and BG_PLAN_FUSED_TREE name their plan. BG_PLAN_AUTO takes the
 * fused plan (its tree variant for scenes with many objects or with meshes) unless the settings ask
 * for something only the multipass has or the fused plan declines the frame; the multipass then
 * renders it, and the reason goes to the logger at BG_LOG_INFO. A forced fused plan that cannot
 * render the frame fails instead. */
#include <string.h>

#include "driver.h"

/* BG_PLAN_AUTO walks a tree from this many objects in the scene's tree on, and unrolls below. At
 * 512x512 (one process, 2 quiet cores) many_spheres with 8 and 16 spheres took 79 and 102 ms with
 * the tree against 89 and 170 unrolled; the shared scenes of 2 to 5 objects (paper_earth_shadow,
 * glass, textured_aniso) 21-62 ms against 12-42 ms. */
#define AUTO_TREE_FROM 8

/* Every plan, for bgi_gpu_plans_release (the fused variants share their objects: the second call
 * finds nothing left). */
static const gpu_plan *const every_plan[] = {&bgi_gpu_fused_plan, &bgi_gpu_fused_tree_plan, &bgi_gpu_multipass_plan};

/* A setting or renderer option that only the multipass has, which BG_PLAN_AUTO honours by choosing
 * it (a forced fused plan has none of them and ignores them); NULL when none is asked for. */
static const char *multipass_option(const bg_renderer *r, const bg_render_settings *settings)
{
    if (settings->gpu_disable_skips)
        return "settings.gpu_disable_skips switches off work of the multipass plan";
    if (settings->dmax > 0.0)
        return "settings.dmax sets the multipass plan's depth scale";
    if (r->half_gbuffer)
        return "the renderer was created for a half-float G-buffer, which only the multipass plan has";
    if (r->float_depth)
        return "the renderer was created for a float depth buffer, which only the multipass plan has";
    return NULL;
}

/* BG_PLAN_AUTO goes to the multipass: says why. */
static void fall_back(const bg_renderer *r, const char *why)
{
    bgi_gpu_log(r, BG_LOG_INFO, "rendering with the multipass plan: %s", why);
}

/* The fused plan the settings ask for or BG_PLAN_AUTO would take; NULL for BG_PLAN_MULTIPASS. */
static const gpu_plan *fused_variant(const bg_scene_state *state, bg_gpu_plan asked)
{
    if (asked == BG_PLAN_MULTIPASS)
        return NULL;
    bool tree = asked == BG_PLAN_FUSED_TREE ||
                (asked == BG_PLAN_AUTO && (state->tree_count >= AUTO_TREE_FROM || state->mesh_object_count > 0));
    return tree ? &bgi_gpu_fused_tree_plan : &bgi_gpu_fused_plan;
}

static bg_status choose_and_render(bg_renderer *r, gpu_plan_frame *f)
{
    bg_gpu_plan asked = f->settings->gpu_plan;
    const gpu_plan *fused = fused_variant(f->state, asked);
    char why[MACS_MESSAGE_SIZE];
    r->stats.plan = BG_PLAN_MULTIPASS;
    f->forced = asked == BG_PLAN_FUSED || asked == BG_PLAN_FUSED_TREE;
    const char *option = f->forced ? NULL : multipass_option(r, f->settings);
    /* The multipass draws no environment (docs/gpu_pipeline.md): a frame that would go there is
     * refused, saying why it would. */
    const char *no_env = "the scene has an environment (bg_scene_set_environment), which the multipass plan does not "
                         "draw; it would render this frame because";
    if (f->state->environment.on && !fused)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s settings.gpu_plan asks for it", no_env);
    if (f->state->environment.on && option)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s %s", no_env, option);
    /* Nor does it draw the path integrator, which only the fused plans do. */
    bool path = f->settings->integrator == BG_INTEGRATOR_PATH;
    const char *no_path = "settings.integrator is BG_INTEGRATOR_PATH, which the multipass plan does not draw; it would "
                          "render this frame because";
    if (path && !fused)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s settings.gpu_plan asks for it", no_path);
    if (path && option)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s %s", no_path, option);
    /* Rasterised camera rays replace the tree variant's walk, and nothing of another plan. */
    bool raster = f->settings->primary == BG_PRIMARY_RASTER;
    if (raster && (fused != &bgi_gpu_fused_tree_plan || option))
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "settings.primary is BG_PRIMARY_RASTER, which replaces a walk of "
                            "BG_PLAN_FUSED_TREE, but this frame goes to %s%s%s", fused && !option ? fused->name :
                            "BG_PLAN_MULTIPASS", option ? ": " : "", option ? option : "");
    if (fused && option) {
        fall_back(r, option);
    } else if (fused) {
        bg_status st = fused->render(r, f, why, sizeof why);
        if (st != BG_OK)
            return st;
        if (!why[0]) {
            r->stats.plan = fused->id;
            return BG_OK;
        }
        if (f->forced || raster)
            return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s cannot render this frame: %s", fused->name, why);
        if (f->state->environment.on)
            return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s %s declines it: %s", no_env, fused->name, why);
        if (path)
            return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s %s declines it: %s", no_path, fused->name, why);
        fall_back(r, why);
    }
    f->forced = asked == BG_PLAN_MULTIPASS;
    return bgi_gpu_multipass_plan.render(r, f, why, sizeof why);
}

bg_status bgi_gpu_plan_render(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                              const bg_render_settings *settings, const gpu_frame_out *out)
{
    memset(&r->stats, 0, sizeof r->stats);
    if (state->gpu_range[0])
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "%s (docs/gpu_pipeline.md, \"Float range\")", state->gpu_range);
    uint64_t compiled = macs_context_programs_compiled(r->ctx);
    gpu_plan_frame f = {scene, state, settings, out, false};
    bg_status st = choose_and_render(r, &f);
    r->stats.texture_bytes = r->scene_textures.bytes;
    r->stats.programs_compiled = (int)(macs_context_programs_compiled(r->ctx) - compiled);
    return st;
}

void bgi_gpu_plans_release(bg_renderer *r)
{
    for (size_t i = 0; i < sizeof every_plan / sizeof every_plan[0]; i++)
        every_plan[i]->release(r);
}
