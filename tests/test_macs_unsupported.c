/* GL requirements: a loader wrapper hides functions, extensions or version, and MACS refuses with
 * MACS_ERR_GL_UNSUPPORTED naming what is missing; the EXT_framebuffer_object fallback works.
 * Every context here is used as GL 2.1 (desc.max_gl_version 21), whatever version the driver made
 * it: framebuffer objects are core from 3.0, so on a driver whose default context is 4.6 (NVIDIA's,
 * through EGL without version attributes) hiding the FBO extensions would otherwise change nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

#define FAKE_GL_VERSION 0x1F02u
#define FAKE_GL_EXTENSIONS 0x1F03u

/* What the wrapper hides; tests are single-threaded, so file-level state is enough. */
static struct {
    macs_get_proc_address_fn real;
    void *real_user;
    const char *hidden_function;
    const char *hidden_extensions[4];
    const char *version;
    bool null_version;
} hide;
static const unsigned char *(*real_get_string)(unsigned);
static char filtered[1 << 16];

static const unsigned char *fake_get_string(unsigned name)
{
    if (name == FAKE_GL_VERSION && hide.null_version)
        return NULL;
    if (name == FAKE_GL_VERSION && hide.version)
        return (const unsigned char *)hide.version;
    const unsigned char *s = real_get_string(name);
    if (name != FAKE_GL_EXTENSIONS || !s)
        return s;
    /* Rebuild the list without the hidden names (whole tokens only). */
    filtered[0] = '\0';
    char copy[1 << 16];
    snprintf(copy, sizeof copy, "%s", (const char *)s);
    for (char *save = NULL, *tok = strtok_r(copy, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        bool drop = false;
        for (int i = 0; i < 4; i++)
            drop |= hide.hidden_extensions[i] && strcmp(tok, hide.hidden_extensions[i]) == 0;
        if (!drop) {
            strncat(filtered, tok, sizeof filtered - strlen(filtered) - 2);
            strcat(filtered, " ");
        }
    }
    return (const unsigned char *)filtered;
}

static macs_gl_proc hiding_loader(const char *name, void *user)
{
    (void)user;
    if (hide.hidden_function && strcmp(name, hide.hidden_function) == 0)
        return NULL;
    macs_gl_proc p = hide.real(name, hide.real_user);
    if (strcmp(name, "glGetString") == 0) {
        real_get_string = (const unsigned char *(*)(unsigned))p;
        p = (macs_gl_proc)fake_get_string;
    }
    return p;
}

static macs_status create_hidden(void **state, char *message, size_t size, macs_context **out)
{
    hide.real = macs_headless_get_proc_address(*state);
    hide.real_user = macs_headless_proc_user(*state);
    macs_context_desc d = {0};
    d.get_proc_address = hiding_loader;
    d.max_gl_version = 21;
    macs_status st = macs_context_create(&d, out, message, size);
    memset(&hide, 0, sizeof hide);
    return st;
}

static void missing_function_is_named(void **state)
{
    char message[1024];
    macs_context *ctx = NULL;
    hide.hidden_function = "glDrawBuffers";
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_GL_UNSUPPORTED);
    assert_null(ctx);
    assert_non_null(strstr(message, "glDrawBuffers"));
    hide.hidden_function = "glGenFramebuffers";
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_GL_UNSUPPORTED);
    assert_non_null(strstr(message, "glGenFramebuffers"));
}

static void missing_extension_is_named(void **state)
{
    char message[1024];
    macs_context *ctx = NULL;
    hide.hidden_extensions[0] = "GL_ARB_texture_float";
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_GL_UNSUPPORTED);
    assert_non_null(strstr(message, "GL_ARB_texture_float"));
    hide.hidden_extensions[0] = "GL_ARB_framebuffer_object";
    hide.hidden_extensions[1] = "GL_EXT_framebuffer_object";
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_GL_UNSUPPORTED);
    assert_non_null(strstr(message, "GL_ARB_framebuffer_object"));
    assert_null(strstr(message, "GL_ARB_texture_float"));
}

static void old_version_is_refused(void **state)
{
    char message[1024];
    macs_context *ctx = NULL;
    hide.version = "2.0 Fake";
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_GL_UNSUPPORTED);
    assert_non_null(strstr(message, "2.1"));
    assert_non_null(strstr(message, "2.0 Fake"));
    hide.version = "OpenGL ES 3.2 Fake";
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_GL_UNSUPPORTED);
    hide.null_version = true;
    assert_int_equal(create_hidden(state, message, sizeof message, &ctx), MACS_ERR_CONTEXT);
    assert_non_null(strstr(message, "current"));
}

static void ext_framebuffer_object_fallback_works(void **state)
{
    char message[1024];
    macs_context *ctx = NULL;
    hide.hidden_extensions[0] = "GL_ARB_framebuffer_object";
    macs_status st = create_hidden(state, message, sizeof message, &ctx);
    if (st != MACS_OK)
        fail_msg("%s", message);
    macs_features f;
    macs_context_get_features(ctx, &f);
    assert_false(f.arb_framebuffer_object);
    /* A split pass with depth and stencil through the EXT entry points. */
    macs_texture *out[3];
    for (int i = 0; i < 3; i++)
        out[i] = util_texture(ctx, 4, 4, 0);
    macs_output_desc o[3] = {{"a", "vec4(1.0)"}, {"b", "vec4(2.0)"}, {"c", "vec4(3.0)"}};
    macs_pass_desc d = {0};
    d.outputs = o;
    d.output_count = 3;
    d.output_textures = out;
    macs_context_destroy(ctx);
    macs_limits caps = {0};
    caps.max_draw_buffers = 2;
    hide.hidden_extensions[0] = "GL_ARB_framebuffer_object";
    hide.real = macs_headless_get_proc_address(*state);
    hide.real_user = macs_headless_proc_user(*state);
    macs_context_desc cd = {0};
    cd.get_proc_address = hiding_loader;
    cd.max_gl_version = 21;
    cd.caps = caps;
    assert_int_equal(macs_context_create(&cd, &ctx, message, sizeof message), MACS_OK);
    memset(&hide, 0, sizeof hide);
    for (int i = 0; i < 3; i++)
        out[i] = util_texture(ctx, 4, 4, 0);
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(p), 2);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    float px[64];
    for (int i = 0; i < 3; i++) {
        assert_int_equal(macs_texture_read(out[i], px, 0), MACS_OK);
        assert_true(px[0] == (float)(i + 1) && px[63] == (float)(i + 1));
    }
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(missing_function_is_named),
        cmocka_unit_test(missing_extension_is_named),
        cmocka_unit_test(old_version_is_refused),
        cmocka_unit_test(ext_framebuffer_object_fallback_works),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
