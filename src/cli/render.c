/* `betelgeuse render` and `betelgeuse info` (docs/command.md): a scene or model file through the
 * scene-file library into a scene, rendered by the GPU (a headless context) or the CPU reference,
 * with the frame, samples, window and tile the options ask for, written as a PNG that records its
 * place in the frame (and a PFM of the radiance with --float). Ctrl-C cancels through the progress
 * callback: the render returns BG_ERR_CANCELLED and nothing is written. The outputs are replaced
 * only when all of them are written (output.h), and never when they name a file the scene reads. */
#include "cli.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"
#include "inputs.h"
#include "macs.h"
#include "options.h"
#include "output.h"
#include "progress.h"
#include "scene_load.h"
#include "tile_file.h"

static volatile sig_atomic_t interrupted;

static void on_interrupt(int signal)
{
    (void)signal;
    interrupted = 1;
}

/* The PNG as the render tells its final rows (settings.rows_done): encoded while the GPU renders
 * the next tiles, and timed for --timings. */
typedef struct png_rows {
    cli_png_stream *stream;
    const bg_image *image;
    double seconds; /* spent encoding inside the render */
} png_rows;

static void on_rows(int y0, int y1, void *user)
{
    png_rows *p = user;
    double t0 = cli_now();
    cli_png_stream_rows(p->stream, p->image, y0, y1);
    p->seconds += cli_now() - t0;
}

/* What the render's progress calls reach: the bar, the interrupt flag, and the PNG's state (a write
 * that failed stops the render: its file cannot be finished). */
typedef struct progress_user {
    cli_progress *bar;
    const png_rows *png;
} progress_user;

static bool on_progress(double fraction, void *user)
{
    progress_user *p = user;
    cli_progress_update(p->bar, fraction);
    return !interrupted && !cli_png_stream_failed(p->png->stream);
}

/* The GPU's pieces, made and freed together. */
typedef struct gpu {
    macs_headless *headless;
    macs_context *context;
    bg_renderer *renderer;
} gpu;

static void gpu_close(gpu *g)
{
    bg_renderer_destroy(g->renderer);
    macs_context_destroy(g->context);
    macs_headless_destroy(g->headless);
    memset(g, 0, sizeof *g);
}

static bool gpu_open(cli_backend backend, gpu *g, char *why, size_t size)
{
    memset(g, 0, sizeof *g);
    macs_headless_desc hd;
    memset(&hd, 0, sizeof hd);
    hd.backend = backend == CLI_BACKEND_OSMESA ? MACS_HEADLESS_OSMESA : MACS_HEADLESS_DEFAULT;
    macs_status ms = MACS_OK;
    if (backend == CLI_BACKEND_EGL) {
        /* EGL on a GPU device first, then EGL surfaceless. */
        hd.backend = MACS_HEADLESS_EGL_DEVICE;
        ms = macs_headless_create(&hd, &g->headless, why, size);
        if (ms != MACS_OK) {
            hd.backend = MACS_HEADLESS_EGL;
            ms = macs_headless_create(&hd, &g->headless, why, size);
        }
    } else {
        ms = macs_headless_create(&hd, &g->headless, why, size);
    }
    if (ms != MACS_OK)
        return false;
    macs_context_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.get_proc_address = macs_headless_get_proc_address(g->headless);
    cd.get_proc_address_user = macs_headless_proc_user(g->headless);
    if (macs_context_create(&cd, &g->context, why, size) != MACS_OK) {
        gpu_close(g);
        return false;
    }
    bg_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.context = g->context;
    if (bg_renderer_create(&rd, &g->renderer, why, size) != BG_OK) {
        gpu_close(g);
        return false;
    }
    return true;
}

/* One render of the window into image, on the chosen renderer. */
static bg_status render_once(const cli_options *o, gpu *g, bg_scene *scene, const bg_render_settings *settings,
                             bg_image *image, char *why, size_t size)
{
    bg_status st;
    if (o->renderer == CLI_RENDERER_CPU) {
        st = bg_render_cpu(scene, settings, image);
        if (st != BG_OK)
            snprintf(why, size, "%s", bg_scene_error_message(scene));
    } else {
        st = bg_render_gpu(g->renderer, scene, settings, image);
        /* A limit is the GPU's alone (a float range, a budget, the path integrator before a GPU plan
           draws it): the CPU reference has none of them, so the message says how to get the image. */
        if (st == BG_ERR_LIMIT)
            snprintf(why, size, "%s (a limit of the GPU renderer: --renderer cpu renders without it)",
                     bg_renderer_error_message(g->renderer));
        else if (st != BG_OK)
            snprintf(why, size, "%s", bg_renderer_error_message(g->renderer));
    }
    return st;
}

