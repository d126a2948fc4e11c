/* The viewer's window and GPU (view_window.c): a GLFW window with an OpenGL 2.1 context, and MACS
 * and the renderer on it, made from glfwGetProcAddress as any program with its own context makes them. */
#ifndef CLI_VIEW_WINDOW_H
#define CLI_VIEW_WINDOW_H

#include <stdbool.h>
#include <stddef.h>

#include "view.h"

/* Opens a window of width x height titled title, current on this thread, with v->frames.context and
 * v->frames.renderer on it; false with the reason (nothing left open). */
bool view_window_open(viewer *v, int width, int height, const char *title, char *why, size_t why_size);

/* Frees the renderer, MACS and the window, and ends GLFW. */
void view_window_close(viewer *v);

#endif
