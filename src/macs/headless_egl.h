/* Private interface shared by the EGL backends: each platform (surfaceless, device) finds an
 * initialised display its own way, and one code path makes a desktop GL context on it. */
#ifndef MACS_HEADLESS_EGL_H
#define MACS_HEADLESS_EGL_H

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "headless.h"

/* Whether EGL's client extension string (the one of EGL_NO_DISPLAY) names extension. */
bool macsi_egl_client_has(const char *extension);

/* An EGL entry point by name through eglGetProcAddress, as a generic function pointer that the
 * caller casts to its own type (NULL if absent); extension functions may not be linked directly. */
__eglMustCastToProperFunctionPointerType macsi_egl_proc(const char *name);

/* eglGetPlatformDisplayEXT(platform, native) and eglInitialize, or why not into message. The display
 * is shared by every user of the platform and native handle in the process, so it is never
 * terminated: destroying one headless context must not pull it from under another. */
macs_status macsi_egl_platform_display(EGLenum platform, void *native, EGLDisplay *out, char *message, size_t size);

/* Creates a desktop GL context on an initialised display and makes it current without a surface;
 * fills h->impl, or writes why not into message. */
macs_status macsi_egl_create_on(macs_headless *h, EGLDisplay display, char *message, size_t size);

#endif
