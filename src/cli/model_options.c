/* The model options (model_options.h): each value checked here with the option and the reason in the
 * message, before any file is read; what only the file can tell (how many cameras it has, where its
 * camera stands) the library checks, and its messages are given the options' names. */
#include "model_options.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "numbers.h"

/* One row per option: its name, and the desc field the library names in its messages. */
static const struct {
    const char *option, *field;
} fields[] = {
    {"--up", "desc->up_axis"},
    {"--smooth", "desc->smooth_angle_degrees"},
    {"--camera", "desc->camera"},
    {"--look-from", "desc->look_from"},
    {"--look-at", "desc->look_at"},
    {"--fov", "desc->fov_y_degrees"},
    {"--aperture", "desc->aperture_radius"},
    {"--focus-distance", "desc->focus_distance"},
};

static int bad(char *why, size_t size, const char *option, const char *value, const char *reason)
{
    snprintf(why, size, "%s: '%s' %s", option, value, reason);
    return -1;
}

static bool parse_point(const char *text, bg_vec3 *out)
{
    double v[3];
    if (!cli_parse_doubles(text, ',', 3, v))
        return false;
    *out = bg_vec3_make(v[0], v[1], v[2]);
    return true;
}

int cli_model_option(int argc, char **argv, int *i, const char *name, const char *value, cli_model_options *o,
                     char *why, size_t size)
{
    bool known = false;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++)
        known = known || strcmp(name, fields[k].option) == 0;
    if (!known)
        return 0;
    if (strcmp(name, "--smooth") == 0) {
        /* The angle is optional: the next argument is it only when it is a number, so that
         * "--smooth model.ply" smooths fully and reads the model. */
        double angle = 180.0;
        if (!value && *i + 1 < argc && cli_parse_doubles(argv[*i + 1], '\0', 1, &angle))
            value = argv[++*i];
        if (value && (!cli_parse_doubles(value, '\0', 1, &angle) || angle < 0 || angle > 180))
            return bad(why, size, name, value, "is not a crease angle in degrees, 0 .. 180");
        o->smooth = true;
        o->smooth_angle = angle;
        return 1;
    }
    if (!value) {
        if (*i + 1 >= argc) {
            snprintf(why, size, "%s needs a value", name);
            return -1;
        }
        value = argv[++*i];
    }
    if (strcmp(name, "--up") == 0) {
        static const char *const axes[] = {"y", "z", "-y", "-z"};
        static const bg_scenefile_up ups[] = {BG_SCENEFILE_UP_Y, BG_SCENEFILE_UP_Z, BG_SCENEFILE_UP_NEG_Y,
                                              BG_SCENEFILE_UP_NEG_Z};
        for (int k = 0; k < 4; k++)
            if (strcmp(value, axes[k]) == 0) {
                o->up = ups[k];
                return 1;
            }
        return bad(why, size, name, value, "is not an axis: y, z, -y or -z");
    }
    if (strcmp(name, "--camera") == 0) {
        if (strcmp(value, "auto") == 0)
            o->camera = BG_SCENEFILE_CAMERA_FRAME;
        else if (!cli_parse_ints(value, '\0', 1, 1, INT_MAX, &o->camera))
            return bad(why, size, name, value, "is neither auto nor a camera number (the file's cameras count from 1)");
        return 1;
    }
    if (strcmp(name, "--fov") == 0) {
        if (!cli_parse_doubles(value, '\0', 1, &o->fov) || !(o->fov > 0 && o->fov < 180))
            return bad(why, size, name, value, "is not a vertical field of view in degrees, between 0 and 180");
        return 1;
    }
    if (strcmp(name, "--aperture") == 0) {
        if (!cli_parse_doubles(value, '\0', 1, &o->aperture) || !(o->aperture >= 0))
            return bad(why, size, name, value, "is not a lens radius, a number >= 0 (0: a pinhole)");
        o->has_aperture = true;
        return 1;
    }
    if (strcmp(name, "--focus-distance") == 0) {
        if (!cli_parse_doubles(value, '\0', 1, &o->focus_distance) || !(o->focus_distance >= 0))
            return bad(why, size, name, value,
                       "is not a focus distance, a number >= 0 (0: the distance to the point looked at)");
        o->has_focus_distance = true;
        return 1;
    }
    bool from = strcmp(name, "--look-from") == 0;
    if (!parse_point(value, from ? &o->look_from : &o->look_at))
        return bad(why, size, name, value, "is not a point X,Y,Z of three numbers");
    *(from ? &o->has_look_from : &o->has_look_at) = true;
    return 1;
}

static bool is_json(const char *path)
{
    size_t n = strlen(path);
    return n >= 5 && strcasecmp(path + n - 5, ".json") == 0;
}

bool cli_model_options_check(const cli_model_options *o, const char *scene, char *why, size_t size)
{
    if (o->has_look_from && o->has_look_at && o->look_from.x == o->look_at.x && o->look_from.y == o->look_at.y &&
        o->look_from.z == o->look_at.z) {
        snprintf(why, size, "--look-from %g,%g,%g: the same point as --look-at (the camera needs a direction)",
                 o->look_from.x, o->look_from.y, o->look_from.z);
        return false;
    }
    const char *model_only = o->up ? "--up" : o->smooth ? "--smooth" : o->camera ? "--camera" : NULL;
    if (model_only && scene && is_json(scene)) {
        snprintf(why, size, "%s applies to model files, not to a JSON scene (its meshes have \"transform\" and "
                 "\"normals\", and it has one \"camera\"; --look-from, --look-at, --fov, --aperture and "
                 "--focus-distance apply to it)", model_only);
        return false;
    }
    return true;
}

void cli_model_options_desc(const cli_model_options *o, bg_scenefile_desc *d)
{
    d->up_axis = o->up;
    /* --smooth 0 creases every edge: flat faces, which is what a zero angle asks of the library. */
    d->smooth_angle_degrees = o->smooth ? o->smooth_angle : 0.0;
    d->camera = o->camera;
    d->look_from = o->has_look_from ? &o->look_from : NULL;
    d->look_at = o->has_look_at ? &o->look_at : NULL;
    d->fov_y_degrees = o->fov;
    d->aperture_radius = o->has_aperture ? &o->aperture : NULL;
    d->focus_distance = o->has_focus_distance ? &o->focus_distance : NULL;
}

void cli_model_options_rename(char *message)
{
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
        size_t from = strlen(fields[k].field), to = strlen(fields[k].option);
        char *at;
        /* Every option's name is shorter than its field's: the text only shrinks. */
        while ((at = strstr(message, fields[k].field)) != NULL) {
            memmove(at + to, at + from, strlen(at + from) + 1);
            memcpy(at, fields[k].option, to);
        }
    }
}
