/* Test helpers shared by the MACS suites. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <GL/osmesa.h>
#include <cmocka.h>

#include "util_gl.h"

void util_release_current(void)
{
    if (eglGetCurrentContext() != EGL_NO_CONTEXT)
        assert_true(eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
    else
        OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
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
    desc.backend = (b && strcmp(b, "egl") == 0) ? MACS_HEADLESS_EGL : MACS_HEADLESS_OSMESA;
    macs_headless *h = NULL;
    char message[512];
    macs_status st = macs_headless_create(&desc, &h, message, sizeof message);
    if (st != MACS_OK)
        fail_msg("headless context (%s): %s", b ? b : "osmesa", message);
    assert_int_equal(macs_headless_backend_used(h), desc.backend);
    return h;
}

macs_context *util_context(macs_headless *headless, const macs_limits *caps)
{
    macs_context_desc desc = {0};
    desc.get_proc_address = macs_headless_get_proc_address(headless);
    desc.get_proc_address_user = macs_headless_proc_user(headless);
    if (caps)
        desc.caps = *caps;
    macs_context *ctx = NULL;
    char message[1024];
    macs_status st = macs_context_create(&desc, &ctx, message, sizeof message);
    if (st != MACS_OK)
        fail_msg("macs_context_create: %s", message);
    return ctx;
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
    if (st != MACS_OK)
        fail_msg("macs_texture_create %dx%d: %s", width, height, macs_context_error_message(ctx));
    return t;
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
