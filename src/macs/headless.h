/* Private interface between the headless front end and its OSMesa and EGL backends. */
#ifndef MACS_HEADLESS_H
#define MACS_HEADLESS_H

#include "macs.h"

struct macs_headless {
    macs_headless_backend backend;
    macs_allocator allocator;
    void *impl; /* the backend's own state */
};

/* Each backend fills impl and makes its context current, or writes why not into message. */
macs_status macs_osmesa_create(macs_headless *h, char *message, size_t size);
void macs_osmesa_destroy(macs_headless *h);
macs_status macs_osmesa_make_current(macs_headless *h);
void *macs_osmesa_get_proc_address(const char *name, void *user);

macs_status macs_egl_create(macs_headless *h, char *message, size_t size);
void macs_egl_destroy(macs_headless *h);
macs_status macs_egl_make_current(macs_headless *h);
void *macs_egl_get_proc_address(const char *name, void *user);

#endif
