/* Argument checks shared by bg_render_cpu and bg_render_gpu. */
#include "render_args.h"

#include <stdio.h>

#include "image.h"
#include "render_settings.h"

bg_status bgi_render_args_check(const char *where, const bg_render_settings *settings, const bg_image *image,
                               size_t *out_stride, bgi_render_view *view, char *message, size_t size)
{
    /* A missing argument is named before any field of the other is looked at. */
    if (!settings || !image) {
        snprintf(message, size, "%s: %s is NULL", where, !settings ? "settings" : "image");
        return BG_ERR_INVALID_ARGUMENT;
    }
    bg_status st = bgi_render_settings_check(settings, where, message, size);
    if (st != BG_OK)
        return st;
    char why[256];
    st = bgi_image_check(image, out_stride, why, sizeof why);
    if (st != BG_OK) {
        snprintf(message, size, "%s: %s", where, why);
        return st;
    }
    return bgi_render_view_make(settings, image->width, image->height, where, view, message, size);
}
