/* EGL contexts: a desktop GL context made current without a surface on a display of any platform
 * (the surfaceless and device backends each find their display, then come here). */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "headless_egl.h"
#include "internal.h"

/* glvnd's and Mesa's soname; the unversioned name is only a development link. */
static const char *const egl_sonames[] = {"libEGL.so.1", NULL};

static const macsi_library_symbol egl_symbols[] = {
#define MACS_EGL_SYMBOL_(ret, name, params) {"egl" #name, offsetof(macsi_egl_api, name)},
    MACS_EGL_FUNCTIONS(MACS_EGL_SYMBOL_)
#undef MACS_EGL_SYMBOL_
};

typedef struct egl_state {
    macsi_egl_api api;
    EGLDisplay display;
    EGLContext context;
} egl_state;

macs_status macsi_egl_api_load(macsi_egl_api *api, char *message, size_t size)
{
    memset(api, 0, sizeof *api);
    if (!macsi_library_open(&api->library, egl_sonames, message, size))
        return MACS_ERR_CONTEXT;
    if (!macsi_library_find_all(&api->library, egl_symbols, sizeof egl_symbols / sizeof egl_symbols[0], api, message,
                                size)) {
        macsi_egl_api_unload(api);
        return MACS_ERR_CONTEXT;
    }
    return MACS_OK;
}

void macsi_egl_api_unload(macsi_egl_api *api)
{
    macsi_library_close(&api->library);
}

bool macsi_egl_client_has(const macsi_egl_api *api, const char *extension)
{
    /* NULL where EGL lacks EGL_EXT_client_extensions: then no extension is there. */
    return macsi_gl_has_extension(api->QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), extension);
}

macs_status macsi_egl_platform_display(const macsi_egl_api *api, EGLenum platform, void *native, EGLDisplay *out,
                                       char *message, size_t size)
{
    if (!macsi_egl_client_has(api, "EGL_EXT_platform_base")) {
        snprintf(message, size, "EGL_EXT_platform_base is missing from the client extensions");
        return MACS_ERR_CONTEXT;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)api->GetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) {
        snprintf(message, size, "eglGetPlatformDisplayEXT not found");
        return MACS_ERR_CONTEXT;
    }
    EGLDisplay display = get_display(platform, native, NULL);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !api->Initialize(display, &major, &minor)) {
        snprintf(message, size, "no EGL display (error 0x%04x)", (unsigned)api->GetError());
        return MACS_ERR_CONTEXT;
    }
    *out = display;
    return MACS_OK;
}

/* A config only where the driver needs one: no surface will ever exist, so any config that renders
 * desktop GL will do, whatever surfaces it could have had (the default asks for windows, which no
 * headless platform has). */
static macs_status choose_config(const macsi_egl_api *api, EGLDisplay display, const char *display_ext,
                                 EGLConfig *config, char *message, size_t size)
{
    static const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE,
                                            EGL_NONE};
    *config = EGL_NO_CONFIG_KHR;
    if (macsi_gl_has_extension(display_ext, "EGL_KHR_no_config_context"))
        return MACS_OK;
    EGLint count = 0;
    if (!api->ChooseConfig(display, config_attribs, config, 1, &count) || count < 1) {
        snprintf(message, size, "no EGL config renders desktop OpenGL");
        return MACS_ERR_CONTEXT;
    }
    return MACS_OK;
}

static void free_state(macs_headless *h, egl_state *s)
{
    macsi_egl_api_unload(&s->api);
    macsi_free(&h->allocator, s);
}

macs_status macsi_egl_create_on(macs_headless *h, const macsi_egl_api *api, EGLDisplay display, char *message,
                                size_t size)
{
    const char *display_ext = api->QueryString(display, EGL_EXTENSIONS);
    if (!macsi_gl_has_extension(display_ext, "EGL_KHR_surfaceless_context")) {
        snprintf(message, size, "EGL_KHR_surfaceless_context is missing from the display's extensions");
        return MACS_ERR_CONTEXT;
    }
    if (!api->BindAPI(EGL_OPENGL_API)) {
        snprintf(message, size, "eglBindAPI(EGL_OPENGL_API) failed: no desktop OpenGL");
        return MACS_ERR_CONTEXT;
    }
    EGLConfig config;
    macs_status st = choose_config(api, display, display_ext, &config, message, size);
    if (st != MACS_OK)
        return st;
    egl_state *s = macsi_calloc(&h->allocator, 1, sizeof *s);
    if (!s) {
        snprintf(message, size, "out of memory");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    /* The context's own reference to libEGL, so that it outlives the caller's. */
    st = macsi_egl_api_load(&s->api, message, size);
    if (st != MACS_OK) {
        macsi_free(&h->allocator, s);
        return st;
    }
    s->display = display;
    /* No version attributes: a legacy (compatibility) context of the highest version, which covers 2.1. */
    s->context = api->CreateContext(display, config, EGL_NO_CONTEXT, NULL);
    if (s->context == EGL_NO_CONTEXT) {
        snprintf(message, size, "eglCreateContext failed (error 0x%04x)", (unsigned)api->GetError());
        free_state(h, s);
        return MACS_ERR_CONTEXT;
    }
    if (!api->MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, s->context)) {
        snprintf(message, size, "eglMakeCurrent without a surface failed (error 0x%04x)", (unsigned)api->GetError());
        api->DestroyContext(display, s->context);
        free_state(h, s);
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
    bool was_current = s->api.GetCurrentContext() == s->context;
    if (was_current)
        s->api.MakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    s->api.DestroyContext(s->display, s->context);
    if (was_current)
        s->api.ReleaseThread();
    free_state(h, s);
    h->impl = NULL;
}

macs_status macsi_egl_make_current(macs_headless *h)
{
    egl_state *s = h->impl;
    if (!s->api.BindAPI(EGL_OPENGL_API) || !s->api.MakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, s->context))
        return MACS_ERR_CONTEXT;
    return MACS_OK;
}

macs_gl_proc macsi_egl_get_proc_address(const char *name, void *user)
{
    /* The state is the user pointer (macs_headless_proc_user); without it there is no library to ask. */
    const egl_state *s = user;
    return s ? (macs_gl_proc)s->api.GetProcAddress(name) : NULL;
}
