/* Textures: a caller image copied at its own precision, rows flipped into GL order (row 0 of the
 * stored texture is the image's bottom row, v = 0). RGBA8 stays bytes, 4 a texel, a quarter of
 * linear floats; its colour channels are decoded from sRGB where they are sampled, by the one table
 * of the exact piecewise EOTF (srgb.h) that both renderers read; alpha is always linear. */
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
    bool bytes = image->format == BG_PIXEL_RGBA8;
    size_t row = (size_t)w * 4 * (bytes ? 1 : sizeof(float));
    unsigned char *texels = bgi_alloc(&scene->allocator, row * (size_t)h);
    if (!texels)
        return bgi_scene_fail(scene, BG_ERR_OUT_OF_MEMORY, "%s: out of memory for a %dx%d texture", where, w, h);
    for (int y = 0; y < h; y++)
        memcpy(texels + (size_t)y * row, (const unsigned char *)image->pixels + (size_t)(h - 1 - y) * stride, row);
    bg_texture_data t = {w, h, d.wrap, d.filter, bytes ? NULL : (float *)(void *)texels, bytes ? texels : NULL,
                         bytes && d.encoding == BG_TEXTURE_SRGB};
    return bgi_pool_add(scene, &scene->textures, where, &t, out_texture); /* reserved: cannot fail */
}

double bgi_texture_channel(const bg_texture_data *t, size_t k, int c)
{
    if (t->texels)
        return t->texels[4 * k + (size_t)c];
    unsigned char b = t->bytes[4 * k + (size_t)c];
    return t->srgb && c < 3 ? bgi_srgb_table[b] : b / 255.0;
}

void bgi_texture_texel(const bg_texture_data *t, size_t k, double rgba[4])
{
    for (int c = 0; c < 4; c++)
        rgba[c] = bgi_texture_channel(t, k, c);
}

size_t bgi_texture_bytes(const bg_texture_data *t)
{
    return (size_t)t->width * (size_t)t->height * 4 * (t->bytes ? 1 : sizeof(float));
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
    st = bgi_array_reserve(scene, retired, retired->count + 1, sizeof(void *), where);
    if (st != BG_OK)
        return st;
    bg_texture_data *t = bgi_pool_item(&scene->textures, slot);
    ((void **)retired->data)[retired->count++] = t->texels ? (void *)t->texels : (void *)t->bytes;
    t->texels = NULL;
    t->bytes = NULL;
    bgi_pool_remove(&scene->textures, slot);
    return BG_OK;
}
