/* The options of `betelgeuse render` and `betelgeuse info`, parsed and checked (options.c). */
#ifndef CLI_OPTIONS_H
#define CLI_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "model_options.h"

typedef enum cli_renderer { CLI_RENDERER_GPU = 0, CLI_RENDERER_CPU } cli_renderer;
typedef enum cli_backend { CLI_BACKEND_DEFAULT = 0, CLI_BACKEND_EGL, CLI_BACKEND_OSMESA } cli_backend;

/* Which subcommand's options are parsed: each takes its own set (docs/command.md). */
typedef enum cli_command { CLI_COMMAND_RENDER = 0, CLI_COMMAND_INFO, CLI_COMMAND_VIEW } cli_command;

typedef struct cli_options {
    const char *scene;      /* the scene or model file */
    const char *output;     /* -o: the PNG */
    const char *float_output; /* --float: the PFM, or NULL */
    int width, height;      /* --size; 0: the scene file's */
    int samples;            /* --samples; 0: the scene file's */
    int max_depth;          /* --max-depth; -1: the scene file's */
    int integrator;         /* --integrator: a bg_integrator; -1: the scene file's */
    cli_renderer renderer;
    cli_backend backend;
    bool crop;              /* --crop X0,Y0,X1,Y1 (x1, y1 exclusive) */
    int crop_x0, crop_y0, crop_x1, crop_y1;
    int tile, tiles;        /* --tile I/N (1-based); tiles 0: none */
    bool linear;            /* --linear: the PNG holds linear values, not sRGB */
    bool quiet;             /* --quiet: errors only */
    bool strict;            /* --strict: a warning while loading the scene is fatal (exit 2) */
    bool timings;           /* --timings (render): each phase's wall time to stderr */
    cli_model_options model; /* --up, --smooth, --camera, --look-from, --look-at, --fov */
    /* view only */
    double frame_ms;        /* --frame-ms: the frame time to hold while moving; 0: 33 */
    const char *script;     /* --script FILE, or NULL */
    bool benchmark;         /* --benchmark */
    bool verbose;           /* -v, --verbose: the GL version and each reload */
} cli_options;

/* Parses argv (after the subcommand's name); render wants -o, info takes only SCENE,
 * --renderer/--backend, --integrator and the model options, view SCENE, --size, --samples, --max-depth,
 * --integrator, -q, the model options and its own. False with the reason in why (a usage error). */
bool cli_options_parse(int argc, char **argv, cli_command command, cli_options *out, char *why, size_t why_size);

/* The window of the frame the options ask for: the crop rectangle (or the whole frame), then the
 * band of rows of tile I of N in it (rows [floor((I - 1) h / N), floor(I h / N))). False with the
 * reason when it lies outside the frame or is empty. */
bool cli_options_window(const cli_options *o, int frame_width, int frame_height, int *x, int *y, int *w, int *h,
                        char *why, size_t why_size);

#endif
