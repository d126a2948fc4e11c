/* Every file a load reads goes through here: only regular files are opened, without blocking, and
 * the caller hears of each one before it is read (a command keeps its outputs off its inputs). */
#include "scenefile_internal.h"

#include "betelgeuse/io/open_input.h"

void bgi_sf_note_input(bgi_sf_ctx *ctx, const char *path)
{
    if (ctx->inputs.func)
        ctx->inputs.func(path, ctx->inputs.user);
}

bg_status bgi_sf_open_input(bgi_sf_ctx *ctx, const char *path, const char *what, FILE **out)
{
    char why[256];
    *out = bgi_open_input(path, why, sizeof why);
    if (!*out)
        return what ? bgi_sf_fail(ctx, BG_ERR_IO, "%s: %s", what, why) : bgi_sf_fail(ctx, BG_ERR_IO, "%s", why);
    bgi_sf_note_input(ctx, path);
    return BG_OK;
}
