/* A suite that crashes on purpose, to check the runner's handling of crashes (make check-runner, and
 * the device check's first step): it is not one of the suites (tests/test_*.c) and never runs in
 * them. In order, its tests pass, fail, skip, die of SIGSEGV (which cmocka catches, failing the test
 * and going on in the same process) and of SIGABRT (which cmocka does not catch: the process ends),
 * then pass. tests/run_suites.sh must then rerun the last two, each in a fresh process, and count
 * 2 passed, 3 failed (one by assertion, two by their signals, each named) and 1 skipped. */
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

static void passes_before(void **state)
{
    (void)state;
    assert_int_equal(2 + 2, 4);
}

static void fails_by_assertion(void **state)
{
    (void)state;
    assert_int_equal(2 + 2, 5);
}

static void skips(void **state)
{
    (void)state;
    skip();
}

/* Neither inlined nor a tail call (the check after raise), so that a backtrace names both frames. */
static void __attribute__((noinline)) raise_segv(void)
{
    if (raise(SIGSEGV) != 0)
        fail_msg("raise(SIGSEGV) failed");
}

static void dies_of_sigsegv(void **state)
{
    (void)state;
    raise_segv();
    assert_true(1);
}

static void dies_of_sigabrt(void **state)
{
    (void)state;
    abort();
}

static void passes_after(void **state)
{
    (void)state;
    assert_true(1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(passes_before),   cmocka_unit_test(fails_by_assertion), cmocka_unit_test(skips),
        cmocka_unit_test(dies_of_sigsegv), cmocka_unit_test(dies_of_sigabrt),    cmocka_unit_test(passes_after),
    };
    return cmocka_run_group_tests_name("crash_suite", tests, NULL, NULL);
}
