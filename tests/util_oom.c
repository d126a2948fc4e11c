/* Test helper: GL_OUT_OF_MEMORY on demand through a wrapped GL loader (util_oom.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "util_oom.h"

typedef void (*tex_image_fn)(unsigned, int, int, int, int, int, unsigned, unsigned, const void *);
typedef void (*storage_fn)(unsigned, unsigned, int, int);
typedef unsigned (*get_error_fn)(void);

static struct {
    macs_get_proc_address_fn real;
    void *real_user;
    tex_image_fn tex_image;
    storage_fn storage, storage_ext;
    get_error_fn get_error;
    int remaining; /* allocations still to fail; < 0 every one */
    int pending;   /* a failure the next glGetError reports */
    int injected;
} oom;

static void note_allocation(void)
{
    if (oom.remaining == 0)
        return;
    if (oom.remaining > 0)
        oom.remaining--;
    oom.pending = 1;
    oom.injected++;
}

static void fake_tex_image(unsigned target, int level, int ifmt, int w, int h, int border, unsigned fmt,
                           unsigned type, const void *data)
{
    oom.tex_image(target, level, ifmt, w, h, border, fmt, type, data);
    note_allocation();
}

static void fake_storage(unsigned target, unsigned ifmt, int w, int h)
{
    oom.storage(target, ifmt, w, h);
    note_allocation();
}

static void fake_storage_ext(unsigned target, unsigned ifmt, int w, int h)
{
    oom.storage_ext(target, ifmt, w, h);
    note_allocation();
}

static unsigned fake_get_error(void)
{
    if (oom.pending) {
        oom.pending = 0;
        return 0x0505; /* GL_OUT_OF_MEMORY */
    }
    return oom.get_error();
}

/* The real entry point is kept in its own type and the fake handed out in the loader's: both are
 * casts between function pointer types, which C99 defines. */
static macs_gl_proc oom_loader(const char *name, void *user)
{
    (void)user;
    macs_gl_proc p = oom.real(name, oom.real_user);
    if (!p)
        return p;
    if (strcmp(name, "glTexImage2D") == 0) {
        oom.tex_image = (tex_image_fn)p;
        return (macs_gl_proc)fake_tex_image;
    }
    if (strcmp(name, "glRenderbufferStorage") == 0) {
        oom.storage = (storage_fn)p;
        return (macs_gl_proc)fake_storage;
    }
    if (strcmp(name, "glRenderbufferStorageEXT") == 0) {
        oom.storage_ext = (storage_fn)p;
        return (macs_gl_proc)fake_storage_ext;
    }
    if (strcmp(name, "glGetError") == 0) {
        oom.get_error = (get_error_fn)p;
        return (macs_gl_proc)fake_get_error;
    }
    return p;
}

macs_context *util_oom_context(macs_headless *headless)
{
    memset(&oom, 0, sizeof oom);
    oom.real = macs_headless_get_proc_address(headless);
    oom.real_user = macs_headless_proc_user(headless);
    macs_context_desc cd = {0};
    cd.get_proc_address = oom_loader;
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    return ctx;
}

void util_oom_start(int count)
{
    oom.remaining = count;
    oom.pending = 0;
    oom.injected = 0;
}

void util_oom_stop(void)
{
    oom.remaining = 0;
    oom.pending = 0;
}

int util_oom_injected(void)
{
    return oom.injected;
}
