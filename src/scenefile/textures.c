/* "textures": name -> {"file", "wrap", "encoding", "filter"}: PNG files loaded by the scene. */
#include "scenefile_internal.h"

#include <stdio.h>

static bg_status read_texture(bgi_sf_ctx *ctx, const cJSON *v, const char *name)
{
    static const char *const keys[] = {"file", "wrap", "encoding", "filter", NULL};
    static const char *const wraps[] = {"repeat", "clamp", NULL};
    static const char *const encodings[] = {"srgb", "linear", NULL};
    static const char *const filters[] = {"linear", "nearest", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    const cJSON *f = bgi_sf_member(v, "file");
    if (!f)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "\"file\" is required");
    int wrap = BG_WRAP_REPEAT, enc = BG_TEXTURE_SRGB, filter = BG_FILTER_LINEAR;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "wrap", wraps, &wrap));
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "encoding", encodings, &enc));
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "filter", filters, &filter));
    size_t at = bgi_sf_push_key(ctx, "file");
    char path[BGI_SF_PATH_MAX];
    bg_status st = bgi_sf_file_path(ctx, f, path);
    uint32_t handle = 0;
    if (st == BG_OK) {
        bg_texture_desc d = {(bg_texture_wrap)wrap, (bg_texture_encoding)enc, (bg_texture_filter)filter};
        bgi_sf_note_input(ctx, path);
        st = bg_scene_load_texture_png(ctx->scene, path, &d, &handle);
        if (st != BG_OK)
            st = bgi_sf_fail(ctx, st, "%s", bg_scene_error_message(ctx->scene));
    }
    bgi_sf_pop(ctx, at);
    BGI_SF_TRY(st);
    ctx->out->summary.textures++;
    return bgi_sf_names_add(ctx, &ctx->textures, name, handle);
}

bg_status bgi_sf_read_textures(bgi_sf_ctx *ctx, const cJSON *v)
{
    if (!cJSON_IsObject(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an object of name: texture (got %s)",
                           bgi_sf_type_name(v));
    for (const cJSON *t = v->child; t; t = t->next) {
        size_t at = bgi_sf_push_key(ctx, t->string);
        bg_status st = bgi_sf_names_find(&ctx->textures, t->string)
                           ? bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "the texture name is given twice")
                           : read_texture(ctx, t, t->string);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    return BG_OK;
}
