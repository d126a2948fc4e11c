/* Test helpers: which GL implementation a suite runs on, and the named skips for a driver's own
 * defects, each shown by a reduced raw-GL program (README, "Run the tests"; docs/architecture.md,
 * "Tests"). A skip is printed with its reason and counted as skipped, never as passed. */
#ifndef UTIL_DRIVER_H
#define UTIL_DRIVER_H

#include <stdbool.h>

#include "macs.h"

/* Whether a GL_RENDERER string names Mesa's zink (GL on Vulkan): "zink (llvmpipe ...)" over
 * lavapipe, "zink (<the GPU>)" over a hardware Vulkan driver. NULL is not zink. */
bool util_renderer_is_zink(const char *renderer);

/* Whether ctx's GL context is zink, by its GL_RENDERER. */
bool util_context_is_zink(const macs_context *ctx);

/* zink (Mesa 22.3) ignores glClear's stencil bits when the stencil write mask is not all ones:
 * the buffer keeps its old values (tests/probe_stencil_clear.c shows it in raw GL). A test of
 * macs_depth_stencil_clear's write mask calls this before its first masked clear: on zink it prints
 * the reason and skips the rest of the test; elsewhere it returns. */
void util_skip_masked_stencil_clear_on_zink(const macs_context *ctx);

#endif
