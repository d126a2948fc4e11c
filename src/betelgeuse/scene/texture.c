/* Textures: a caller image copied into linear float RGBA, rows flipped into GL order (row 0 of
 * the stored texture is the image's bottom row, v = 0). RGBA8 colour data is decoded from sRGB
 * with the exact piecewise EOTF (srgb.h); alpha is always linear. */
#include <math.h>
#include <string.h>

#include "../common/alloc.h"
#include "../common/image.h"
#include "scene_private.h"
#include "../common/srgb.h"

bg_status bgi_texture_add(bg_scene *scene, const char *where, const bg_image *image,
                         const bg_texture_desc *desc, uint32_t *out_texture)
{
    char msg[256];
    size_t stride;
    bg_status st = bgi_image_check(image, &stride, msg, sizeof msg);
    if (st != BG_OK)
        return bgi_scene_fail(scene, st, "%s: %s", where, msg);
    bg_texture_desc d = {BG_WRAP_REPEAT, BG_TEXTURE_SRGB, BG_FILTER_LINEAR};
    if (desc)
        d = *desc;
    if ((int)d.wrap < 0 || d.wrap > BG_WRAP_CLAMP)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: desc.wrap = %d is not a bg_texture_wrap", where, (int)d.wrap);
    if ((int)d.filter < 0 || d.filter > BG_FILTER_NEAREST)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: desc.filter = %d is not a bg_texture_filter", where,
                             (int)d.filter);
    if ((int)d.encoding < 0 || d.encoding > BG_TEXTURE_LINEAR)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: desc.encoding = %d is not a bg_texture_encoding",
                             where, (int)d.encoding);

    int w = image->width, h = image->height;
    /* Float input is taken as linear whatever the encoding; it must be finite and non-negative. */
    if (image->format == BG_PIXEL_RGBA32F) {
        for (int y = 0; y < h; y++) {
            const float *row = (const float *)((const unsigned char *)image->pixels + (size_t)y * stride);
            for (int i = 0; i < w * 4; i++)
                if (!isfinite(row[i]) || row[i] < 0.0f)
                    return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT,
                                         "%s: image pixel (%d, %d) channel %d = %g is not finite and >= 0",
                                         where, i / 4, y, i % 4, (double)row[i]);
        }
    }
    st = bgi_array_reserve(scene, &scene->textures, scene->textures.count + 1, sizeof(bg_texture_data), where);
    if (st != BG_OK)
        return st;
    size_t bytes = (size_t)w * (size_t)h * 4 * sizeof(float);
    float *texels = bgi_alloc(&scene->allocator, bytes);
    if (!texels)
        return bgi_scene_fail(scene, BG_ERR_OUT_OF_MEMORY, "%s: out of memory for a %dx%d texture", where, w, h);

    float table[256];
    for (int i = 0; i < 256; i++)
        table[i] = d.encoding == BG_TEXTURE_SRGB ? (float)bgi_srgb_to_linear(i / 255.0) : (float)(i / 255.0);
    for (int y = 0; y < h; y++) {
        const unsigned char *src = (const unsigned char *)image->pixels + (size_t)(h - 1 - y) * stride;
        float *dst = texels + (size_t)y * (size_t)w * 4;
        if (image->format == BG_PIXEL_RGBA32F) {
            memcpy(dst, src, (size_t)w * 4 * sizeof(float));
            continue;
        }
        for (int x = 0; x < w; x++) {
            for (int c = 0; c < 3; c++)
                dst[4 * x + c] = table[src[4 * x + c]];
            dst[4 * x + 3] = (float)(src[4 * x + 3] / 255.0);
        }
    }
    bg_texture_data *t = &((bg_texture_data *)scene->textures.data)[scene->textures.count++];
    t->width = w;
    t->height = h;
    t->wrap = d.wrap;
    t->filter = d.filter;
    t->texels = texels;
    *out_texture = scene->textures.count;
    return BG_OK;
}

bg_status bg_scene_add_texture(bg_scene *scene, const bg_image *image, const bg_texture_desc *desc,
                               uint32_t *out_texture)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!out_texture)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "bg_scene_add_texture: out_texture is NULL");
    return bgi_texture_add(scene, "bg_scene_add_texture", image, desc, out_texture);
}
