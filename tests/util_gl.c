/* Test helpers shared by the MACS suites. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dlfcn.h>
#include <cmocka.h>

#include "util_gl.h"

macs_gl_proc util_library_function(const char *soname, const char *name)
{
    /* Never unloaded: Mesa's LLVM does not survive a second load in one process. */
    void *library = dlopen(soname, RTLD_NOW | RTLD_NODELETE);
    if (!library)
        return NULL;
    void *address = dlsym(library, name);
    dlclose(library);
    macs_gl_proc f = NULL;
    memcpy(&f, &address, sizeof f); /* POSIX's conversion of dlsym's result, as the library does */
    return f;
}

bool util_osmesa_present(void)
{
    static const char *const sonames[] = {"libOSMesa.so.8", "libOSMesa.so.6"};
    for (size_t i = 0; i < sizeof sonames / sizeof sonames[0]; i++) {
        /* Never unloaded: Mesa's LLVM does not survive a second load in one process. */
        if (dlopen(sonames[i], RTLD_NOW | RTLD_NODELETE))
            return true;
    }
    return false;
}

void util_release_current(void)
{
    typedef void *(*get_current_fn)(void);
    typedef unsigned (*egl_make_current_fn)(void *display, void *draw, void *read, void *context);
    typedef unsigned char (*osmesa_make_current_fn)(void *context, void *buffer, unsigned type, int width, int height);
    get_current_fn egl_context = (get_current_fn)util_library_function("libEGL.so.1", "eglGetCurrentContext");
    if (egl_context && egl_context()) {
        get_current_fn egl_display = (get_current_fn)util_library_function("libEGL.so.1", "eglGetCurrentDisplay");
        egl_make_current_fn make_current =
            (egl_make_current_fn)util_library_function("libEGL.so.1", "eglMakeCurrent");
        assert_non_null(egl_display);
        assert_non_null(make_current);
        assert_true(make_current(egl_display(), NULL, NULL, NULL));
        return;
    }
    osmesa_make_current_fn osmesa = (osmesa_make_current_fn)util_library_function("libOSMesa.so.8", "OSMesaMakeCurrent");
    if (!osmesa)
        osmesa = (osmesa_make_current_fn)util_library_function("libOSMesa.so.6", "OSMesaMakeCurrent");
    assert_non_null(osmesa);
    osmesa(NULL, NULL, 0, 0, 0);
}

bool util_quick(void)
{
    const char *q = getenv("MACS_TEST_QUICK");
    return q && *q && strcmp(q, "0") != 0;
}

macs_headless *util_headless(void)
{
    const char *b = getenv("MACS_TEST_BACKEND");
    macs_headless_desc desc = {0};
    /* egl: EGL surfaceless (Mesa); device: the first EGL device, a GPU (NVIDIA's driver has no
     * surfaceless platform); otherwise OSMesa. */
    desc.backend = !b                       ? MACS_HEADLESS_OSMESA
                   : strcmp(b, "egl") == 0    ? MACS_HEADLESS_EGL
                   : strcmp(b, "device") == 0 ? MACS_HEADLESS_EGL_DEVICE
                                              : MACS_HEADLESS_OSMESA;
    macs_headless *h = NULL;
    char message[512];
    macs_status st = macs_headless_create(&desc, &h, message, sizeof message);
    if (st != MACS_OK && desc.backend == MACS_HEADLESS_OSMESA && !util_osmesa_present()) {
        print_message("skipped: OSMesa is not installed (%s)\n", message);
        skip();
    }
    if (st != MACS_OK)
        fail_msg("headless context (%s): %s", b ? b : "osmesa", message);
    assert_int_equal(macs_headless_backend_used(h), desc.backend);
    return h;
}

const char *util_profile(void)
{
    const char *p = getenv("MACS_TEST_PROFILE");
    return p && *p ? p : NULL;
}

/* Whether the last context made lacks float32 blending; tests run single-threaded. */
static bool half_accumulation;

bool util_half_accumulation(void)
{
    return half_accumulation;
}

/* A driver whose glMapBuffer returns NULL: the loader of util_context_null_map hands MACS this
 * stand-in and the headless context's own function for every other name. */
