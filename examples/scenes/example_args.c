/* One command-line parser for the examples on the shared scenes. Arguments are read in order, so
 * --help anywhere answers with the usage unless an unknown option comes before it. */
#include "example_args.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void print_usage(const char *name, const char *what)
{
    printf("usage: %s [out.png [size]]\n"
           "%s\n"
           "\n"
           "  out.png     where to write the PNG (default %s.png in the current folder)\n"
           "  size        width and height in pixels, 1..%d (default 512)\n"
           "  -h, --help  print this help and exit\n",
           name, what, name, EXAMPLE_MAX_SIZE);
}

/* Digits only: strtol alone would also take " 12", "+12" and "0x10". */
static int parse_size(const char *text)
{
    if (text[0] < '0' || text[0] > '9')
        return 0;
    char *end = NULL;
    long v = strtol(text, &end, 10);
    if (*end != '\0' || v < 1 || v > EXAMPLE_MAX_SIZE)
        return 0;
    return (int)v;
}

int example_args_parse(int argc, char **argv, const char *name, const char *what, example_args *args)
{
    snprintf(args->default_path, sizeof args->default_path, "%s.png", name);
    args->path = args->default_path;
    args->size = 512;
    int positional = 0;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            print_usage(name, what);
            return 0;
        }
        if (arg[0] == '-') {
            fprintf(stderr, "%s: unknown option '%s' (try --help)\n", name, arg);
            return 2;
        }
        if (positional == 0) {
            args->path = arg;
        } else if (positional == 1) {
            args->size = parse_size(arg);
            if (args->size == 0) {
                fprintf(stderr, "%s: size '%s' is not an integer in 1..%d\n", name, arg, EXAMPLE_MAX_SIZE);
                return 2;
            }
        } else {
            fprintf(stderr, "%s: too many arguments ('%s'): at most out.png and size (try --help)\n", name,
                    arg);
            return 2;
        }
        positional++;
    }
    return -1;
}
