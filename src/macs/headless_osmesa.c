/* OSMesa backend: a compatibility-profile 2.1 context rendering into a tiny private colour buffer.
 * libOSMesa is loaded at run time (library.h) and its few declarations are written here, since Mesa
 * 25.1 and later ship neither the library nor <GL/osmesa.h>. */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "headless.h"
#include "internal.h"
#include "library.h"

/* The values of OSMesa's attribute names, as its header defines them. */
enum {
    OSMESA_FORMAT = 0x22,
    OSMESA_DEPTH_BITS = 0x30,
    OSMESA_STENCIL_BITS = 0x31,
    OSMESA_PROFILE = 0x33,
    OSMESA_COMPAT_PROFILE = 0x35,
    OSMESA_CONTEXT_MAJOR_VERSION = 0x36,
    OSMESA_CONTEXT_MINOR_VERSION = 0x37,
    OSMESA_RGBA = GL_RGBA
};
typedef struct osmesa_context *OSMesaContext;

/* Every OSMesa function the backend calls: X(return type, name without "OSMesa", parameters). */
#define MACS_OSMESA_FUNCTIONS(X) \
    X(OSMesaContext, CreateContextAttribs, (const int *attribs, OSMesaContext share)) \
    X(void, DestroyContext, (OSMesaContext context)) \
    X(GLboolean, MakeCurrent, (OSMesaContext context, void *buffer, GLenum type, GLsizei width, GLsizei height)) \
    X(OSMesaContext, GetCurrentContext, (void)) \
    X(macs_gl_proc, GetProcAddress, (const char *name))

typedef struct osmesa_api {
#define MACS_OSMESA_MEMBER_(ret, name, params) ret (GLAPIENTRY *name) params;
    MACS_OSMESA_FUNCTIONS(MACS_OSMESA_MEMBER_)
#undef MACS_OSMESA_MEMBER_
} osmesa_api;

static const macsi_library_symbol osmesa_symbols[] = {
#define MACS_OSMESA_SYMBOL_(ret, name, params) {"OSMesa" #name, offsetof(osmesa_api, name)},
    MACS_OSMESA_FUNCTIONS(MACS_OSMESA_SYMBOL_)
#undef MACS_OSMESA_SYMBOL_
};

/* Mesa's soname since 2011, then the one Debian also keeps as a link for older programs. */
static const char *const osmesa_sonames[] = {"libOSMesa.so.8", "libOSMesa.so.6", NULL};

typedef struct osmesa_state {
    macsi_library library;
    osmesa_api api;
    OSMesaContext context;
    /* OSMesa only makes a context current together with a colour buffer; MACS renders into FBOs,
     * so one pixel is enough. */
    unsigned char pixel[4];
} osmesa_state;

static macs_status make_current(osmesa_state *s)
{
    return s->api.MakeCurrent(s->context, s->pixel, GL_UNSIGNED_BYTE, 1, 1) ? MACS_OK : MACS_ERR_CONTEXT;
}

static OSMesaContext create_context(const osmesa_api *api)
{
    static const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                                  OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 2,
                                  OSMESA_CONTEXT_MINOR_VERSION, 1, 0};
    OSMesaContext context = api->CreateContextAttribs(attribs, NULL);
    if (context)
        return context;
    /* An OSMesa that cannot honour the exact version request may still give a compatibility
     * context of a higher version, which MACS accepts just as well. */
    static const int any_version[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                                      OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
    return api->CreateContextAttribs(any_version, NULL);
}

static void free_state(macs_headless *h, osmesa_state *s)
{
    macsi_library_close(&s->library);
    macsi_free(&h->allocator, s);
}

macs_status macsi_osmesa_create(macs_headless *h, char *message, size_t size)
{
    osmesa_state *s = macsi_calloc(&h->allocator, 1, sizeof *s);
    if (!s) {
        snprintf(message, size, "out of memory");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    if (!macsi_library_open(&s->library, osmesa_sonames, message, size)) {
        free_state(h, s);
        return MACS_ERR_CONTEXT;
    }
    if (!macsi_library_find_all(&s->library, osmesa_symbols, sizeof osmesa_symbols / sizeof osmesa_symbols[0],
                                &s->api, message, size)) {
        free_state(h, s);
        return MACS_ERR_CONTEXT;
    }
    s->context = create_context(&s->api);
    if (!s->context) {
        snprintf(message, size, "OSMesaCreateContextAttribs failed for a compatibility context");
        free_state(h, s);
        return MACS_ERR_CONTEXT;
    }
    if (make_current(s) != MACS_OK) {
        snprintf(message, size, "OSMesaMakeCurrent failed");
        s->api.DestroyContext(s->context);
        free_state(h, s);
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
    if (s->api.GetCurrentContext() == s->context)
        s->api.MakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    s->api.DestroyContext(s->context);
    free_state(h, s);
    h->impl = NULL;
}

macs_status macsi_osmesa_make_current(macs_headless *h)
{
    return make_current(h->impl);
}

macs_gl_proc macsi_osmesa_get_proc_address(const char *name, void *user)
{
    /* The state is the user pointer (macs_headless_proc_user); without it there is no library to ask. */
    const osmesa_state *s = user;
    return s ? s->api.GetProcAddress(name) : NULL;
}
