/* Headless GL contexts: checks the descriptor, tries the backends in the default order (or the one
 * asked for), keeps what the context runs on, and hands out the matching get_proc_address. */
#include <stdio.h>
#include <string.h>

#include "headless.h"
#include "internal.h"

/* The default order, each backend with its name in messages: a hardware device first where EGL
 * offers one, as a user with a GPU expects; software (OSMesa) last. An explicit backend is its row. */
static const struct {
    macs_headless_backend backend;
    const char *name;
} backend_order[] = {
    {MACS_HEADLESS_EGL_DEVICE, "EGL device"},
    {MACS_HEADLESS_EGL, "EGL surfaceless"},
    {MACS_HEADLESS_OSMESA, "OSMesa"},
};
enum { BACKEND_ORDER_COUNT = sizeof backend_order / sizeof backend_order[0] };

static const char *backend_name(macs_headless_backend backend)
{
    for (int i = 0; i < BACKEND_ORDER_COUNT; i++)
        if (backend_order[i].backend == backend)
            return backend_order[i].name;
    return "default";
}

static bool uses_egl(macs_headless_backend backend)
{
    return backend == MACS_HEADLESS_EGL || backend == MACS_HEADLESS_EGL_DEVICE;
}

/* Refuses a descriptor before anything is allocated, one fault at a time, naming the argument. */
static bool check_desc(const macs_headless_desc *d, macs_headless **out, char *text, size_t size)
{
    if (!out)
        snprintf(text, size, "macs_headless_create: out is NULL");
    else if ((unsigned)d->backend > MACS_HEADLESS_EGL_DEVICE)
        snprintf(text, size, "macs_headless_create: desc.backend %d is not a macs_headless_backend (0 .. %d)",
                 (int)d->backend, (int)MACS_HEADLESS_EGL_DEVICE);
    else if (!macsi_allocator_valid(&d->allocator))
        snprintf(text, size, "macs_headless_create: desc.allocator: set alloc, realloc and free together or leave "
                 "all NULL");
    else if (d->device_index < 0)
        snprintf(text, size, "macs_headless_create: desc.device_index %d is negative (0 is the first device)",
                 d->device_index);
    else if (d->device_index > 0 && (d->backend == MACS_HEADLESS_OSMESA || d->backend == MACS_HEADLESS_EGL))
        snprintf(text, size, "macs_headless_create: desc.device_index %d picks an EGL device, but desc.backend %s "
                 "has no devices", d->device_index, backend_name(d->backend));
    else
        return true;
    return false;
}

static macs_status try_backend(macs_headless *h, macs_headless_backend backend, const macs_headless_desc *d,
                               char *why, size_t size)
{
    h->backend = backend;
    switch (backend) {
    case MACS_HEADLESS_OSMESA:
        return macsi_osmesa_create(h, why, size);
    case MACS_HEADLESS_EGL:
        return macsi_egl_surfaceless_create(h, why, size);
    default: {
        /* Index 0 under DEFAULT is no choice of device: the first one that works will do. */
        bool any_device = d->backend == MACS_HEADLESS_DEFAULT && d->device_index == 0;
        return macsi_egl_device_create(h, any_device ? -1 : d->device_index, why, size);
    }
    }
}

/* Tries the backends the descriptor allows, in order, until one gives a context; reasons gets
 * "<backend>: <why>" for each that did not. Only MACS_ERR_CONTEXT moves on to the next backend. */
static macs_status create_first_that_works(macs_headless *h, const macs_headless_desc *d, char *reasons,
                                           size_t size)
{
    macs_status st = MACS_ERR_CONTEXT;
    reasons[0] = '\0';
    for (int i = 0; i < BACKEND_ORDER_COUNT && st == MACS_ERR_CONTEXT; i++) {
        if (d->backend != MACS_HEADLESS_DEFAULT && d->backend != backend_order[i].backend)
            continue;
        char why[MACS_MESSAGE_SIZE] = "";
        st = try_backend(h, backend_order[i].backend, d, why, sizeof why);
        size_t used = strlen(reasons);
        if (st != MACS_OK && used + 1 < size)
            snprintf(reasons + used, size - used, "%s%s: %s", used ? "; " : "", backend_order[i].name, why);
    }
    return st;
}

/* GL_RENDERER of the context just made current, read through the backend's own loader. */
static macs_status copy_renderer(macs_headless *h)
{
    typedef const GLubyte *(GLAPIENTRY * get_string_fn)(GLenum name);
    get_string_fn get_string = (get_string_fn)macs_headless_get_proc_address(h)("glGetString", h->impl);
    const GLubyte *renderer = get_string ? get_string(GL_RENDERER) : NULL;
    h->renderer = macsi_strdup(&h->allocator, renderer ? (const char *)renderer : "");
    return h->renderer ? MACS_OK : MACS_ERR_OUT_OF_MEMORY;
}

