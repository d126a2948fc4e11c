/* The frame shown by a framebuffer blit (view_display.h): the texture is attached to a read
 * framebuffer and glBlitFramebuffer scales it into the window's. ARB_framebuffer_object, which MACS
 * requires anyway, gives the blit; it needs no quad, no shader, no vertex or matrix state, and MACS
 * leaves none of that for us to set back. Its one piece of MACS's state that touches a blit is the
 * scissor test, which is switched off first.
 *
 * The functions come from glfwGetProcAddress, as MACS's do, so that the command links no GL library
 * (tests/check_symbols.sh): GLFW itself loads GL at run time. */
#include "view_display.h"

#include <stdio.h>
#include <stdlib.h>

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GL/glext.h>
#include <GLFW/glfw3.h>

/* GL 1.1's own functions have no PFN types in <GL/glext.h>. */
typedef void(APIENTRYP view_gl_disable)(GLenum cap);
typedef void(APIENTRYP view_gl_clear_color)(GLclampf r, GLclampf g, GLclampf b, GLclampf a);
typedef void(APIENTRYP view_gl_clear)(GLbitfield mask);
typedef void(APIENTRYP view_gl_finish)(void);

/* One list, the table and the loader (STYLE.md 1). */
#define VIEW_GL_FUNCTIONS(X)                                                                   \
    X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                                             \
    X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                                       \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                             \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                                   \
    X(PFNGLBLITFRAMEBUFFERPROC, glBlitFramebuffer)                                             \
    X(view_gl_disable, glDisable)                                                             \
    X(view_gl_clear_color, glClearColor)                          \
    X(view_gl_clear, glClear)                                                                  \
    X(view_gl_finish, glFinish)

struct view_display {
#define FIELD(type, name) type name;
    VIEW_GL_FUNCTIONS(FIELD)
#undef FIELD
    GLuint framebuffer;
};

bool view_display_create(view_display **out, char *why, size_t size)
{
    *out = NULL;
    view_display *d = calloc(1, sizeof *d);
    if (!d) {
        snprintf(why, size, "out of memory");
        return false;
    }
#define LOAD(type, name)                                                                       \
    d->name = (type)glfwGetProcAddress(#name);                                                 \
    if (!d->name) {                                                                            \
        snprintf(why, size, "the window's GL has no %s", #name);                              \
        free(d);                                                                               \
        return false;                                                                          \
    }
    VIEW_GL_FUNCTIONS(LOAD)
#undef LOAD
    d->glGenFramebuffers(1, &d->framebuffer);
    *out = d;
    return true;
}

void view_display_show(view_display *d, void *window, const macs_texture *texture, int width, int height)
{
    d->glDisable(GL_SCISSOR_TEST);
    d->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    d->glClearColor(0, 0, 0, 1);
    d->glClear(GL_COLOR_BUFFER_BIT);
    if (texture) {
        int w = 0, h = 0;
        macs_texture_size(texture, &w, &h);
        d->glBindFramebuffer(GL_READ_FRAMEBUFFER, d->framebuffer);
        d->glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                  macs_texture_gl_name(texture), 0);
        /* Both have row 0 at the bottom: the frame shows upright as it is. */
        d->glBlitFramebuffer(0, 0, w, h, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        d->glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        d->glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glfwSwapBuffers(window);
    /* The renderer only queues a frame's passes: waiting for them here makes the frame time the
     * resolution rule measures the GPU's, not the time it took to queue them. */
    d->glFinish();
}

void view_display_destroy(view_display *d)
{
    if (!d)
        return;
    d->glDeleteFramebuffers(1, &d->framebuffer);
    free(d);
}
