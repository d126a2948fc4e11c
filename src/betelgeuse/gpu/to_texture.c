/* bg_render_gpu_to_texture: the frame ends in the caller's MACS texture instead of a host image.
 * The same checks as bg_render_gpu, with the texture's size and format in the image's place; the
 * frame itself is bgi_gpu_frame_render's, which writes the target on the GPU (fused/fused.c, multipass/multipass_frame.c) and
 * reads back only the tree variant's marks (fallback.c). */

#include "../common/image.h"
#include "../common/render_settings.h"
#include "driver.h"

#define FN "bg_render_gpu_to_texture"

static bg_status render(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                        macs_texture *target)
{
    bg_renderer *r = renderer;
    if (!r)
        return BG_ERR_INVALID_ARGUMENT;
    r->entry = FN;
    if (!scene || !settings)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "%s is NULL", !scene ? "scene" : "settings");
    char message[256];
    bg_status st = bgi_render_settings_check(settings, FN, message, sizeof message);
    if (st != BG_OK)
        return bgi_gpu_fail_checked(r, st, message);
    if (!target)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT,
                        "target is NULL (a macs_texture of the renderer's MACS context is required)");
    if (macs_texture_context(target) != r->ctx)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT,
                        "target belongs to another macs_context than the renderer's (bg_renderer_desc.context)");
    int width = 0, height = 0;
    macs_texture_size(target, &width, &height);
    if (width > BG_MAX_IMAGE_SIDE || height > BG_MAX_IMAGE_SIDE)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "target size %dx%d is outside [1, %d] per side", width, height,
                        BG_MAX_IMAGE_SIDE);
    int max = r->limits.max_texture_size;
    if (width > max || height > max)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "target size %dx%d exceeds the GL texture size limit %d", width, height,
                        max);
    /* RGBA8 takes the settings' encoding; the float formats take linear radiance (RGBA16F rounded to
     * half by GL when the shader's output is stored). */
    macs_format format = macs_texture_format(target);
    bgi_render_view view;
    st = bgi_render_view_make(settings, width, height, FN, &view, message, sizeof message);
    if (st != BG_OK)
        return bgi_gpu_fail_checked(r, st, message);
    gpu_frame_out out = {NULL, 0, target, width, height, format != MACS_FORMAT_RGBA8};
    st = bgi_gpu_frame_render(r, scene, settings, &out, &view);
    r->stats.tiles = 1;
    return st;
}

bg_status bg_render_gpu_to_texture(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                                   macs_texture *target)
{
    if (!renderer)
        return BG_ERR_INVALID_ARGUMENT;
    gpu_entry e;
    bgi_gpu_entry_begin(renderer, settings, &e);
    return bgi_gpu_entry_end(renderer, &e, render(renderer, scene, settings, target));
}
