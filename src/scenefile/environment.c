/* "settings.environment": an equirectangular image around the scene (docs/scene_format.md), a
 * Radiance .hdr (hdr_decode.c) or a PNG, told apart by their first bytes. The file is opened with
 * the checked opener that every input uses, so a FIFO, a directory or a device is refused by name
 * instead of blocking or being read as an image. */
#include "scenefile_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "betelgeuse/io/open_input.h"

/* What the file is, from its first bytes: 'h' Radiance HDR, 'p' PNG, 0 neither. */
static int sniff(FILE *f)
{
    static const unsigned char png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char head[10] = {0};
    size_t n = fread(head, 1, sizeof head, f);
    rewind(f);
    if (n >= 10 && memcmp(head, "#?RADIANCE", 10) == 0)
        return 'h';
    if (n >= 6 && memcmp(head, "#?RGBE", 6) == 0)
        return 'h';
    if (n >= 8 && memcmp(head, png_sig, 8) == 0)
        return 'p';
    return 0;
}

bg_status bgi_sf_load_environment_image(bgi_sf_ctx *ctx, const char *path, uint32_t *out_texture)
{
    char why[256];
    FILE *f = bgi_open_input(path, why, sizeof why);
    if (!f)
        return bgi_sf_fail(ctx, BG_ERR_IO, "%s: %s", path, why);
    int kind = sniff(f);
    if (kind != 'h') {
        fclose(f);
        if (kind == 0)
            return bgi_sf_fail(ctx, BG_ERR_IO, "%s is neither a Radiance HDR (.hdr) nor a PNG file", path);
    }
    bgi_sf_note_input(ctx, path);
    bg_texture_desc desc = {BG_WRAP_REPEAT, BG_TEXTURE_SRGB, BG_FILTER_LINEAR};
    if (kind == 'p') {
        bg_status st = bg_scene_load_texture_png(ctx->scene, path, &desc, out_texture);
        return st == BG_OK ? BG_OK : bgi_sf_fail(ctx, st, "%s", bg_scene_error_message(ctx->scene));
    }
    int w = 0, h = 0;
    float *texels = bgi_sf_hdr_decode(f, &w, &h, why, sizeof why);
    fclose(f);
    if (!texels)
        return bgi_sf_fail(ctx, BG_ERR_IO, "%s: not a readable Radiance HDR image (%s)", path, why);
    /* RGBE decodes to finite values >= 0; alpha is opaque. */
    for (size_t k = 0; k < (size_t)w * (size_t)h; k++)
        texels[4 * k + 3] = 1.0f;
    bg_image img = {w, h, BG_PIXEL_RGBA32F, 0, texels};
    bg_status st = bg_scene_add_texture(ctx->scene, &img, &desc, out_texture);
    bgi_sf_hdr_free(texels);
    return st == BG_OK ? BG_OK : bgi_sf_fail(ctx, st, "%s: %s", path, bg_scene_error_message(ctx->scene));
}

bg_status bgi_sf_read_environment(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"file", "intensity", "light", "sampling", NULL};
    static const char *const samplings[] = {"importance", "uniform", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    const cJSON *f = bgi_sf_member(v, "file");
    if (!f)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "\"file\" is required");
    bg_environment e = bg_environment_init();
    BGI_SF_TRY(bgi_sf_field_number(ctx, v, "intensity", bgi_sf_nonneg, &e.intensity));
    BGI_SF_TRY(bgi_sf_field_bool(ctx, v, "light", &e.lights));
    int sampling = (int)e.sampling;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "sampling", samplings, &sampling));
    e.sampling = (bg_environment_sampling)sampling;
    size_t at = bgi_sf_push_key(ctx, "file");
    char path[BGI_SF_PATH_MAX];
    bg_status st = bgi_sf_file_path(ctx, f, path);
    if (st == BG_OK)
        st = bgi_sf_load_environment_image(ctx, path, &e.texture);
    bgi_sf_pop(ctx, at);
    BGI_SF_TRY(st);
    ctx->out->summary.textures++;
    st = bg_scene_set_environment(ctx->scene, &e);
    return st == BG_OK ? BG_OK : bgi_sf_scene_fail(ctx, st, "the environment");
}
