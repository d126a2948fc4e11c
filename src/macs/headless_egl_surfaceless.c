/* EGL surfaceless backend: Mesa's platform without any window system or device choice; on Mesa it
 * picks the first render node it can open, else its software renderer. */
#include <stdio.h>

#include "headless_egl.h"

static macs_status create_with(macs_headless *h, const macsi_egl_api *api, char *message, size_t size)
{
    if (!macsi_egl_client_has(api, "EGL_MESA_platform_surfaceless")) {
        snprintf(message, size, "EGL_MESA_platform_surfaceless is missing from the client extensions");
        return MACS_ERR_CONTEXT;
    }
    EGLDisplay display;
    macs_status st = macsi_egl_platform_display(api, EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, &display,
                                               message, size);
    if (st != MACS_OK)
        return st;
    return macsi_egl_create_on(h, api, display, message, size);
}

macs_status macsi_egl_surfaceless_create(macs_headless *h, char *message, size_t size)
{
    macsi_egl_api api;
    macs_status st = macsi_egl_api_load(&api, message, size);
    if (st != MACS_OK)
        return st;
    st = create_with(h, &api, message, size);
    macsi_egl_api_unload(&api);
    return st;
}
