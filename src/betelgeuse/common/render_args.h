/* The caller's arguments both renderers check alike, so that a bad call reads the same on either. */
#ifndef BG_RENDER_ARGS_H
#define BG_RENDER_ARGS_H

#include "betelgeuse.h"
#include "render_view.h"

/* Checks settings, then image, then the window and samples (bgi_render_settings_check, bgi_image_check,
 * bgi_render_view_make) and writes the image's row stride in bytes and the render's view. On failure
 * writes "<where>: <what is wrong>" into message and returns the status. */
bg_status bgi_render_args_check(const char *where, const bg_render_settings *settings, const bg_image *image,
                               size_t *out_stride, bgi_render_view *view, char *message, size_t size);

#endif
