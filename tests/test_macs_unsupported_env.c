/* A real Mesa context without GL_ARB_texture_float (MESA_EXTENSION_OVERRIDE, set before the context
 * exists, which is why this is a suite of its own): MACS refuses it by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

static void context_without_texture_float_is_refused(void **state)
{
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