static struct {
    macs_get_proc_address_fn real;
    void *real_user;
} null_map_loader_state;

static void *null_map_buffer(unsigned target, unsigned access)
{
    (void)target;
    (void)access;
    return NULL;
}

static macs_gl_proc null_map_loader(const char *name, void *user)
{
    (void)user;
    if (strcmp(name, "glMapBuffer") == 0)
        return (macs_gl_proc)null_map_buffer;
    return null_map_loader_state.real(name, null_map_loader_state.real_user);
}

/* util_context's body, with extensions hidden and glMapBuffer's stand-in on request. */
static macs_context *context_made(macs_headless *headless, const macs_limits *caps, const char *hidden,
                                  bool null_map)
{
    macs_context_desc desc = {0};
    desc.get_proc_address = macs_headless_get_proc_address(headless);
    desc.get_proc_address_user = macs_headless_proc_user(headless);
    if (null_map) {
        null_map_loader_state.real = desc.get_proc_address;
        null_map_loader_state.real_user = desc.get_proc_address_user;
        desc.get_proc_address = null_map_loader;
        desc.get_proc_address_user = NULL;
    }
    if (caps)
        desc.caps = *caps;
    desc.hidden_extensions = hidden;
    /* MACS combines the profile with the test's caps, the smaller limit winning. */
    desc.profile = util_profile();
    macs_context *ctx = NULL;
    char message[1024];
    macs_status st = macs_context_create(&desc, &ctx, message, sizeof message);
    if (st != MACS_OK)
        fail_msg("macs_context_create%s%s: %s", desc.profile ? " under MACS_TEST_PROFILE=" : "",
                 desc.profile ? desc.profile : "", message);
    macs_features f;
    macs_context_get_features(ctx, &f);
    half_accumulation = !f.float32_blend;
    return ctx;
}

macs_context *util_context(macs_headless *headless, const macs_limits *caps)
{
    return context_made(headless, caps, NULL, false);
}

macs_context *util_context_hiding(macs_headless *headless, const char *hidden)
{
    return context_made(headless, NULL, hidden, false);
}

macs_context *util_context_null_map(macs_headless *headless, const macs_limits *caps)
{
    return context_made(headless, caps, NULL, true);
}

int util_group_setup(void **state)
{
    *state = util_headless();
    return 0;
}

int util_group_teardown(void **state)
{
    macs_headless_destroy(*state);
    return 0;
}

macs_texture *util_texture(macs_context *ctx, int width, int height, macs_format format)
{
    macs_texture_desc desc = {0};
    desc.width = width;
    desc.height = height;
    desc.format = format;
    macs_texture *t = NULL;
    macs_status st = macs_texture_create(ctx, &desc, &t);
    if (st == MACS_ERR_LIMIT && util_profile()) {
        /* The test's own texture is beyond the profile's hardware: the test cannot run there. */
        print_message("skipped: the test's %dx%d texture is beyond profile %s: %s\n", width, height, util_profile(),
                      macs_context_error_message(ctx));
        macs_context_clear_error(ctx);
        skip();
    }
    if (st != MACS_OK)
        fail_msg("macs_texture_create %dx%d: %s", width, height, macs_context_error_message(ctx));
    return t;
}

void util_require_texture_size(macs_context *ctx, int width, int height)
{
    macs_limits eff;
    macs_context_get_limits(ctx, NULL, &eff);
    if (!util_profile() || (width <= eff.max_texture_size && height <= eff.max_texture_size))
        return;
    print_message("skipped: the test needs %dx%d textures, beyond profile %s's max_texture_size %d\n", width, height,
                  util_profile(), eff.max_texture_size);
    skip();
}

void util_fill_pattern(float *data, size_t n, unsigned seed)
{
    uint32_t x = seed * 2654435761u + 12345u;
    for (size_t i = 0; i < n; i++) {
        x = x * 1664525u + 1013904223u;
        float mantissa = (float)(x >> 8) / 16777216.0f; /* 0..1 */
        int e = (int)((x >> 3) % 60) - 30;
        float v = mantissa;
        for (; e > 0; e--)
            v *= 4.0f;
        for (; e < 0; e++)
            v *= 0.25f;
        data[i] = (x & 1) ? -v : v;
    }
}
