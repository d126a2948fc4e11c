/* Driver detection and the named skips of util_driver.h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "util_driver.h"

bool util_renderer_is_zink(const char *renderer)
{
    return renderer && strncmp(renderer, "zink", 4) == 0;
}

bool util_context_is_zink(const macs_context *ctx)
{
    macs_gl_info info;
    macs_context_get_gl_info(ctx, &info);
    return util_renderer_is_zink(info.renderer);
}

void util_skip_masked_stencil_clear_on_zink(const macs_context *ctx)
{
    if (!util_context_is_zink(ctx))
        return;
    print_message("skipped on zink: it ignores glClear's stencil bits under a stencil write mask other than "
                  "0xFF (Mesa 22.3 over lavapipe; tests/probe_stencil_clear.c shows it in raw GL)\n");
    skip();
}
