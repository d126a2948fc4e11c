/* The options that say how a model is turned, shaded and looked at (model_options.c): --up,
 * --smooth, --camera, --look-from, --look-at, --fov, --aperture and --focus-distance, parsed in one
 * place for every subcommand
 * that loads a scene (render, info, and a viewer to come), and handed to the scene-file library
 * through its desc. */
#ifndef CLI_MODEL_OPTIONS_H
#define CLI_MODEL_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "betelgeuse_scenefile.h"

typedef struct cli_model_options {
    bg_scenefile_up up;        /* --up; 0: the file's (+y) */
    bool smooth;               /* --smooth given */
    double smooth_angle;       /* its crease angle, 0 .. 180 (180 without a value) */
    int camera;                /* --camera N (from 1), BG_SCENEFILE_CAMERA_FRAME for auto; 0: not given */
    bool has_look_from, has_look_at;
    bg_vec3 look_from, look_at;
    double fov;                /* --fov; 0: not given */
    bool has_aperture, has_focus_distance; /* given: 0 is a value of each (a pinhole; focus at look_at) */
    double aperture, focus_distance;
} cli_model_options;

/* When argv[*i] (its name in name, its value in value when it was given after '=', else NULL) is one
 * of these options: reads it, and its value from argv[*i + 1] when it takes one (*i moves past it),
 * and returns 1; 0 when it is another option; -1 with the reason in why when its value is bad. */
int cli_model_option(int argc, char **argv, int *i, const char *name, const char *value, cli_model_options *o,
                     char *why, size_t why_size);

/* What can be checked before the scene is read: --look-from equal to --look-at, and --up, --smooth
 * or --camera given for a JSON scene (the same rule as bg_scenefile_load_any). False with the reason. */
bool cli_model_options_check(const cli_model_options *o, const char *scene, char *why, size_t why_size);

/* The options into the library's desc; d points into o, which must outlive the load. */
void cli_model_options_desc(const cli_model_options *o, bg_scenefile_desc *d);

/* The library names the desc field in its messages ("desc->camera: ..."); the command's user gave an
 * option: each field name in message is replaced by its option's, in place (the names are shorter). */
void cli_model_options_rename(char *message);

#endif
