/* One frame of the committed scene: the driver's step between the entry points (through tiles.c) and
 * the plan choice (plan.c). The committed state is read here, once per frame; a frame of several
 * samples goes to samples.c, which hands each sample's pass to the plan choice. */
#include "../common/render_settings.h"
#include "driver.h"

bg_status bgi_gpu_frame_render(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings,
                               const gpu_frame_out *out, const bgi_render_view *view)
{
    const bg_scene_state *state = bgi_scene_committed(scene);
    if (!state)
        return bgi_gpu_fail(r, BG_ERR_NOT_COMMITTED, "the scene was never committed");
    if (!bgi_render_progress(settings, 0.0))
        return bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress before the first pass; the "
                            "pixels of this frame (of this tile, when tiled) are untouched");
    if (view->samples > 1)
        return bgi_gpu_samples_render(r, scene, state, settings, out, view);
    bgi_gpu_view_for_sample(view, 0, &r->view);
    bg_status st = bgi_gpu_plan_render(r, scene, state, settings, out);
    if (st == BG_OK)
        bgi_render_progress(settings, 1.0);
    return st;
}
