/* Whole numbers in the command's options and in a tile's text chunk, parsed strictly: an overflow
 * or a stray character is an error, never a wrapped or truncated value. */
#ifndef CLI_NUMBERS_H
#define CLI_NUMBERS_H

#include <stdbool.h>

/* A macro's number as a string literal, for messages and help that state a library limit where the
 * code enforces it: CLI_NUMBER_TEXT(BG_MAX_DEPTH) is "64". */
#define CLI_TEXT(x) #x
#define CLI_NUMBER_TEXT(x) CLI_TEXT(x)

/* Exactly count whole numbers in [lo, hi], separated by single sep characters and nothing else
 * (no spaces, no signs but a leading '-'), into out[0 .. count). False when text is anything else. */
bool cli_parse_ints(const char *text, char sep, int count, int lo, int hi, int *out);

/* Exactly count finite decimal numbers (digits with an optional '-', point and exponent: "2",
 * "-0.5", "1e3"), separated by single sep characters and nothing else; no "inf", "nan", hex or
 * spaces. False when text is anything else. */
bool cli_parse_doubles(const char *text, char sep, int count, double *out);

#endif
