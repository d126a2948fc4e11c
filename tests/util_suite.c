/* The test runner's hooks into every cmocka suite, kept in this one file rather than in each main.
 * Every test program is linked with -Wl,--wrap=_cmocka_run_group_tests (TEST_LIBS in the Makefile),
 * so the call that cmocka_run_group_tests() and cmocka_run_group_tests_name() expand to reaches
 * this function first, and cmocka's own function is __real__cmocka_run_group_tests. It:
 * - makes stdout line-buffered: a suite killed by a timeout or a signal has then written every line
 *   up to that moment, where a pipe to the runner would otherwise hold back the last few kilobytes
 *   (cmocka writes its progress to stdout and its errors to stderr, which is unbuffered);
 * - with BG_TEST_LIST=1, prints the group's test names, one "bg-test: NAME" line each, in the order
 *   they run, and runs nothing (no group setup, so no GL context): tests/run_suites.sh asks for them
 *   to run the tests after a crash one by one, each in a fresh process;
 * - with CMOCKA_TEST_FILTER set, runs only the tests whose names match it (cmocka's patterns: * and
 *   ?; a plain name is that one test). cmocka 2.0 reads that variable itself; cmocka 1.1 only takes
 *   a filter through cmocka_set_test_filter(), which this calls, so both run the same tests. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

int __real__cmocka_run_group_tests(const char *group_name, const struct CMUnitTest *const tests, const size_t num_tests,
                                   CMFixtureFunction group_setup, CMFixtureFunction group_teardown);
int __wrap__cmocka_run_group_tests(const char *group_name, const struct CMUnitTest *const tests, const size_t num_tests,
                                   CMFixtureFunction group_setup, CMFixtureFunction group_teardown);

int __wrap__cmocka_run_group_tests(const char *group_name, const struct CMUnitTest *const tests, const size_t num_tests,
                                   CMFixtureFunction group_setup, CMFixtureFunction group_teardown)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    const char *list = getenv("BG_TEST_LIST");
    if (list && strcmp(list, "1") == 0) {
        for (size_t i = 0; i < num_tests; i++)
            if (tests[i].name)
                printf("bg-test: %s\n", tests[i].name);
        return 0;
    }
    const char *filter = getenv("CMOCKA_TEST_FILTER");
    if (filter && filter[0])
        cmocka_set_test_filter(filter);
    return __real__cmocka_run_group_tests(group_name, tests, num_tests, group_setup, group_teardown);
}
