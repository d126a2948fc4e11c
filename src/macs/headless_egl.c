/* EGL contexts: a desktop GL context made current without a surface on a display of any platform
 * (the surfaceless and device backends each find their display, then come here). */
#include <stdio.h>
#include <string.h>

#include "headless_egl.h"
#include "internal.h"

typedef struct egl_state {
    EGLDisplay display;
    EGLContext context;
} egl_state;

bool macsi_egl_client_has(const char *extension)
{
    /* NULL where EGL lacks EGL_EXT_client_extensions: then no extension is there. */
    return macsi_gl_has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), extension);
}

__eglMustCastToProperFunctionPointerType macsi_egl_proc(const char *name)
{
    return eglGetProcAddress(name);
}

macs_status macsi_egl_platform_display(EGLenum platform, void *native, EGLDisplay *out, char *message, size_t size)
{
    if (!macsi_egl_client_has("EGL_EXT_platform_base")) {
        snprintf(message, size, "EGL_EXT_platform_base is missing from the client extensions");
        return MACS_ERR_CONTEXT;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)macsi_egl_proc("eglGetPlatformDisplayEXT");
    if (!get_display) {
        snprintf(message, size, "eglGetPlatformDisplayEXT not found");
        return MACS_ERR_CONTEXT;
    }
    EGLDisplay display = get_display(platform, native, NULL);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
        snprintf(message, size, "no EGL display (error 0x%04x)", (unsigned)eglGetError());
        return MACS_ERR_CONTEXT;
    }
    *out = display;
    return MACS_OK;
}

/* A config only where the driver needs one: no surface will ever exist, so any config that renders
 * desktop GL will do, whatever surfaces it could have had (the default asks for windows, which no
 * headless platform has). */
static macs_status choose_config(EGLDisplay display, const char *display_ext, EGLConfig *config, char *message,
                                 size_t size)
{
    static const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE,
                                            EGL_NONE};
    *config = EGL_NO_CONFIG_KHR;
    if (macsi_gl_has_extension(display_ext, "EGL_KHR_no_config_context"))
        return MACS_OK;
    EGLint count = 0;
    if (!eglChooseConfig(display, config_attribs, config, 1, &count) || count < 1) {
        snprintf(message, size, "no EGL config renders desktop OpenGL");
        return MACS_ERR_CONTEXT;
    }
    return MACS_OK;
}

macs_status macsi_egl_create_on(macs_headless *h, EGLDisplay display, char *message, size_t size)
{
    const char *display_ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!macsi_gl_has_extension(display_ext, "EGL_KHR_surfaceless_context")) {
        snprintf(message, size, "EGL_KHR_surfaceless_context is missing from the display's extensions");
        return MACS_ERR_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(message, size, "eglBindAPI(EGL_OPENGL_API) failed: no desktop OpenGL");
        return MACS_ERR_CONTEXT;
    }
    EGLConfig config;
    macs_status st = choose_config(display, display_ext, &config, message, size);
    if (st != MACS_OK)
        return st;
    egl_state *s = macsi_calloc(&h->allocator, 1, sizeof *s);
    if (!s) {
        snprintf(message, size, "out of memory");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    s->display = display;
    /* No version attributes: a legacy (compatibility) context of the highest version, which covers 2.1. */
    s->context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
    if (s->context == EGL_NO_CONTEXT) {
        snprintf(message, size, "eglCreateContext failed (error 0x%04x)", (unsigned)eglGetError());
        macsi_free(&h->allocator, s);
        return MACS_ERR_CONTEXT;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, s->context)) {
        snprintf(message, size, "eglMakeCurrent without a surface failed (error 0x%04x)", (unsigned)eglGetError());
        eglDestroyContext(display, s->context);
        macsi_free(&h->allocator, s);
        return MACS_ERR_CONTEXT;
    }
    h->impl = s;
    return MACS_OK;
}

void macsi_egl_destroy(macs_headless *h)
{
    egl_state *s = h->impl;
    if (!s)
        return;
    /* Only our own context is unbound: another headless context current on this thread stays so. */
    bool was_current = eglGetCurrentContext() == s->context;
    if (was_current)
        eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(s->display, s->context);
    if (was_current)
        eglReleaseThread();
    macsi_free(&h->allocator, s);
    h->impl = NULL;
}

macs_status macsi_egl_make_current(macs_headless *h)
{
    egl_state *s = h->impl;
    if (!eglBindAPI(EGL_OPENGL_API) || !eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, s->context))
        return MACS_ERR_CONTEXT;
    return MACS_OK;
}

macs_gl_proc macsi_egl_get_proc_address(const char *name, void *user)
{
    (void)user;
    return (macs_gl_proc)eglGetProcAddress(name);
}
