/* Private interface between the headless front end and its OSMesa and EGL backends. */
#ifndef MACS_HEADLESS_H
#define MACS_HEADLESS_H

#include "macs.h"

struct macs_headless {
    macs_headless_backend backend;
    macs_allocator allocator;
    void *impl; /* the backend's own state */
    /* What macs_headless_get_info reports; NULL strings read as "". */
    int device_index; /* EGL_DEVICE: the device used; else -1 */
    int device_count; /* EGL_DEVICE: how many devices EGL listed; else 0 */
    char *device_name;
    char *device_extensions;
    char *renderer;
};

/* Each backend fills impl and makes its context current, or writes why not into message: status
 * MACS_ERR_CONTEXT where the next backend of the default order may still succeed, any other status
 * where it should not be tried (out of memory, a device index that does not exist). */
macs_status macsi_osmesa_create(macs_headless *h, char *message, size_t size);
void macsi_osmesa_destroy(macs_headless *h);
macs_status macsi_osmesa_make_current(macs_headless *h);
macs_gl_proc macsi_osmesa_get_proc_address(const char *name, void *user);

/* The EGL backends share one context type, so destroy, make current and get_proc_address are one. */
macs_status macsi_egl_surfaceless_create(macs_headless *h, char *message, size_t size);
/* index < 0: every device in the order EGL lists them, the first that gives a context; else that
 * device only. Fills the device fields of h. */
macs_status macsi_egl_device_create(macs_headless *h, int index, char *message, size_t size);
void macsi_egl_destroy(macs_headless *h);
macs_status macsi_egl_make_current(macs_headless *h);
macs_gl_proc macsi_egl_get_proc_address(const char *name, void *user);

#endif