/* Refuses, before any render, outputs that would overwrite an input or each other; the exit code. */
static int check_outputs(const cli_options *o, const cli_inputs *inputs)
{
    char why[1024];
    if (inputs->out_of_memory) {
        fprintf(stderr, "betelgeuse: out of memory listing the scene's files\n");
        return CLI_EXIT_FAILED;
    }
    if (!cli_inputs_allow(inputs, "-o", o->output, why, sizeof why) ||
        (o->float_output && !cli_inputs_allow(inputs, "--float", o->float_output, why, sizeof why))) {
        fprintf(stderr, "betelgeuse render: %s\n", why);
        return CLI_EXIT_USAGE;
    }
    return CLI_EXIT_OK;
}

/* The frame, window and settings the options and the scene file ask for; false with the reason
 * when the window does not fit the frame. */
static bool plan_render(const cli_options *o, const bg_scenefile_result *file, bg_render_settings *settings,
                        cli_placement *where, int *w, int *h, char *why, size_t size)
{
    int frame_w = o->width ? o->width : file->image.width, frame_h = o->height ? o->height : file->image.height;
    int x, y;
    if (!cli_options_window(o, frame_w, frame_h, &x, &y, w, h, why, size))
        return false;
    *settings = file->settings;
    settings->samples = o->samples ? o->samples : file->image.samples;
    if (o->max_depth >= 0)
        settings->max_depth = o->max_depth;
    if (o->integrator >= 0)
        settings->integrator = (bg_integrator)o->integrator;
    if (o->linear)
        settings->encoding = BG_ENCODING_LINEAR;
    settings->frame_width = frame_w;
    settings->frame_height = frame_h;
    settings->window_x = x;
    settings->window_y = y;
    *where = (cli_placement){x, y, frame_w, frame_h};
    return true;
}

/* Wall times of the command's phases for --timings (seconds). The render's first frame holds the
 * programs' compilation; a second frame, rendered only for --timings, shows the frame alone. */
typedef struct phase_times {
    double load, context, render, again, png, png_in_render, write;
    int compiled;
} phase_times;

static void print_times(const phase_times *t)
{
    fprintf(stderr,
            "betelgeuse: timings: scene load %.1f ms, context %.1f ms, render %.1f ms (%d programs compiled), "
            "render again %.1f ms, PNG encode and write %.1f ms (%.1f ms of it inside the render, as rows came), "
            "put in place %.1f ms\n",
            1e3 * t->load, 1e3 * t->context, 1e3 * t->render, t->compiled, 1e3 * t->again,
            1e3 * (t->png + t->png_in_render), 1e3 * t->png_in_render, 1e3 * t->write);
}

/* The float frame (when asked for) and the PNG's, whose rows go into png as they become final;
 * BG_OK or the failure, with the reason in why. Ctrl-C cancels through the progress callback. */
static bg_status render_images(const cli_options *o, gpu *g, bg_scene *scene, bg_render_settings *settings,
                               bg_image *image, bg_image *radiance, cli_progress *bar, png_rows *png, char *why,
                               size_t size)
{
    cli_progress_start(bar, !o->quiet);
    progress_user user = {bar, png};
    bg_render_settings set = *settings;
    set.progress = on_progress;
    set.progress_user = &user;
    /* The float frame renders first when asked for: it is the one progress runs over twice. */
    bg_status st = o->float_output ? render_once(o, g, scene, &set, radiance, why, size) : BG_OK;
    set.rows_done = on_rows;
    set.rows_user = png;
    if (st == BG_OK)
        st = render_once(o, g, scene, &set, image, why, size);
    cli_progress_finish(bar, st == BG_OK);
    if (st == BG_ERR_CANCELLED)
        snprintf(why, size, cli_png_stream_failed(png->stream) ? "the PNG could not be written; nothing was written"
                                                               : "cancelled; nothing was written");
    return st;
}

