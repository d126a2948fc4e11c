/* The window and the GPU on it (view_window.h). GLFW 3.3 gives windows, GL contexts and input and
 * nothing else the viewer would not use (docs/command.md says why it, not SDL); its
 * glfwGetProcAddress is the get_proc_address MACS asks a caller's own context for. */
#include "view_window.h"

#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

static macs_gl_proc glfw_proc(const char *name, void *user)
{
    (void)user;
    return (macs_gl_proc)glfwGetProcAddress(name);
}

/* GLFW's last error, or what failed when it has none. */
static void glfw_failure(char *why, size_t size, const char *what)
{
    const char *description = NULL;
    glfwGetError(&description);
    snprintf(why, size, "%s%s%s", what, description ? ": " : "", description ? description : "");
}

bool view_window_open(viewer *v, int width, int height, const char *title, char *why, size_t size)
{
    if (!glfwInit()) {
        glfw_failure(why, size, "GLFW could not start (is there a display? DISPLAY or WAYLAND_DISPLAY)");
        return false;
    }
    /* GL 2.1, the version the libraries are written for; a compatibility context, as MACS needs. */
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    /* The window is the frame: its pixels are the rendered ones, never stretched to another aspect. */
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    GLFWwindow *w = glfwCreateWindow(width, height, title, NULL, NULL);
    if (!w) {
        glfw_failure(why, size, "no window with an OpenGL 2.1 context");
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(w);
    /* No wait for the display's refresh: a ray-traced frame is slower than one anyway, and the frame
     * times the resolution rule measures must be the render's. */
    glfwSwapInterval(0);
    v->window = w;
    glfwGetFramebufferSize(w, &v->window_width, &v->window_height);
    macs_context_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.get_proc_address = glfw_proc;
    bg_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    char reason[900] = "";
    if (macs_context_create(&cd, &v->frames.context, reason, sizeof reason) != MACS_OK ||
        ((rd.context = v->frames.context),
         bg_renderer_create(&rd, &v->frames.renderer, reason, sizeof reason) != BG_OK)) {
        snprintf(why, size, "the window's OpenGL context: %s", reason);
        view_window_close(v);
        return false;
    }
    return true;
}

void view_window_close(viewer *v)
{
    view_frames_free(&v->frames);
    bg_renderer_destroy(v->frames.renderer);
    macs_context_destroy(v->frames.context);
    v->frames.renderer = NULL;
    v->frames.context = NULL;
    if (v->window)
        glfwDestroyWindow(v->window);
    v->window = NULL;
    glfwTerminate();
}
