/* Showing a frame in the viewer's window (view_display.c), with the GL of the window's context. */
#ifndef CLI_VIEW_DISPLAY_H
#define CLI_VIEW_DISPLAY_H

#include <stdbool.h>
#include <stddef.h>

#include "macs.h"

typedef struct view_display view_display;

/* Loads the few GL functions the display needs through GLFW (the context must be current); false
 * with the reason when one is missing. */
bool view_display_create(view_display **out, char *why, size_t why_size);

/* Draws texture over the whole window framebuffer (width x height pixels), scaled up with GL_NEAREST
 * when it is smaller, so that a reduced moving frame shows its own pixels rather than a blur; then
 * swaps the window's buffers and waits until the GPU has done it all. */
void view_display_show(view_display *d, void *window, const macs_texture *texture, int width, int height);

void view_display_destroy(view_display *d);

#endif