/* Both images into their temporaries, then both put in place: a failure anywhere before the
 * renames leaves every existing file as it was. */
static bool write_outputs(const cli_options *o, cli_output outs[2], png_rows *png, const bg_image *radiance,
                          char *why, size_t size, phase_times *times)
{
    double t0 = cli_now();
    /* The PNG's rows not yet written (all of them when the render told none), then its end. */
    cli_png_stream *stream = png->stream;
    png->stream = NULL;
    if (!cli_png_stream_end(stream, png->image, why, size) || !cli_output_finish(&outs[0], why, size))
        return false;
    double t1 = cli_now();
    times->png = t1 - t0;
    if (o->float_output && (!cli_pfm_write(outs[1].file, o->float_output, radiance, why, size) ||
                            !cli_output_finish(&outs[1], why, size)))
        return false;
    /* Ctrl-C while the files were written still cancels: the last moment before anything changes. */
    if (interrupted) {
        snprintf(why, size, "cancelled; nothing was written");
        return false;
    }
    bool done = cli_outputs_commit(outs, o->float_output ? 2 : 1, why, size);
    times->write = cli_now() - t1;
    return done;
}

/* Renders the planned window and writes it; the exit code, with the message printed. The outputs'
 * temporaries are made first, so that a folder that cannot be written fails before the render. */
static int render_and_write(const cli_options *o, bg_scene *scene, bg_render_settings *settings,
                            const cli_placement *where, int w, int h, phase_times *times)
{
    char why[1024];
    cli_output outs[2];
    memset(outs, 0, sizeof outs);
    gpu g;
    memset(&g, 0, sizeof g);
    bg_image image = {w, h, BG_PIXEL_RGBA8, 0, NULL};
    bg_image radiance = {w, h, BG_PIXEL_RGBA32F, 0, NULL};
    png_rows png = {NULL, &image, 0.0};
    int status = CLI_EXIT_FAILED;
    double t0 = cli_now();
    if (!cli_output_open(&outs[0], o->output, why, sizeof why) ||
        (o->float_output && !cli_output_open(&outs[1], o->float_output, why, sizeof why))) {
        fprintf(stderr, "betelgeuse: %s\n", why);
    } else if (o->renderer == CLI_RENDERER_GPU && !gpu_open(o->backend, &g, why, sizeof why)) {
        fprintf(stderr, "betelgeuse: no GPU context: %s (--renderer cpu renders without one)\n", why);
    } else if (!(image.pixels = malloc((size_t)w * (size_t)h * 4)) ||
               (o->float_output && !(radiance.pixels = malloc((size_t)w * (size_t)h * 16)))) {
        fprintf(stderr, "betelgeuse: out of memory for a %dx%d image\n", w, h);
    } else if (!cli_png_stream_begin(&png.stream, outs[0].file, o->output, w, h, where, why, sizeof why)) {
        fprintf(stderr, "betelgeuse: %s\n", why);
    } else {
        /* Ctrl-C is caught until the outputs are in place, so that it never leaves a temporary. */
        struct sigaction action, previous;
        memset(&action, 0, sizeof action);
        action.sa_handler = on_interrupt;
        sigaction(SIGINT, &action, &previous);
        cli_progress bar;
        double t1 = cli_now();
        times->context = t1 - t0;
        bg_status st = render_images(o, &g, scene, settings, &image, &radiance, &bar, &png, why, sizeof why);
        double t2 = cli_now();
        times->render = t2 - t1;
        times->png_in_render = png.seconds;
        if (st == BG_OK && o->timings) {
            bg_render_stats stats;
            if (g.renderer) {
                bg_renderer_get_stats(g.renderer, &stats);
                times->compiled = stats.programs_compiled;
            }
            bg_render_settings quiet = *settings;
            quiet.progress = NULL;
            st = render_once(o, &g, scene, &quiet, &image, why, sizeof why);
        }
        double t3 = cli_now();
        times->again = t3 - t2;
        if (st != BG_OK || !write_outputs(o, outs, &png, &radiance, why, sizeof why, times))
            fprintf(stderr, "betelgeuse: %s\n", why);
        else
            status = CLI_EXIT_OK;
        sigaction(SIGINT, &previous, NULL);
        if (status == CLI_EXIT_OK && !o->quiet && isatty(2))
            fprintf(stderr, "betelgeuse: %dx%d%s written to %s in %.1f s\n", w, h,
                    w != where->frame_width || h != where->frame_height ? " window" : "", o->output,
                    cli_now() - bar.start);
    }
    cli_png_stream_abort(png.stream);
    cli_output_discard(&outs[0]);
    cli_output_discard(&outs[1]);
    free(image.pixels);
    free(radiance.pixels);
    gpu_close(&g);
    return status;
}

