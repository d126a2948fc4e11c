/* What the fuzz targets share. */
#include "fuzz_target.h"

#include <stdio.h>
#include <stdlib.h>

void bg_fuzz_detach_stdin(void)
{
    /* Failure leaves stdin as it was: the run still works, it only loses this protection. */
    (void)freopen("/dev/null", "r", stdin);
}

void bg_fuzz_report(bg_status status, const char *message)
{
    /* Read at every call, not cached: a replay's children and libFuzzer's workers see the same
     * environment, and the cost is nothing next to a load. */
    const char *v = getenv("BG_FUZZ_VERBOSE");
    if (v && *v && *v != '0')
        fprintf(stderr, "fuzz: %s%s%s\n", bg_status_string(status), *message ? ": " : "", message);
}
