/* bg_render_gpu: the frame ends in the caller's host image. The arguments are checked here; the
 * frame goes through tiles.c, which renders it whole or in windows. */
#include "../common/render_args.h"
#include "driver.h"

static bg_status render(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings, bg_image *image)
{
    bg_renderer *r = renderer;
    if (!r)
        return BG_ERR_INVALID_ARGUMENT;
    r->entry = "bg_render_gpu";
    if (!scene)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "scene is NULL");
    char message[256];
    size_t stride = 0;
    bgi_render_view view;
    bg_status st = bgi_render_args_check("bg_render_gpu", settings, image, &stride, &view, message, sizeof message);
    if (st != BG_OK)
        return bgi_gpu_fail_checked(r, st, message);
    /* Beyond the GL texture size limit (or the memory budget) the image is rendered in tiles. */
    gpu_frame_out out = {image, stride, NULL, image->width, image->height, image->format == BG_PIXEL_RGBA32F};
    return bgi_gpu_tiles_render(r, scene, settings, &out, &view);
}

bg_status bg_render_gpu(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings, bg_image *image)
{
    if (!renderer)
        return BG_ERR_INVALID_ARGUMENT;
    gpu_entry e;
    bgi_gpu_entry_begin(renderer, settings, &e);
    return bgi_gpu_entry_end(renderer, &e, render(renderer, scene, settings, image));
}