int cli_render(int argc, char **argv)
{
    cli_options o;
    char why[1024];
    if (!cli_options_parse(argc, argv, CLI_COMMAND_RENDER, &o, why, sizeof why)) {
        fprintf(stderr, "betelgeuse render: %s\n(see betelgeuse --help)\n", why);
        return CLI_EXIT_USAGE;
    }
    if (o.float_output && cli_output_same_file(o.output, o.float_output)) {
        fprintf(stderr, "betelgeuse render: --float %s: the same file as -o %s; one would replace the other\n",
                o.float_output, o.output);
        return CLI_EXIT_USAGE;
    }
    /* Warnings (what a model's materials lose) go to stderr terminal or not, so that a script's log
     * says what was dropped; --quiet silences them. */
    cli_load_logs logs = {o.quiet, o.strict, 0};
    bg_scene *scene = NULL;
    bg_scenefile_result file;
    cli_inputs inputs;
    memset(&inputs, 0, sizeof inputs);
    phase_times times;
    memset(&times, 0, sizeof times);
    double loading = cli_now();
    int status = cli_scene_load(o.scene, &o.model, &logs, &inputs, &scene, &file, NULL, 0);
    times.load = cli_now() - loading;
    if (status == CLI_EXIT_OK)
        status = check_outputs(&o, &inputs);
    cli_inputs_free(&inputs);
    bg_render_settings settings;
    cli_placement where;
    int w = 0, h = 0;
    if (status == CLI_EXIT_OK && !plan_render(&o, &file, &settings, &where, &w, &h, why, sizeof why)) {
        fprintf(stderr, "betelgeuse render: %s\n", why);
        status = CLI_EXIT_USAGE;
    }
    if (status == CLI_EXIT_OK)
        status = render_and_write(&o, scene, &settings, &where, w, h, &times);
    if (status == CLI_EXIT_OK && o.timings)
        print_times(&times);
    bg_scene_destroy(scene);
    return status;
}

const char *cli_plan_name(bg_gpu_plan p)
{
    switch (p) {
    case BG_PLAN_FUSED:
        return "fused (BG_PLAN_FUSED)";
    case BG_PLAN_FUSED_TREE:
        return "fused with the object tree (BG_PLAN_FUSED_TREE)";
    case BG_PLAN_MULTIPASS:
        return "multipass (BG_PLAN_MULTIPASS)";
    default:
        return "automatic";
    }
}

/* Which camera info shows, and which others the file has, so that a user can pick one with --camera. */
static void camera_choice(const cli_options *o, const bg_scenefile_result *file, char *text, size_t size)
{
    int n = file->file_cameras;
    const cli_model_options *m = &o->model;
    const char *changed = m->has_look_from || m->has_look_at || m->fov || m->has_aperture || m->has_focus_distance
                              ? ", changed by --look-from/--look-at/--fov/--aperture/--focus-distance"
                              : "";
    size_t len = strlen(o->scene);
    bool json = len >= 5 && strcasecmp(o->scene + len - 5, ".json") == 0;
    if (json)
        snprintf(text, size, " (%s%s)", file->camera_from_file ? "the file's" : "the default camera", changed);
    else if (file->camera_number > 0)
        snprintf(text, size, " (the file's camera %d of %d%s)", file->camera_number, n, changed);
    else if (n == 1)
        snprintf(text, size, " (framing the bounds; the file has 1 camera: --camera 1%s)", changed);
    else if (n > 1)
        snprintf(text, size, " (framing the bounds; the file has %d cameras: --camera 1 .. %d%s)", n, n, changed);
    else
        snprintf(text, size, " (framing the bounds; the file has no camera%s)", changed);
}

