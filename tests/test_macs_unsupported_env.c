/* A real Mesa context without GL_ARB_texture_float (MESA_EXTENSION_OVERRIDE, set before the context
 * exists, which is why this is a suite of its own): MACS refuses it by name. The lever is Mesa's
 * alone, so on any other driver the test says so and is skipped; the same refusal on any driver,
 * through macs_context_desc.hidden_extensions, is test_macs_profiles' hidden_extensions_count_as_absent. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

#define GL_VERSION_ENUM 0x1F02u

/* Whether the current context is Mesa's: every Mesa driver ends GL_VERSION with "Mesa <release>". */
static bool context_is_mesa(macs_headless *h)
{
    typedef const unsigned char *(*get_string_fn)(unsigned);
    get_string_fn get_string = (get_string_fn)macs_headless_get_proc_address(h)("glGetString", macs_headless_proc_user(h));
    assert_non_null(get_string);
    const char *version = (const char *)get_string(GL_VERSION_ENUM);
    assert_non_null(version);
    return strstr(version, "Mesa") != NULL;
}

static void context_without_texture_float_is_refused(void **state)
{
    if (!context_is_mesa(*state)) {
        print_message("skipped: context_without_texture_float_is_refused: MESA_EXTENSION_OVERRIDE is Mesa's, and "
                      "this driver is not Mesa\n");
        skip();
    }
    macs_context_desc d = {0};
    d.get_proc_address = macs_headless_get_proc_address(*state);
    d.get_proc_address_user = macs_headless_proc_user(*state);
    macs_context *ctx = NULL;
    char message[1024] = "";
    assert_int_equal(macs_context_create(&d, &ctx, message, sizeof message), MACS_ERR_GL_UNSUPPORTED);
    assert_null(ctx);
    assert_non_null(strstr(message, "GL_ARB_texture_float"));
}

int main(void)
{
    setenv("MESA_EXTENSION_OVERRIDE", "-GL_ARB_texture_float", 1);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(context_without_texture_float_is_refused),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
