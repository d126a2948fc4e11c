/* Strict number lists (numbers.h). strtol, unlike sscanf's %d, reports an overflow (sscanf's
 * behaviour is undefined there and glibc wraps), so a huge value cannot turn into a small one. */
#include "numbers.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <string.h>
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

/* One decimal number at *text; *text moves past it. strtod would also read "inf", "nan", hex and
 * leading spaces, so the characters are checked to be a decimal number's first. */
static bool parse_real(const char **text, char sep, double *out)
{
    const char *at = *text;
    size_t n = 0;
    while (at[n] && at[n] != sep && strchr("0123456789.-+eE", at[n]))
        n++;
    if (n == 0 || !(isdigit((unsigned char)at[0]) || at[0] == '-' || at[0] == '.'))
        return false;
    char *end = NULL;
    errno = 0;
    double v = strtod(at, &end);
    if (end != at + n || errno == ERANGE || !isfinite(v))
        return false;
    *out = v;
    *text = end;
    return true;
}

bool cli_parse_doubles(const char *text, char sep, int count, double *out)
{
    if (!text)
        return false;
    for (int i = 0; i < count; i++) {
        if (i > 0 && *text++ != sep)
            return false;
        if (!parse_real(&text, sep, &out[i]))
            return false;
    }
    return *text == '\0';
}
