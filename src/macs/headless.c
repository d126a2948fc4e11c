/* Headless GL contexts: picks the backend and hands out the matching get_proc_address. */
#include <stdio.h>
#include <string.h>

#include "headless.h"
#include "internal.h"

macs_status macs_headless_create(const macs_headless_desc *desc, macs_headless **out, char *message,
                                 size_t message_size)
{
    static const macs_headless_desc defaults = {0};
    if (message && message_size > 0)
        message[0] = '\0';
    if (out)
        *out = NULL;
    if (!desc)
        desc = &defaults;
    if (!out || (unsigned)desc->backend > MACS_HEADLESS_EGL || !macs_allocator_valid(&desc->allocator)) {
        macs_report(desc->logger, desc->logger_user, message, message_size, MACS_ERR_INVALID_ARGUMENT,
                    "macs_headless_create: out is required; backend and allocator must be valid");
        return MACS_ERR_INVALID_ARGUMENT;
    }
    macs_headless *h = macs_calloc(&desc->allocator, 1, sizeof *h);
    if (!h) {
        macs_report(desc->logger, desc->logger_user, message, message_size, MACS_ERR_OUT_OF_MEMORY,
                    "allocating a headless context");
        return MACS_ERR_OUT_OF_MEMORY;
    }
    h->allocator = desc->allocator;
    char why_osmesa[512] = "", why_egl[512] = "";
    macs_status st = MACS_ERR_CONTEXT;
    if (desc->backend != MACS_HEADLESS_EGL) {
        h->backend = MACS_HEADLESS_OSMESA;
        st = macs_osmesa_create(h, why_osmesa, sizeof why_osmesa);
    }
    if (st != MACS_OK && desc->backend != MACS_HEADLESS_OSMESA) {
        h->backend = MACS_HEADLESS_EGL;
        st = macs_egl_create(h, why_egl, sizeof why_egl);
    }
    if (st != MACS_OK) {
        macs_report(desc->logger, desc->logger_user, message, message_size, st, "%s%s%s%s%s",
                    why_osmesa[0] ? "OSMesa: " : "", why_osmesa, why_osmesa[0] && why_egl[0] ? "; " : "",
                    why_egl[0] ? "EGL: " : "", why_egl);
        macs_free(&desc->allocator, h);
        return st;
    }
    *out = h;
    return MACS_OK;
}

void macs_headless_destroy(macs_headless *h)
{
    if (!h)
        return;
    if (h->backend == MACS_HEADLESS_OSMESA)
        macs_osmesa_destroy(h);
    else
        macs_egl_destroy(h);
    macs_allocator a = h->allocator;
    macs_free(&a, h);
}

macs_status macs_headless_make_current(macs_headless *h)
{
    if (!h)
        return MACS_ERR_INVALID_ARGUMENT;
    return h->backend == MACS_HEADLESS_OSMESA ? macs_osmesa_make_current(h) : macs_egl_make_current(h);
}

macs_headless_backend macs_headless_backend_used(const macs_headless *h)
{
    return h ? h->backend : MACS_HEADLESS_DEFAULT;
}

macs_get_proc_address_fn macs_headless_get_proc_address(const macs_headless *h)
{
    if (!h)
        return NULL;
    return h->backend == MACS_HEADLESS_OSMESA ? macs_osmesa_get_proc_address : macs_egl_get_proc_address;
}

void *macs_headless_proc_user(const macs_headless *h)
{
    return h ? h->impl : NULL;
}
