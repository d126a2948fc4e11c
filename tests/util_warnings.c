/* The warnings logger of the tests (util_warnings.h). */
#include "util_warnings.h"

#include <stdio.h>
#include <string.h>

void util_warnings_collect(bg_log_level level, const char *message, void *user)
{
    util_warnings *w = user;
    if (level != BG_LOG_WARNING)
        return;
    w->count++;
    size_t n = strlen(w->all);
    snprintf(w->all + n, sizeof w->all - n, "%s\n", message);
}
