/* The conventions both public headers share (README, "API conventions"): one set of log levels,
 * one logger shape, one word for success, and a GL loader type that the usual loaders fit with the
 * one-line adapters macs.h shows, with no cast through void *. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "util_gl.h"

static void log_levels_have_one_numbering(void **state)
{
    (void)state;
    assert_int_equal(MACS_LOG_ERROR, 0);
    assert_int_equal((int)MACS_LOG_ERROR, (int)BG_LOG_ERROR);
    assert_int_equal((int)MACS_LOG_WARNING, (int)BG_LOG_WARNING);
    assert_int_equal((int)MACS_LOG_INFO, (int)BG_LOG_INFO);
    assert_int_equal((int)MACS_LOG_DEBUG, (int)BG_LOG_DEBUG);
}

static void success_reads_the_same(void **state)
{
    (void)state;
    assert_string_equal(macs_status_string(MACS_OK), "ok");
    assert_string_equal(bg_status_string(BG_OK), "ok");
    assert_int_equal(MACS_OK, 0);
    assert_int_equal(BG_OK, 0);
}

typedef struct heard {
    int calls;
    int level;
    char last[512];
} heard;

static void hear_macs(macs_log_level level, const char *message, void *user)
{
    heard *h = user;
    h->calls++;
    h->level = (int)level;
    snprintf(h->last, sizeof h->last, "%s", message);
}

static void hear_bg(bg_log_level level, const char *message, void *user)
{
    heard *h = user;
    h->calls++;
    h->level = (int)level;
    snprintf(h->last, sizeof h->last, "%s", message);
}

/* Both libraries take a logger as {func, user} in their descs and report an error at level 0. */
static void loggers_are_set_and_called_alike(void **state)
{
    (void)state;
    heard m = {0, -1, ""};
    macs_headless_desc hd = {0};
    hd.backend = (macs_headless_backend)7;
    hd.logger.func = hear_macs;
    hd.logger.user = &m;
    macs_headless *h = NULL;
    assert_int_equal(macs_headless_create(&hd, &h, NULL, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(m.calls, 1);
    assert_int_equal(m.level, MACS_LOG_ERROR);
    assert_non_null(strstr(m.last, "backend"));

    heard b = {0, -1, ""};
    bg_scene_desc sd = {0};
    sd.logger.func = hear_bg;
    sd.logger.user = &b;
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(&sd, &scene), BG_OK);
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_sphere(scene, bg_vec3_make(0, 0, 0), -1.0, 1, &id), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(b.calls, 1);
    assert_int_equal(b.level, BG_LOG_ERROR);
    bg_scene_destroy(scene);
}

/* The loaders a program linked to libEGL or libOSMesa would call; the suite links neither (as the
 * libraries do not), so it takes them from the libraries by name. */
typedef macs_gl_proc (*loader_fn)(const char *name);
static loader_fn eglGetProcAddress, OSMesaGetProcAddress;

/* The adapters exactly as macs.h writes them. */
static macs_gl_proc egl_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)eglGetProcAddress(n); }
static macs_gl_proc osmesa_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)OSMesaGetProcAddress(n); }

static void find_loaders(void)
{
    eglGetProcAddress = (loader_fn)util_library_function("libEGL.so.1", "eglGetProcAddress");
    OSMesaGetProcAddress = (loader_fn)util_library_function("libOSMesa.so.8", "OSMesaGetProcAddress");
    if (!OSMesaGetProcAddress)
        OSMesaGetProcAddress = (loader_fn)util_library_function("libOSMesa.so.6", "OSMesaGetProcAddress");
}

/* A caller's own loader (not the headless one) makes a working context: GL strings are read and a
 * texture round-trips. */
static void adapter_loads_gl(macs_headless_backend backend, macs_get_proc_address_fn loader)
{
    macs_headless_desc hd = {0};
    hd.backend = backend;
    macs_headless *h = NULL;
    char message[512];
    macs_status st = macs_headless_create(&hd, &h, message, sizeof message);
    if (st != MACS_OK && backend == MACS_HEADLESS_OSMESA && !util_osmesa_present()) {
        print_message("skipped: OSMesa is not installed (%s)\n", message);
        skip();
    }
    if (st != MACS_OK)
        fail_msg("headless backend %d: %s", (int)backend, message);
    find_loaders();
    assert_true(backend == MACS_HEADLESS_OSMESA ? OSMesaGetProcAddress != NULL : eglGetProcAddress != NULL);
    macs_context_desc cd = {0};
    cd.get_proc_address = loader;
    macs_context *ctx = NULL;
    st = macs_context_create(&cd, &ctx, message, sizeof message);
    if (st != MACS_OK)
        fail_msg("macs_context_create with the adapter: %s", message);
    macs_gl_info info;
    macs_context_get_gl_info(ctx, &info);
    assert_non_null(info.version);
    const float texel[4] = {0.25f, -1.5f, 3.0f, 1e-3f};
    macs_texture_desc td = {0};
    td.width = 1;
    td.height = 1;
    td.data = texel;
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(ctx, &td, &t), MACS_OK);
    float back[4] = {0};
    assert_int_equal(macs_texture_read(t, back, 0), MACS_OK);
    assert_memory_equal(back, texel, sizeof texel);
    macs_texture_destroy(t);
    macs_context_destroy(ctx);
    macs_headless_destroy(h);
}

static void egl_adapter_loads_gl(void **state)
{
    (void)state;
    adapter_loads_gl(MACS_HEADLESS_EGL, egl_proc);
}

static void osmesa_adapter_loads_gl(void **state)
{
    (void)state;
    adapter_loads_gl(MACS_HEADLESS_OSMESA, osmesa_proc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(log_levels_have_one_numbering),
        cmocka_unit_test(success_reads_the_same),
        cmocka_unit_test(loggers_are_set_and_called_alike),
        cmocka_unit_test(egl_adapter_loads_gl),
        cmocka_unit_test(osmesa_adapter_loads_gl),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
