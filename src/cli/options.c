/* Option parsing for the command (options.h): every value is checked here, with the option and the
 * reason in the message, before any file is read. */
#include "options.h"

#include <stdio.h>
#include <string.h>

#include "betelgeuse.h"
#include "numbers.h"

/* The limits are the library's, so that a value the parser accepts is one the renderer takes. */
#define SIDE CLI_NUMBER_TEXT(BG_MAX_IMAGE_SIDE)

/* X1 and Y1 are exclusive, so they may reach the largest side itself. */
static bool parse_crop(const char *text, cli_options *o)
{
    int v[4];
    if (!cli_parse_ints(text, ',', 4, 0, BG_MAX_IMAGE_SIDE, v) || v[2] <= v[0] || v[3] <= v[1])
        return false;
    o->crop = true;
    o->crop_x0 = v[0];
    o->crop_y0 = v[1];
    o->crop_x1 = v[2];
    o->crop_y1 = v[3];
    return true;
}

static bool fail(char *why, size_t size, const char *format, const char *option, const char *value)
{
    snprintf(why, size, format, option, value ? value : "");
    return false;
}

/* render's options that mean nothing to a window: the viewer names them rather than ignoring them. */
static bool render_only(const char *a)
{
    static const char *const names[] = {"-o", "--output", "--float", "--crop", "--tile", "--linear", "--renderer",
                                        "--backend"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (strcmp(a, names[k]) == 0)
            return true;
    return false;
}

bool cli_options_parse(int argc, char **argv, cli_command command, cli_options *o, char *why, size_t size)
{
    const bool render = command == CLI_COMMAND_RENDER, view = command == CLI_COMMAND_VIEW;
    memset(o, 0, sizeof *o);
    o->max_depth = -1;
    o->integrator = -1;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        /* Options with a value take it from the next argument or after '='. */
        const char *value = NULL;
        char name[32];
        const char *eq = a[0] == '-' && a[1] == '-' ? strchr(a, '=') : NULL;
        if (eq && (size_t)(eq - a) < sizeof name) {
            memcpy(name, a, (size_t)(eq - a));
            name[eq - a] = '\0';
            value = eq + 1;
            a = name;
        }
#define VALUE()                                                                                \
    do {                                                                                       \
        if (!value) {                                                                          \
            if (i + 1 >= argc)                                                                 \
                return fail(why, size, "%s needs a value%s", a, NULL);                         \
            value = argv[++i];                                                                 \
        }                                                                                      \
    } while (0)
        int model = cli_model_option(argc, argv, &i, a, value, &o->model, why, size);
        if (model < 0)
            return false;
        if (model > 0)
            continue;
        if (view && render_only(a)) {
            return fail(why, size, "%s is an option of render, not of view%s", a, NULL);
        } else if (view && strcmp(a, "--frame-ms") == 0) {
            VALUE();
            double ms = 0;
            if (!cli_parse_doubles(value, '\0', 1, &ms) || !(ms >= 1 && ms <= 10000))
                return fail(why, size, "%s: '%s' is not a frame time in milliseconds, 1 .. 10000", a, value);
            o->frame_ms = ms;
        } else if (view && strcmp(a, "--script") == 0) {
            VALUE();
            o->script = value;
        } else if (view && strcmp(a, "--benchmark") == 0) {
            o->benchmark = true;
        } else if (view && (strcmp(a, "-v") == 0 || strcmp(a, "--verbose") == 0)) {
            o->verbose = true;
        } else if (strcmp(a, "--renderer") == 0) {
            VALUE();
            if (strcmp(value, "gpu") == 0)
                o->renderer = CLI_RENDERER_GPU;
            else if (strcmp(value, "cpu") == 0)
                o->renderer = CLI_RENDERER_CPU;
            else
                return fail(why, size, "%s: '%s' is neither gpu nor cpu", a, value);
        } else if (strcmp(a, "--backend") == 0) {
            VALUE();
            if (strcmp(value, "egl") == 0)
                o->backend = CLI_BACKEND_EGL;
            else if (strcmp(value, "osmesa") == 0)
                o->backend = CLI_BACKEND_OSMESA;
            else
                return fail(why, size, "%s: '%s' is neither egl nor osmesa", a, value);
        } else if (strcmp(a, "--strict") == 0) {
            o->strict = true;
        } else if (strcmp(a, "--integrator") == 0) {
            VALUE();
            if (strcmp(value, "whitted") == 0)
                o->integrator = BG_INTEGRATOR_WHITTED;
            else if (strcmp(value, "path") == 0)
                o->integrator = BG_INTEGRATOR_PATH;
            else
                return fail(why, size, "%s: '%s' is neither whitted nor path", a, value);
        } else if (command == CLI_COMMAND_INFO && a[0] == '-' && a[1] != '\0') {
            return fail(why, size, "unknown option %s for info%s", a, NULL);
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            VALUE();
            o->output = value;
        } else if (strcmp(a, "--float") == 0) {
            VALUE();
            o->float_output = value;
        } else if (strcmp(a, "--size") == 0) {
            VALUE();
            int wh[2];
            if (!cli_parse_ints(value, 'x', 2, 1, BG_MAX_IMAGE_SIDE, wh))
                return fail(why, size, "%s: '%s' is not WIDTHxHEIGHT with each 1 .. " SIDE, a, value);
            o->width = wh[0];
            o->height = wh[1];
        } else if (strcmp(a, "--samples") == 0) {
            VALUE();
            if (!cli_parse_ints(value, '\0', 1, 1, BG_MAX_SAMPLES, &o->samples))
                return fail(why, size,
                            "%s: '%s' is not a whole number of samples, 1 .. " CLI_NUMBER_TEXT(BG_MAX_SAMPLES), a,
                            value);
        } else if (strcmp(a, "--max-depth") == 0) {
            VALUE();
            if (!cli_parse_ints(value, '\0', 1, 0, BG_MAX_DEPTH, &o->max_depth))
                return fail(why, size, "%s: '%s' is not a bounce depth, 0 .. " CLI_NUMBER_TEXT(BG_MAX_DEPTH), a, value);
        } else if (strcmp(a, "--crop") == 0) {
            VALUE();
            if (!parse_crop(value, o))
                return fail(why, size,
                            "%s: '%s' is not X0,Y0,X1,Y1 with 0 <= X0 < X1 <= " SIDE " and 0 <= Y0 < Y1 <= " SIDE, a,
                            value);
        } else if (strcmp(a, "--tile") == 0) {
            VALUE();
            /* No frame has more rows than its longest side: more tiles could never be split. */
            int in[2];
            if (!cli_parse_ints(value, '/', 2, 1, BG_MAX_IMAGE_SIDE, in) || in[0] > in[1])
                return fail(why, size, "%s: '%s' is not I/N with 1 <= I <= N <= " SIDE, a, value);
            o->tile = in[0];
            o->tiles = in[1];
        } else if (strcmp(a, "--linear") == 0) {
            o->linear = true;
        } else if (strcmp(a, "--timings") == 0) {
            o->timings = true;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            o->quiet = true;
        } else if (a[0] == '-' && a[1] != '\0') {
            return fail(why, size, "unknown option %s%s", a, NULL);
        } else if (o->scene) {
            return fail(why, size, "a second scene file '%s' (one is rendered at a time)%s", a, NULL);
        } else {
            o->scene = a;
        }
        if (eq && value == eq + 1 &&
            (strcmp(a, "--linear") == 0 || strcmp(a, "--quiet") == 0 || strcmp(a, "--strict") == 0 ||
             strcmp(a, "--timings") == 0 ||
             strcmp(a, "--benchmark") == 0 ||
             strcmp(a, "--verbose") == 0))
            return fail(why, size, "%s takes no value%s", a, NULL);
#undef VALUE
    }
    if (!o->scene)
        return fail(why, size, "no scene file given%s%s", "", NULL);
    if (o->script && o->benchmark)
        return fail(why, size, "--script and --benchmark both drive the window: give one%s%s", "", NULL);
    if (render && !o->output)
        return fail(why, size, "-o OUT.png is required%s%s", "", NULL);
    return cli_model_options_check(&o->model, o->scene, why, size);
}