int cli_info(int argc, char **argv)
{
    cli_options o;
    char why[1024];
    if (!cli_options_parse(argc, argv, CLI_COMMAND_INFO, &o, why, sizeof why)) {
        fprintf(stderr, "betelgeuse info: %s\n(see betelgeuse --help)\n", why);
        return CLI_EXIT_USAGE;
    }
    cli_load_logs logs = {false, o.strict, 0};
    bg_scene *scene = NULL;
    bg_scenefile_result file;
    int loaded = cli_scene_load(o.scene, &o.model, &logs, NULL, &scene, &file, NULL, 0);
    if (loaded != CLI_EXIT_OK)
        return loaded;
    /* The integrator render would use, so that the plan below is the one it would get. */
    if (o.integrator >= 0)
        file.settings.integrator = (bg_integrator)o.integrator;
    const bg_scenefile_summary *s = &file.summary;
    printf("scene      %s\n", o.scene);
    printf("image      %dx%d, %d sample%s per pixel\n", file.image.width, file.image.height, file.image.samples,
           file.image.samples == 1 ? "" : "s");
    printf("objects    %zu (%zu meshes: %llu triangles, %llu vertices)\n", s->objects, s->meshes,
           (unsigned long long)s->triangles, (unsigned long long)s->vertices);
    /* A JSON scene without "lights" has none (an environment may light it); a model file gets one. */
    printf("lights     %zu%s\n", s->lights, file.lights_from_file || s->lights == 0 ? "" : " (the default light)");
    printf("materials  %zu, textures %zu\n", s->materials, s->textures);
    printf("integrator %s, max_depth %d\n",
           file.settings.integrator == BG_INTEGRATOR_PATH
               ? (file.settings.path_ambient ? "path, with the ambient term" : "path")
               : "whitted",
           file.settings.max_depth);
    if (s->bounded)
        printf("bounds     (%g, %g, %g) .. (%g, %g, %g)%s\n", s->bounds_min.x, s->bounds_min.y, s->bounds_min.z,
               s->bounds_max.x, s->bounds_max.y, s->bounds_max.z, s->unbounded ? ", and unbounded planes" : "");
    else
        printf("bounds     %s\n", s->unbounded ? "unbounded (planes only)" : "none (empty)");
    char which[192];
    camera_choice(&o, &file, which, sizeof which);
    char projection[96];
    if (file.camera.projection == BG_PROJECTION_ORTHOGRAPHIC)
        snprintf(projection, sizeof projection, "orthographic, half_height %g", file.camera.half_height);
    else
        snprintf(projection, sizeof projection, "fov_y %g degrees", file.camera.fov_y_degrees);
    printf("camera     (%g, %g, %g) looking at (%g, %g, %g), %s%s\n", file.camera.position.x, file.camera.position.y,
           file.camera.position.z, file.camera.look_at.x, file.camera.look_at.y, file.camera.look_at.z, projection,
           which);
    /* Only a lens is worth a line: a pinhole's focus distance changes nothing. */
    if (file.camera.aperture_radius > 0) {
        if (file.camera.focus_distance > 0)
            printf("lens       aperture radius %g, in focus at distance %g\n", file.camera.aperture_radius,
                   file.camera.focus_distance);
        else
            printf("lens       aperture radius %g, in focus at the point looked at\n", file.camera.aperture_radius);
    }
    /* The plan is the GPU renderer's choice for this scene and these settings: one pixel shows it. */
    if (o.renderer == CLI_RENDERER_GPU) {
        gpu g;
        if (!gpu_open(o.backend, &g, why, sizeof why)) {
            printf("GPU plan   unknown: no GPU context (%s)\n", why);
        } else {
            unsigned char pixel[4];
            bg_image one = {1, 1, BG_PIXEL_RGBA8, 0, pixel};
            bg_render_settings set = file.settings;
            set.frame_width = file.image.width;
            set.frame_height = file.image.height;
            bg_status st = bg_render_gpu(g.renderer, scene, &set, &one);
            bg_render_stats stats;
            bg_renderer_get_stats(g.renderer, &stats);
            if (st == BG_OK) {
                printf("GPU plan   %s\n", cli_plan_name(stats.plan));
                printf("GPU memory %.1f MiB of scene textures (%llu bytes)\n", (double)stats.texture_bytes / 1048576.0,
                       (unsigned long long)stats.texture_bytes);
            }
            else
                printf("GPU plan   none: %s\n", bg_renderer_error_message(g.renderer));
            gpu_close(&g);
        }
    }
    bg_scene_destroy(scene);
    return CLI_EXIT_OK;
}
