/* Headless contexts on the EGL device platform (EGL_EXT_platform_device): each listed device gives a
 * working context and says which device and renderer it is, Mesa's software device among them; the
 * default order prefers a device; an index the list does not hold is refused by number. Whatever
 * MACS_TEST_BACKEND says, these tests create their own device contexts; they skip, saying why, only
 * where EGL has no device platform or lists no device. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "util_gl.h"

/* What this process's EGL offers, found without MACS, so that MACS's answers are checked against it. */
typedef struct device_probe {
    const char *absent; /* why the device platform cannot be used, or NULL */
    EGLint count;
    int software_index; /* the device with EGL_MESA_device_software, or -1 */
} device_probe;

static bool has_token(const char *list, const char *token)
{
    size_t n = strlen(token);
    for (const char *p = list; p && (p = strstr(p, token)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

static device_probe probe_devices(void)
{
    device_probe probe = {NULL, 0, -1};
    /* The suite links no EGL (as MACS does not): the two core functions it needs, by name. */
    PFNEGLQUERYSTRINGPROC query_client = (PFNEGLQUERYSTRINGPROC)util_library_function("libEGL.so.1", "eglQueryString");
    PFNEGLGETPROCADDRESSPROC get_proc =
        (PFNEGLGETPROCADDRESSPROC)util_library_function("libEGL.so.1", "eglGetProcAddress");
    if (!query_client || !get_proc) {
        probe.absent = "libEGL.so.1 cannot be loaded";
        return probe;
    }
    const char *client = query_client(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    bool enumeration = has_token(client, "EGL_EXT_device_enumeration") || has_token(client, "EGL_EXT_device_base");
    if (!has_token(client, "EGL_EXT_platform_device") || !enumeration) {
        probe.absent = "EGL lacks EGL_EXT_platform_device or EGL_EXT_device_enumeration";
        return probe;
    }
    PFNEGLQUERYDEVICESEXTPROC query_devices = (PFNEGLQUERYDEVICESEXTPROC)get_proc("eglQueryDevicesEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC query_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)get_proc("eglQueryDeviceStringEXT");
    EGLDeviceEXT devices[64];
    if (!query_devices || !query_devices(64, devices, &probe.count) || probe.count < 1) {
        probe.absent = "eglQueryDevicesEXT lists no device";
        return probe;
    }
    for (int i = 0; query_string && i < probe.count; i++)
        if (has_token(query_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
            probe.software_index = i;
    return probe;
}

/* Skips the calling test, saying why, where the device platform is genuinely absent. */
#define SKIP_WITHOUT_DEVICES(probe) \
    do { \
        if ((probe).absent) { \
            print_message("skipped: %s\n", (probe).absent); \
            skip(); \
        } \
    } while (0)

static macs_headless *device_context(int index, char *message, size_t size, macs_status *status)
{
    macs_headless_desc d = {0};
    d.backend = MACS_HEADLESS_EGL_DEVICE;
    d.device_index = index;
    macs_headless *h = NULL;
    *status = macs_headless_create(&d, &h, message, size);
    return h;
}

/* A MACS context on the headless context clears and reads back a texture: the context really works. */
static void check_context_computes(macs_headless *h)
{
    assert_int_equal(macs_headless_make_current(h), MACS_OK);
    macs_context *ctx = util_context(h, NULL);
    macs_texture *t = util_texture(ctx, 2, 2, 0);
    assert_int_equal(macs_texture_clear(t, (const float[4]){0.5f, -2.0f, 3.0f, 1e6f}), MACS_OK);
    float px[16];
    assert_int_equal(macs_texture_read(t, px, 0), MACS_OK);
    assert_true(px[12] == 0.5f && px[13] == -2.0f && px[14] == 3.0f && px[15] == 1e6f);
    macs_context_destroy(ctx);
}

static void every_listed_device_gives_a_context(void **state)
{
    device_probe probe = probe_devices();
    SKIP_WITHOUT_DEVICES(probe);
    int worked = 0;
    for (int i = 0; i < probe.count; i++) {
        char message[1024];
        macs_status st;
        macs_headless *h = device_context(i, message, sizeof message, &st);
        if (st != MACS_OK) {
            /* A hardware device this process may not open (no render node access) is no failure of
             * MACS; Mesa's software device always opens. */
            assert_int_equal(st, MACS_ERR_CONTEXT);
            assert_true(i != probe.software_index);
            print_message("device %d gave no context: %s\n", i, message);
            continue;
        }
        worked++;
        assert_int_equal(macs_headless_backend_used(h), MACS_HEADLESS_EGL_DEVICE);
        macs_headless_info info;
        macs_headless_get_info(h, &info);
        assert_int_equal(info.backend, MACS_HEADLESS_EGL_DEVICE);
        assert_int_equal(info.device_index, i);
        assert_int_equal(info.device_count, probe.count);
        assert_true(info.renderer[0] != '\0');
        if (i == probe.software_index)
            assert_string_equal(info.device_name, "software");
        assert_true(i != probe.software_index || has_token(info.device_extensions, "EGL_MESA_device_software"));
        print_message("device %d of %d (%s): GL_RENDERER \"%s\"\n", i, info.device_count, info.device_name,
                      info.renderer);
        check_context_computes(h);
        macs_headless_destroy(h);
    }
    assert_true(worked > 0 || probe.software_index < 0);
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
}

static void software_device_gives_a_context(void **state)
{
    device_probe probe = probe_devices();
    SKIP_WITHOUT_DEVICES(probe);
    if (probe.software_index < 0) {
        print_message("skipped: EGL lists no Mesa software device (EGL_MESA_device_software)\n");
        skip();
    }
    char message[1024];
    macs_status st;
    macs_headless *h = device_context(probe.software_index, message, sizeof message, &st);
    if (st != MACS_OK)
        fail_msg("software device %d: %s", probe.software_index, message);
    macs_headless_info info;
    macs_headless_get_info(h, &info);
    assert_int_equal(info.backend, MACS_HEADLESS_EGL_DEVICE);
    assert_string_equal(info.device_name, "software");
    assert_true(info.renderer[0] != '\0');
    check_context_computes(h);
    macs_headless_destroy(h);
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
}

typedef struct info_log {
    int count;
    char last[1024];
} info_log;

static void keep_info(macs_log_level level, const char *message, void *user)
{
    info_log *log = user;
    if (level == MACS_LOG_INFO) {
        log->count++;
        snprintf(log->last, sizeof log->last, "%s", message);
    }
}

static void default_order_prefers_a_device(void **state)
{
    device_probe probe = probe_devices();
    SKIP_WITHOUT_DEVICES(probe);
    /* DEFAULT must land on a device whenever some device works; the software device always does. */
    if (probe.software_index < 0) {
        print_message("skipped: no device known to work (no Mesa software device)\n");
        skip();
    }
    info_log log = {0, ""};
    macs_headless_desc d = {0};
    d.logger.func = keep_info;
    d.logger.user = &log;
    macs_headless *h = NULL;
    char message[1024];
    if (macs_headless_create(&d, &h, message, sizeof message) != MACS_OK)
        fail_msg("default headless context: %s", message);
    assert_int_equal(macs_headless_backend_used(h), MACS_HEADLESS_EGL_DEVICE);
    macs_headless_info info;
    macs_headless_get_info(h, &info);
    assert_true(info.device_index >= 0 && info.device_index < probe.count);
    assert_true(info.renderer[0] != '\0');
    assert_int_equal(log.count, 1);
    assert_non_null(strstr(log.last, "EGL device"));
    assert_non_null(strstr(log.last, info.renderer));
    macs_headless_destroy(h);
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
}

static void device_index_outside_the_list_is_refused(void **state)
{
    char message[512], expected[64];
    macs_status st;
    macs_headless *h = device_context(-1, message, sizeof message, &st);
    assert_int_equal(st, MACS_ERR_INVALID_ARGUMENT);
    assert_null(h);
    assert_non_null(strstr(message, "desc.device_index -1"));
    macs_headless_desc d = {0};
    d.backend = MACS_HEADLESS_OSMESA;
    d.device_index = 1; /* OSMesa has no devices */
    assert_int_equal(macs_headless_create(&d, &h, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(message, "desc.device_index 1"));

    device_probe probe = probe_devices();
    SKIP_WITHOUT_DEVICES(probe);
    int index = (int)probe.count + 3;
    h = device_context(index, message, sizeof message, &st);
    assert_int_equal(st, MACS_ERR_INVALID_ARGUMENT);
    assert_null(h);
    snprintf(expected, sizeof expected, "desc.device_index %d", index);
    assert_non_null(strstr(message, expected));
    snprintf(expected, sizeof expected, "lists %d device", (int)probe.count);
    assert_non_null(strstr(message, expected));
    /* The default order does not swap a named device for another backend either. */
    d.backend = MACS_HEADLESS_DEFAULT;
    d.device_index = index;
    assert_int_equal(macs_headless_create(&d, &h, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_null(h);
    assert_non_null(strstr(message, expected));
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
}

/* An allocator that refuses the allocation numbered fail_at (0 = the first) and counts what lives. */
typedef struct failing_allocator {
    int made;
    int fail_at;
    int live;
} failing_allocator;

static void *failing_alloc(size_t size, void *user)
{
    failing_allocator *f = user;
    if (f->made++ == f->fail_at)
        return NULL;
    void *p = malloc(size);
    f->live += p != NULL;
    return p;
}

static void *failing_realloc(void *ptr, size_t size, void *user)
{
    if (!ptr)
        return failing_alloc(size, user);
    return realloc(ptr, size);
}

static void failing_free(void *ptr, void *user)
{
    failing_allocator *f = user;
    f->live -= ptr != NULL;
    free(ptr);
}

/* Fails each allocation of a create in turn: every one is checked, refused with MACS_ERR_OUT_OF_MEMORY
 * and leaves nothing behind, until the create that needs no more succeeds. */
static void check_every_allocation(macs_headless_backend backend)
{
    for (int fail_at = 0;; fail_at++) {
        assert_true(fail_at < 64);
        failing_allocator f = {0, fail_at, 0};
        macs_headless_desc d = {0};
        d.backend = backend;
        d.allocator.alloc = failing_alloc;
        d.allocator.realloc = failing_realloc;
        d.allocator.free = failing_free;
        d.allocator.user = &f;
        macs_headless *h = NULL;
        char message[1024];
        macs_status st = macs_headless_create(&d, &h, message, sizeof message);
        if (st == MACS_OK) {
            assert_true(f.made <= fail_at); /* no allocation was refused */
            macs_headless_destroy(h);
            assert_int_equal(f.live, 0);
            return;
        }
        if (st != MACS_ERR_OUT_OF_MEMORY)
            fail_msg("allocation %d refused: status %d, %s", fail_at, (int)st, message);
        assert_null(h);
        assert_int_equal(f.live, 0);
    }
}

static void every_allocation_is_checked(void **state)
{
    check_every_allocation(macs_headless_backend_used(*state));
    device_probe probe = probe_devices();
    if (!probe.absent && probe.software_index >= 0)
        check_every_allocation(MACS_HEADLESS_EGL_DEVICE);
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
}

/* The suite's own context is whatever MACS_TEST_BACKEND made: a device one says which device it is,
 * any other says it is on none. */
static void describe_reports_the_backend_in_use(void **state)
{
    macs_headless_info info;
    macs_headless_get_info(*state, &info);
    assert_int_equal(info.backend, macs_headless_backend_used(*state));
    if (info.backend == MACS_HEADLESS_EGL_DEVICE) {
        assert_true(info.device_count > 0);
        assert_true(info.device_index >= 0 && info.device_index < info.device_count);
    } else {
        assert_int_equal(info.device_index, -1);
        assert_int_equal(info.device_count, 0);
        assert_string_equal(info.device_name, "");
        assert_string_equal(info.device_extensions, "");
    }
    assert_true(info.renderer[0] != '\0');
    macs_headless_get_info(NULL, &info);
    assert_int_equal(info.backend, MACS_HEADLESS_DEFAULT);
    assert_string_equal(info.renderer, "");
    macs_headless_get_info(*state, NULL); /* ignored */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_listed_device_gives_a_context),
        cmocka_unit_test(software_device_gives_a_context),
        cmocka_unit_test(default_order_prefers_a_device),
        cmocka_unit_test(device_index_outside_the_list_is_refused),
        cmocka_unit_test(every_allocation_is_checked),
        cmocka_unit_test(describe_reports_the_backend_in_use),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
