/* A logger for the tests that gathers the warnings a load gives, to look for one by its words. */
#ifndef UTIL_WARNINGS_H
#define UTIL_WARNINGS_H

#include "betelgeuse.h"

typedef struct util_warnings {
    int count;
    char all[4096]; /* every warning, a line each, cut at the end when they are more */
} util_warnings;

/* A bg_logger func: appends a BG_LOG_WARNING message to the util_warnings that user points to. */
void util_warnings_collect(bg_log_level level, const char *message, void *user);

#endif
