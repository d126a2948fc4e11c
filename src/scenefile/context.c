/* The load context: the one error sink, the JSON path the reader stands at, path resolution and the
 * name tables. The first failure's message is the one kept: later failures are consequences. */
#include "scenefile_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void bgi_sf_ctx_init(bgi_sf_ctx *ctx, const char *file, const bg_scenefile_desc *desc, bg_scene *scene,
                     bg_scenefile_result *out, char *message, size_t message_size)
{
    memset(ctx, 0, sizeof *ctx);
    ctx->file = file;
    if (desc) {
        ctx->logger = desc->logger;
        ctx->inputs = desc->inputs;
    }
    ctx->scene = scene;
    ctx->out = out;
    ctx->message = message;
    ctx->message_size = message_size;
    if (message && message_size > 0)
        message[0] = '\0';
    /* The scene keeps its first error: forget an old one, so that a refusal names its own reason. */
    bg_scene_clear_error(scene);
}

static void names_free(bgi_sf_names *names)
{
    for (size_t i = 0; i < names->count; i++)
        free(names->items[i].name);
    free(names->items);
    memset(names, 0, sizeof *names);
}

void bgi_sf_ctx_free(bgi_sf_ctx *ctx)
{
    names_free(&ctx->textures);
    names_free(&ctx->materials);
}

/* "FILE: PATH: " in front of a reason; cut (never overrun) when the buffer is too small. */
static size_t prefix(const bgi_sf_ctx *ctx, char *text, size_t size)
{
    size_t n = 0;
    const char *parts[4] = {ctx->file, ": ", ctx->path_len ? ctx->path : "", ctx->path_len ? ": " : ""};
    for (int i = 0; i < 4; i++)
        for (const char *p = parts[i]; *p && n + 1 < size; p++)
            text[n++] = *p;
    text[n] = '\0';
    return n;
}

static bg_status vfail(bgi_sf_ctx *ctx, bg_status status, const char *format, va_list ap)
{
    if (ctx->status != BG_OK)
        return status;
    ctx->status = status;
    char text[2048];
    size_t n = prefix(ctx, text, sizeof text);
    vsnprintf(text + n, sizeof text - n, format, ap);
    if (ctx->message && ctx->message_size > 0)
        snprintf(ctx->message, ctx->message_size, "%s", text);
    if (ctx->logger.func)
        ctx->logger.func(BG_LOG_ERROR, text, ctx->logger.user);
    return status;
}

bg_status bgi_sf_fail(bgi_sf_ctx *ctx, bg_status status, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    bg_status st = vfail(ctx, status, format, ap);
    va_end(ap);
    return st;
}

bg_status bgi_sf_scene_fail(bgi_sf_ctx *ctx, bg_status status, const char *what)
{
    const char *why = bg_scene_error_message(ctx->scene);
    return bgi_sf_fail(ctx, status, "%s refused: %s", what, why && *why ? why : bg_status_string(status));
}

void bgi_sf_warn(bgi_sf_ctx *ctx, const char *format, ...)
{
    if (!ctx->logger.func)
        return;
    char text[2048];
    size_t n = prefix(ctx, text, sizeof text);
    va_list ap;
    va_start(ap, format);
    vsnprintf(text + n, sizeof text - n, format, ap);
    va_end(ap);
    ctx->logger.func(BG_LOG_WARNING, text, ctx->logger.user);
}

/* A path too long for the buffer is cut, never overrun: the message then still starts right. */
static size_t append(bgi_sf_ctx *ctx, const char *text)
{
    size_t before = ctx->path_len;
    int n = snprintf(ctx->path + before, sizeof ctx->path - before, "%s", text);
    size_t added = n < 0 ? 0 : (size_t)n;
    if (before + added >= sizeof ctx->path)
        added = sizeof ctx->path - 1 - before;
    ctx->path_len = before + added;
    return before;
}

size_t bgi_sf_push_key(bgi_sf_ctx *ctx, const char *key)
{
    size_t before = ctx->path_len;
    if (before > 0)
        append(ctx, ".");
    append(ctx, key);
    return before;
}

size_t bgi_sf_push_index(bgi_sf_ctx *ctx, size_t index)
{
    char text[32];
    snprintf(text, sizeof text, "[%zu]", index);
    return append(ctx, text);
}

void bgi_sf_pop(bgi_sf_ctx *ctx, size_t length)
{
    ctx->path_len = length;
    ctx->path[length] = '\0';
}

void bgi_sf_set_dir_of(bgi_sf_ctx *ctx, const char *file)
{
    const char *slash = strrchr(file, '/');
    size_t n = slash ? (size_t)(slash - file) + 1 : 0;
    if (n >= sizeof ctx->dir)
        n = 0;
    memcpy(ctx->dir, file, n);
    ctx->dir[n] = '\0';
}

bg_status bgi_sf_file_path(bgi_sf_ctx *ctx, const cJSON *v, char *out)
{
    const char *file = NULL;
    bg_status st = bgi_sf_string(ctx, v, &file);
    return st == BG_OK ? bgi_sf_resolve(ctx, file, out) : st;
}

bg_status bgi_sf_resolve(bgi_sf_ctx *ctx, const char *path, char *out)
{
    if (!*path)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "the file name is empty");
    const char *dir = path[0] == '/' ? "" : ctx->dir;
    size_t dl = strlen(dir);
    int n = snprintf(out, BGI_SF_PATH_MAX, "%s%s%s", dir, dl > 0 && dir[dl - 1] != '/' ? "/" : "", path);
    if (n < 0 || n >= BGI_SF_PATH_MAX)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "the path \"%s\" is longer than %d bytes", path,
                           BGI_SF_PATH_MAX - 1);
    return BG_OK;
}

bg_status bgi_sf_names_add(bgi_sf_ctx *ctx, bgi_sf_names *names, const char *name, uint32_t handle)
{
    if (names->count == names->capacity) {
        size_t cap = names->capacity ? 2 * names->capacity : 16;
        bgi_sf_name *items = realloc(names->items, cap * sizeof *items);
        if (!items)
            return bgi_sf_fail(ctx, BG_ERR_OUT_OF_MEMORY, "out of memory for the name table");
        names->items = items;
        names->capacity = cap;
    }
    size_t len = strlen(name);
    char *copy = malloc(len + 1);
    if (!copy)
        return bgi_sf_fail(ctx, BG_ERR_OUT_OF_MEMORY, "out of memory for the name table");
    memcpy(copy, name, len + 1);
    names->items[names->count].name = copy;
    names->items[names->count].handle = handle;
    names->count++;
    return BG_OK;
}

uint32_t bgi_sf_names_find(const bgi_sf_names *names, const char *name)
{
    for (size_t i = 0; i < names->count; i++)
        if (strcmp(names->items[i].name, name) == 0)
            return names->items[i].handle;
    return 0;
}

bg_status bgi_sf_default_material(bgi_sf_ctx *ctx, uint32_t *out)
{
    if (!ctx->default_material) {
        bg_material m = bg_material_init();
        bg_status st = bg_scene_add_material(ctx->scene, &m, &ctx->default_material);
        if (st != BG_OK)
            return bgi_sf_scene_fail(ctx, st, "the default material");
        ctx->out->summary.materials++;
    }
    *out = ctx->default_material;
    return BG_OK;
}
