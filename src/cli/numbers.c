/* Strict number lists (numbers.h). strtol, unlike sscanf's %d, reports an overflow (sscanf's
 * behaviour is undefined there and glibc wraps), so a huge value cannot turn into a small one. */
#include "numbers.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>

/* One number at *text in [lo, hi]; *text moves past it. strtol would also take leading spaces and
 * a '+', which no option's syntax has, so the first character must start the number itself. */
static bool parse_one(const char **text, int lo, int hi, int *out)
{
    const char *at = *text;
    const char *digits = *at == '-' ? at + 1 : at;
    if (!isdigit((unsigned char)*digits))
        return false;
    char *end = NULL;
    errno = 0;
    long v = strtol(at, &end, 10);
    if (errno != 0 || v < lo || v > hi)
        return false;
    *out = (int)v;
    *text = end;
    return true;
}

bool cli_parse_ints(const char *text, char sep, int count, int lo, int hi, int *out)
{
    if (!text)
        return false;
    for (int i = 0; i < count; i++) {
        if (i > 0 && *text++ != sep)
            return false;
        if (!parse_one(&text, lo, hi, &out[i]))
            return false;
    }
    return *text == '\0';
}
