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
    st = bgi_pool_reserve(scene, &scene->textures, where);
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
    bg_texture_data t = {w, h, d.wrap, d.filter, texels};
    return bgi_pool_add(scene, &scene->textures, where, &t, out_texture); /* reserved: cannot fail */
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

/* The first field of a live material that references texture, or NULL; *out_material is its id. */
static const char *first_use(const bg_scene *scene, uint32_t texture, uint32_t *out_material)
{
    for (uint32_t k = 0; k < bgi_pool_slot_count(&scene->materials); k++) {
        if (!bgi_pool_live(&scene->materials, k))
            continue;
        const bg_material *m = bgi_pool_item(&scene->materials, k);
        *out_material = bgi_pool_id(&scene->materials, k);
#define USES(field)                    \
    if (m->field.texture == texture) \
        return #field ".texture";
        BG_MATERIAL_TEXTURES(USES)
#undef USES
    }
    return NULL;
}

bg_status bg_scene_remove_texture(bg_scene *scene, uint32_t texture)
{
    static const char where[] = "bg_scene_remove_texture";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot, material;
    bg_status st = bgi_pool_lookup(scene, &scene->textures, where, "texture", texture, &slot);
    if (st != BG_OK)
        return st;
    const char *field = first_use(scene, texture, &material);
    if (field) {
        char t_text[BG_HANDLE_TEXT_SIZE], m_text[BG_HANDLE_TEXT_SIZE];
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: texture %s is used by material %s (%s)", where,
                             bgi_handle_text(texture, t_text), bgi_handle_text(material, m_text), field);
    }
    if (bgi_environment_uses(scene, texture)) {
        char t_text[BG_HANDLE_TEXT_SIZE];
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: texture %s is the scene's environment", where,
                              bgi_handle_text(texture, t_text));
    }
    /* The committed state may still read the texels: they are freed by the next successful commit. */
    bg_array *retired = &scene->retired_texels;
    st = bgi_array_reserve(scene, retired, retired->count + 1, sizeof(float *), where);
    if (st != BG_OK)
        return st;
    bg_texture_data *t = bgi_pool_item(&scene->textures, slot);
    ((float **)retired->data)[retired->count++] = t->texels;
    t->texels = NULL;
    bgi_pool_remove(&scene->textures, slot);
    return BG_OK;
}
