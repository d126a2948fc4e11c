/* EGL backend: Mesa's surfaceless platform, a desktop GL context made current without a surface. */
#include <stdio.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "headless.h"
#include "internal.h"

typedef struct egl_state {
    EGLDisplay display;
    EGLContext context;
} egl_state;

static bool has_token(const char *list, const char *name)
{
    return macs_gl_has_extension(list, name);
}

macs_status macs_egl_create(macs_headless *h, char *message, size_t size)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_token(client, "EGL_MESA_platform_surfaceless") || !has_token(client, "EGL_EXT_platform_base")) {
        snprintf(message, size, "EGL_MESA_platform_surfaceless or EGL_EXT_platform_base missing");
        return MACS_ERR_CONTEXT;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display = NULL;
    __eglMustCastToProperFunctionPointerType fn = eglGetProcAddress("eglGetPlatformDisplayEXT");
    memcpy(&get_display, &fn, sizeof fn);
    if (!get_display) {
        snprintf(message, size, "eglGetPlatformDisplayEXT not found");
        return MACS_ERR_CONTEXT;
    }
    EGLDisplay display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
        snprintf(message, size, "no surfaceless EGL display (error 0x%04x)", (unsigned)eglGetError());
        return MACS_ERR_CONTEXT;
    }
    /* The display is shared by every user of this platform in the process; it is never terminated
     * here, so that destroying one headless context cannot pull the display from under another. */
    const char *display_ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!has_token(display_ext, "EGL_KHR_surfaceless_context")) {
        snprintf(message, size, "EGL_KHR_surfaceless_context missing");
        return MACS_ERR_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(message, size, "eglBindAPI(EGL_OPENGL_API) failed: no desktop OpenGL");
        return MACS_ERR_CONTEXT;
    }
    /* No surface will ever exist, so no config is needed where the driver allows that; otherwise any
     * config that renders desktop GL, whatever surfaces it could have had (the default asks for windows,
     * which the surfaceless platform has none of). */
    static const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE,
                                            EGL_NONE};
    EGLConfig config = EGL_NO_CONFIG_KHR;
    EGLint count = 1;
    if (!has_token(display_ext, "EGL_KHR_no_config_context") &&
        (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count < 1)) {
        snprintf(message, size, "no EGL config renders desktop OpenGL");
        return MACS_ERR_CONTEXT;
    }
    egl_state *s = macs_calloc(&h->allocator, 1, sizeof *s);
    if (!s) {
        snprintf(message, size, "out of memory");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    s->display = display;
    /* No version attributes: a legacy (compatibility) context of the highest version, which covers 2.1. */
    s->context = eglCreateContext(display, config, EGL_NO_CONTEXT, NULL);
    if (s->context == EGL_NO_CONTEXT) {
        snprintf(message, size, "eglCreateContext failed (error 0x%04x)", (unsigned)eglGetError());
        macs_free(&h->allocator, s);
        return MACS_ERR_CONTEXT;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, s->context)) {
        snprintf(message, size, "eglMakeCurrent without a surface failed (error 0x%04x)", (unsigned)eglGetError());
        eglDestroyContext(display, s->context);
        macs_free(&h->allocator, s);
        return MACS_ERR_CONTEXT;
    }
    h->impl = s;
    return MACS_OK;
}

void macs_egl_destroy(macs_headless *h)
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
    macs_free(&h->allocator, s);
    h->impl = NULL;
}

macs_status macs_egl_make_current(macs_headless *h)
{
    egl_state *s = h->impl;
    if (!eglBindAPI(EGL_OPENGL_API) || !eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, s->context))
        return MACS_ERR_CONTEXT;
    return MACS_OK;
}

void *macs_egl_get_proc_address(const char *name, void *user)
{
    (void)user;
    __eglMustCastToProperFunctionPointerType fn = eglGetProcAddress(name);
    void *p = NULL;
    memcpy(&p, &fn, sizeof p < sizeof fn ? sizeof p : sizeof fn);
    return p;
}