/* Frees the headless context's memory; the backend's context must already be gone. */
static void free_headless(macs_headless *h)
{
    macs_allocator a = h->allocator;
    macsi_free(&a, h->device_name);
    macsi_free(&a, h->device_extensions);
    macsi_free(&a, h->renderer);
    macsi_free(&a, h);
}

static void destroy_backend(macs_headless *h)
{
    if (uses_egl(h->backend))
        macsi_egl_destroy(h);
    else
        macsi_osmesa_destroy(h);
}

/* One info line: what the context runs on, and why the backends before it were passed over. */
static void log_created(const macs_headless_desc *d, const macs_headless *h, const char *reasons)
{
    if (!d->logger.func)
        return;
    char line[MACS_MESSAGE_SIZE], device[256] = "";
    if (h->backend == MACS_HEADLESS_EGL_DEVICE)
        snprintf(device, sizeof device, " %d of %d%s%s%s", h->device_index, h->device_count,
                 h->device_name[0] ? " (" : "", h->device_name, h->device_name[0] ? ")" : "");
    snprintf(line, sizeof line, "headless context on %s%s, GL_RENDERER \"%s\"%s%s", backend_name(h->backend), device,
             h->renderer, reasons[0] ? "; passed over: " : "", reasons);
    d->logger.func(MACS_LOG_INFO, line, d->logger.user);
}

macs_status macs_headless_create(const macs_headless_desc *desc, macs_headless **out, char *message,
                                 size_t message_size)
{
    static const macs_headless_desc defaults = {0};
    char text[MACS_MESSAGE_SIZE];
    if (message && message_size > 0)
        message[0] = '\0';
    if (out)
        *out = NULL;
    if (!desc)
        desc = &defaults;
    if (!check_desc(desc, out, text, sizeof text)) {
        macsi_report(desc->logger, message, message_size, MACS_ERR_INVALID_ARGUMENT, "%s", text);
        return MACS_ERR_INVALID_ARGUMENT;
    }
    macs_headless *h = macsi_calloc(&desc->allocator, 1, sizeof *h);
    if (!h) {
        macsi_report(desc->logger, message, message_size, MACS_ERR_OUT_OF_MEMORY,
                    "macs_headless_create: allocating a headless context");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    h->allocator = desc->allocator;
    h->device_index = -1;
    macs_status st = create_first_that_works(h, desc, text, sizeof text);
    if (st == MACS_OK) {
        st = copy_renderer(h);
        if (st != MACS_OK) {
            destroy_backend(h);
            snprintf(text, sizeof text, "copying GL_RENDERER");
        }
    }
    if (st != MACS_OK) {
        macsi_report(desc->logger, message, message_size, st, "macs_headless_create: %s", text);
        free_headless(h);
        return st;
    }
    log_created(desc, h, text);
    *out = h;
    return MACS_OK;
}

void macs_headless_destroy(macs_headless *h)
{
    if (!h)
        return;
    destroy_backend(h);
    free_headless(h);
}

macs_status macs_headless_make_current(macs_headless *h)
{
    if (!h)
        return MACS_ERR_INVALID_ARGUMENT;
    return uses_egl(h->backend) ? macsi_egl_make_current(h) : macsi_osmesa_make_current(h);
}

macs_headless_backend macs_headless_backend_used(const macs_headless *h)
{
    return h ? h->backend : MACS_HEADLESS_DEFAULT;
}

void macs_headless_get_info(const macs_headless *h, macs_headless_info *info)
{
    if (!info)
        return;
    info->backend = h ? h->backend : MACS_HEADLESS_DEFAULT;
    info->device_index = h ? h->device_index : -1;
    info->device_count = h ? h->device_count : 0;
    info->device_name = h && h->device_name ? h->device_name : "";
    info->device_extensions = h && h->device_extensions ? h->device_extensions : "";
    info->renderer = h && h->renderer ? h->renderer : "";
}

macs_get_proc_address_fn macs_headless_get_proc_address(const macs_headless *h)
{
    if (!h)
        return NULL;
    return uses_egl(h->backend) ? macsi_egl_get_proc_address : macsi_osmesa_get_proc_address;
}

void *macs_headless_proc_user(const macs_headless *h)
{
    return h ? h->impl : NULL;
}
