/* A scene or model file through the scene-file library into a new scene, as the model options ask
 * (scene_load.c): one loader for every subcommand, so that render, info and view read a file alike
 * and report a bad one in the same words. */
#ifndef CLI_SCENE_LOAD_H
#define CLI_SCENE_LOAD_H

#include <stdbool.h>
#include <stddef.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"
#include "inputs.h"
#include "model_options.h"

/* What a load does with the library's warnings (what a model's materials lose, a skipped header
 * line): quiet (--quiet) prints none, strict (--strict) makes any one fatal; warnings counts them. */
typedef struct cli_load_logs {
    bool quiet;
    bool strict;
    int warnings;
} cli_load_logs;

/* Loads path into a new committed scene (*out) and its settings (*file), printing or counting the
 * warnings as logs says. Each file the load reads goes into inputs when it is not NULL. Returns the
 * exit code: 0, 2 for a bad or missing file (or an option the file cannot take, or a warning under
 * --strict), 1 when out of memory; on failure the message ("FILE: JSON.PATH: reason", the options
 * named as the user gave them) is printed to stderr after "betelgeuse: " and also copied into why
 * (when not NULL). */
int cli_scene_load(const char *path, const cli_model_options *model, cli_load_logs *logs, cli_inputs *inputs,
                   bg_scene **out, bg_scenefile_result *file, char *why, size_t why_size);

#endif
