/* The command line of the examples built on the shared scenes (bg_earth, bg_earth_shadow, bg_glass,
 * bg_bunny, bg_cpu_earth, bg_cpu_bunny): "<name> [out.png [size]]", with -h / --help. One parser, so that
 * every such example answers the same way; the self-contained examples (standalone_*.c, macs_hello.c) carry their own
 * few lines instead, to need nothing the install does not ship. */
#ifndef EXAMPLE_ARGS_H
#define EXAMPLE_ARGS_H

/* The largest image side an example accepts: bg_render_cpu's limit (the GPU may allow less). */
#define EXAMPLE_MAX_SIZE 16384

/* What the command line asked for. */
typedef struct example_args {
    const char *path; /* default "<name>.png" in the current folder */
    int size;         /* width and height in pixels, default 512 */
    char default_path[256];
} example_args;

/* Parses argv into args. what says in one line what the example renders, for --help. Returns -1
 * when the example should go on; else the exit status to return at once: 0 after printing the usage
 * to stdout for -h / --help, 2 after naming on stderr an unknown option (any other argument starting
 * with '-'), a size that is not an integer in 1..EXAMPLE_MAX_SIZE, or a third argument. */
int example_args_parse(int argc, char **argv, const char *name, const char *what, example_args *args);

#endif