bool cli_options_window(const cli_options *o, int frame_width, int frame_height, int *x, int *y, int *w, int *h,
                        char *why, size_t size)
{
    int x0 = 0, y0 = 0, x1 = frame_width, y1 = frame_height;
    if (o->crop) {
        if (o->crop_x1 > frame_width || o->crop_y1 > frame_height) {
            snprintf(why, size, "--crop %d,%d,%d,%d: beyond the %dx%d frame", o->crop_x0, o->crop_y0, o->crop_x1,
                     o->crop_y1, frame_width, frame_height);
            return false;
        }
        x0 = o->crop_x0;
        y0 = o->crop_y0;
        x1 = o->crop_x1;
        y1 = o->crop_y1;
    }
    if (o->tiles > 0) {
        int rows = y1 - y0;
        if (o->tiles > rows) {
            snprintf(why, size, "--tile %d/%d: more tiles than the %d rows to split", o->tile, o->tiles, rows);
            return false;
        }
        int top = y0 + (int)((long long)(o->tile - 1) * rows / o->tiles);
        int bottom = y0 + (int)((long long)o->tile * rows / o->tiles);
        y0 = top;
        y1 = bottom;
    }
    *x = x0;
    *y = y0;
    *w = x1 - x0;
    *h = y1 - y0;
    return true;
}
