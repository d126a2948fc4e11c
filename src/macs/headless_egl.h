/* Private interface shared by the EGL backends: each platform (surfaceless, device) finds an
 * initialised display its own way, and one code path makes a desktop GL context on it. libEGL is
 * loaded at run time (library.h); the EGL headers give only types and constants. */
#ifndef MACS_HEADLESS_EGL_H
#define MACS_HEADLESS_EGL_H

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "headless.h"
#include "library.h"

/* Every core EGL function the backends call: X(return type, name without "egl", parameters).
 * Extension functions (eglGetPlatformDisplayEXT, the device queries) come from GetProcAddress. */
#define MACS_EGL_FUNCTIONS(X) \
    X(EGLint, GetError, (void)) \
    X(const char *, QueryString, (EGLDisplay display, EGLint name)) \
    X(__eglMustCastToProperFunctionPointerType, GetProcAddress, (const char *name)) \
    X(EGLBoolean, Initialize, (EGLDisplay display, EGLint *major, EGLint *minor)) \
    X(EGLBoolean, ChooseConfig, (EGLDisplay display, const EGLint *attribs, EGLConfig *configs, EGLint size, \
                                 EGLint *count)) \
    X(EGLBoolean, BindAPI, (EGLenum api)) \
    X(EGLContext, CreateContext, (EGLDisplay display, EGLConfig config, EGLContext share, const EGLint *attribs)) \
    X(EGLBoolean, MakeCurrent, (EGLDisplay display, EGLSurface draw, EGLSurface read, EGLContext context)) \
    X(EGLBoolean, DestroyContext, (EGLDisplay display, EGLContext context)) \
    X(EGLContext, GetCurrentContext, (void)) \
    X(EGLBoolean, ReleaseThread, (void))

/* libEGL as loaded, and its functions. */
typedef struct macsi_egl_api {
    macsi_library library;
#define MACS_EGL_MEMBER_(ret, name, params) ret (EGLAPIENTRY *name) params;
    MACS_EGL_FUNCTIONS(MACS_EGL_MEMBER_)
#undef MACS_EGL_MEMBER_
} macsi_egl_api;

/* Loads libEGL and its core functions, or says why not in message (status MACS_ERR_CONTEXT, so that
 * the default order moves on). */
macs_status macsi_egl_api_load(macsi_egl_api *api, char *message, size_t size);

/* Drops the reference of macsi_egl_api_load. */
void macsi_egl_api_unload(macsi_egl_api *api);

/* Whether EGL's client extension string (the one of EGL_NO_DISPLAY) names extension. */
bool macsi_egl_client_has(const macsi_egl_api *api, const char *extension);

/* eglGetPlatformDisplayEXT(platform, native) and eglInitialize, or why not into message. The display
 * is shared by every user of the platform and native handle in the process, so it is never
 * terminated: destroying one headless context must not pull it from under another. */
macs_status macsi_egl_platform_display(const macsi_egl_api *api, EGLenum platform, void *native, EGLDisplay *out,
                                       char *message, size_t size);

/* Creates a desktop GL context on an initialised display and makes it current without a surface;
 * fills h->impl, which holds a reference of its own to libEGL (the caller unloads api as always), or
 * writes why not into message. */
macs_status macsi_egl_create_on(macs_headless *h, const macsi_egl_api *api, EGLDisplay display, char *message,
                                size_t size);

#endif
