/* OSMesa backend: a compatibility-profile 2.1 context rendering into a tiny private colour buffer. */
#include <stdio.h>
#include <string.h>

#include <GL/osmesa.h>

#include "headless.h"
#include "internal.h"

typedef struct osmesa_state {
    OSMesaContext context;
    /* OSMesa only makes a context current together with a colour buffer; MACS renders into FBOs,
     * so one pixel is enough. */
    unsigned char pixel[4];
} osmesa_state;

static macs_status make_current(osmesa_state *s)
{
    return OSMesaMakeCurrent(s->context, s->pixel, GL_UNSIGNED_BYTE, 1, 1) ? MACS_OK : MACS_ERR_CONTEXT;
}

macs_status macsi_osmesa_create(macs_headless *h, char *message, size_t size)
{
    osmesa_state *s = macsi_calloc(&h->allocator, 1, sizeof *s);
    if (!s) {
        snprintf(message, size, "out of memory");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    static const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                                  OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 2,
                                  OSMESA_CONTEXT_MINOR_VERSION, 1, 0};
    s->context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!s->context) {
        /* An OSMesa that cannot honour the exact version request may still give a compatibility
         * context of a higher version, which MACS accepts just as well. */
        static const int any_version[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                                          OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
        s->context = OSMesaCreateContextAttribs(any_version, NULL);
    }
    if (!s->context) {
        snprintf(message, size, "OSMesaCreateContextAttribs failed for a compatibility context");
        macsi_free(&h->allocator, s);
        return MACS_ERR_CONTEXT;
    }
    if (make_current(s) != MACS_OK) {
        snprintf(message, size, "OSMesaMakeCurrent failed");
        OSMesaDestroyContext(s->context);
        macsi_free(&h->allocator, s);
        return MACS_ERR_CONTEXT;
    }
    h->impl = s;
    return MACS_OK;
}

void macsi_osmesa_destroy(macs_headless *h)
{
    osmesa_state *s = h->impl;
    if (!s)
        return;
    if (OSMesaGetCurrentContext() == s->context)
        OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(s->context);
    macsi_free(&h->allocator, s);
    h->impl = NULL;
}

macs_status macsi_osmesa_make_current(macs_headless *h)
{
    return make_current(h->impl);
}

macs_gl_proc macsi_osmesa_get_proc_address(const char *name, void *user)
{
    (void)user;
    return (macs_gl_proc)OSMesaGetProcAddress(name);
}
