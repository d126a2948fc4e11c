/* `betelgeuse view` (docs/command.md): the main loop. Each turn it runs what the script has due,
 * looks at the scene's files, puts an action's camera into the scene, renders the one frame the
 * state asks for (a reduced one while moving, the next samples at rest) and shows it; with nothing
 * to render it sleeps in glfwWaitEventsTimeout until an input, the script's next command or the
 * next look at the files (four times a second: a stat per file, no measurable CPU). */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "progress.h"
#include "scene_load.h"
#include "view.h"
#include "view_display.h"
#include "view_input.h"
#include "view_report.h"
#include "view_resolution.h"
#include "view_script.h"
#include "view_window.h"

/* The samples at rest when neither --samples nor the scene asks for more than one. */
enum { VIEW_DEFAULT_SAMPLES = 64 };
/* How often the scene's files are looked at while the viewer waits. */
#define VIEW_WATCH_SECONDS 0.25

/* Renders poll the window between their passes, so that a drag that starts during a long render
 * cancels it and a closed window is seen at once. */
static bool on_progress(double fraction, void *user)
{
    (void)fraction;
    viewer *v = user;
    glfwPollEvents();
    return !v->camera_changed && !v->quit;
}

/* The title: what the viewer shows and how it got it. */
static void show_title(viewer *v, double now)
{
    char title[1400];
    const char *name = strrchr(v->options->scene, '/');
    name = name ? name + 1 : v->options->scene;
    bg_render_stats stats;
    bg_renderer_get_stats(v->frames.renderer, &stats);
    const char *plan = stats.plan ? cli_plan_name(stats.plan) : "no frame yet";
    char state[1100];
    if (v->error[0])
        snprintf(state, sizeof state, "error: %.1000s", v->error);
    else if (view_moving(v, now))
        snprintf(state, sizeof state, "moving (1/%d size)", v->divisor);
    else
        snprintf(state, sizeof state, "at rest");
    const char *integrator = v->settings.integrator == BG_INTEGRATOR_PATH ? "path" : "whitted";
    snprintf(title, sizeof title, "betelgeuse view: %s | %s | %s | %.1f ms | %d/%d samples | %s", name, plan,
             integrator, v->last_frame_ms, v->frames.samples, v->samples, state);
    glfwSetWindowTitle(v->window, title);
}

/* The viewer's camera into the scene; a camera the scene refuses (it cannot come from the moves,
 * which keep it valid) goes back to the file's. */
static void apply_camera(viewer *v)
{
    v->camera_changed = false;
    view_frames_restart(&v->frames);
    v->render_failed = false;
    if (bg_scene_set_camera(v->scene, &v->camera) != BG_OK || bg_scene_commit(v->scene) != BG_OK) {
        snprintf(v->error, sizeof v->error, "%s", bg_scene_error_message(v->scene));
        v->camera = v->loaded;
        bg_scene_set_camera(v->scene, &v->camera);
        bg_scene_commit(v->scene);
    }
}

/* One frame: reduced while moving, the next samples at rest; shown when it rendered. */
static void render_frame(viewer *v, view_display *d, bool moving)
{
    bg_render_settings settings = v->settings;
    settings.progress = on_progress;
    settings.progress_user = v;
    double start = cli_now();
    bg_status st;
    if (moving) {
        st = view_frames_moving(&v->frames, v->scene, &settings, view_resolution_side(v->width, v->divisor),
                                view_resolution_side(v->height, v->divisor));
    } else {
        if (v->frames.samples >= v->samples)
            v->frames_rest_after_n++; /* never, by the loop's rule: the report proves it */
        if (v->frames.samples == 0) {
            v->rest_started = start;
            v->rest_reached = 0;
        }
        st = view_frames_rest(&v->frames, v->scene, &settings);
    }
    if (st == BG_ERR_CANCELLED) {
        bg_renderer_clear_error(v->frames.renderer);
        return;
    }
    if (st != BG_OK) {
        /* A limit is the GPU renderer's alone (render says the same): the viewer has no other. */
        snprintf(v->error, sizeof v->error, "%s%s", bg_renderer_error_message(v->frames.renderer),
                 st == BG_ERR_LIMIT ? " (a limit of the GPU renderer: betelgeuse render --renderer cpu renders "
                                      "without it)"
                                    : "");
        v->error_of_render = true;
        fprintf(stderr, "betelgeuse view: %s\n", v->error);
        bg_renderer_clear_error(v->frames.renderer);
        v->render_failed = true;
        return;
    }
    if (v->error_of_render) {
        v->error[0] = '\0';
        v->error_of_render = false;
    }
    /* The frame's time is the render's and the display's together, up to the frame on the screen. */
    view_display_show(d, v->window, v->frames.shown, v->window_width, v->window_height);
    double ms = 1000.0 * (cli_now() - start);
    v->last_frame_ms = ms;
    if (moving) {
        v->frames_moving++;
        view_times_add(&v->moving_times, ms, v->divisor);
        v->divisor = view_resolution_next(&v->resolution, v->divisor, ms, v->target_ms);
    } else {
        v->frames_rest++;
        /* A one-sample full frame tells what a moving frame would cost: the first moving frame
         * after a rest starts at the divisor it suggests. */
        if (v->frames.samples == 1)
            v->divisor = view_resolution_next(&v->resolution, 1, ms, v->target_ms);
        if (v->frames.samples >= v->samples)
            v->rest_reached = cli_now();
    }
}

/* Whether the loop has a frame to render now. */
static bool frame_due(const viewer *v, double now, bool *moving)
{
    *moving = view_moving(v, now);
    if (*moving)
        return v->camera_changed;
    return v->camera_changed || (!v->render_failed && v->frames.samples < v->samples);
}

static void save_screenshot(viewer *v)
{
    v->screenshot_wanted = false;
    char why[1400];
    if (!view_screenshot(v, v->screenshot_path, why, sizeof why)) {
        fprintf(stderr, "betelgeuse view: screenshot: %s\n", why);
        if (v->options->script)
            v->exit_code = CLI_EXIT_FAILED;
    }
}

static void run_loop(viewer *v, view_display *d, view_script *script)
{
    double last_watch = cli_now();
    while (!v->quit) {
        double now = cli_now();
        double script_wait = -1;
        if (script) {
            script_wait = view_script_run(script, v, now);
            if (view_script_done(script) && !v->screenshot_wanted)
                v->quit = true;
        }
        if (v->screenshot_wanted)
            save_screenshot(v);
        if (v->quit)
            break;
        if (v->check_files || now - last_watch >= VIEW_WATCH_SECONDS) {
            v->check_files = false;
            last_watch = now;
            if (view_watch_changed(&v->watch))
                view_reload(v);
        }
        bool moving;
        bool due = frame_due(v, now, &moving);
        if (v->camera_changed)
            apply_camera(v);
        if (due)
            render_frame(v, d, moving);
        else if (v->redraw)
            view_display_show(d, v->window, v->frames.shown, v->window_width, v->window_height);
        v->redraw = false;
        show_title(v, cli_now());
        now = cli_now();
        if (frame_due(v, now, &moving) || script_wait == 0 || v->screenshot_wanted || v->check_files) {
            glfwPollEvents();
            continue;
        }
        /* Nothing to render: sleep until an input, the end of the moving time, the script's next
         * command or the next look at the files. */
        double timeout = VIEW_WATCH_SECONDS - (now - last_watch);
        if (moving)
            timeout = fmin(timeout, VIEW_MOVING_SECONDS - (now - v->last_input));
        if (script_wait > 0)
            timeout = fmin(timeout, script_wait);
        glfwWaitEventsTimeout(fmax(timeout, 0.001));
    }
}

/* The session's size, samples and target from the options and the scene file. */
static void plan_session(viewer *v, const cli_options *o)
{
    v->width = o->width ? o->width : v->file.image.width;
    v->height = o->height ? o->height : v->file.image.height;
    v->samples = o->samples ? o->samples : v->file.image.samples > 1 ? v->file.image.samples : VIEW_DEFAULT_SAMPLES;
    v->target_ms = o->frame_ms > 0 ? o->frame_ms : 33.0;
    v->settings = v->file.settings;
    v->settings.samples = v->samples;
    if (o->max_depth >= 0)
        v->settings.max_depth = o->max_depth;
    if (o->integrator >= 0)
        v->settings.integrator = (bg_integrator)o->integrator;
    v->settings.frame_width = v->width;
    v->settings.frame_height = v->height;
    v->camera = v->loaded = v->file.camera;
    v->divisor = 1;
}

static int view_session(viewer *v, view_script *script)
{
    char why[1400];
    if (!view_window_open(v, v->width, v->height, "betelgeuse view", why, sizeof why)) {
        fprintf(stderr, "betelgeuse view: %s\n", why);
        return CLI_EXIT_FAILED;
    }
    view_display *d = NULL;
    if (!view_display_create(&d, why, sizeof why)) {
        fprintf(stderr, "betelgeuse view: %s\n", why);
        view_window_close(v);
        return CLI_EXIT_FAILED;
    }
    if (v->options->verbose) {
        macs_gl_info info;
        macs_context_get_gl_info(v->frames.context, &info);
        fprintf(stderr, "betelgeuse view: OpenGL %s, %s\n", info.version ? info.version : "?",
                info.renderer ? info.renderer : "?");
    }
    v->compiled_mark = macs_context_programs_compiled(v->frames.context);
    view_input_attach(v);
    run_loop(v, d, script);
    view_display_destroy(d);
    view_window_close(v);
    return v->exit_code;
}

int cli_view(int argc, char **argv)
{
    cli_options o;
    char why[1400];
    if (!cli_options_parse(argc, argv, CLI_COMMAND_VIEW, &o, why, sizeof why)) {
        fprintf(stderr, "betelgeuse view: %s\n(see betelgeuse --help)\n", why);
        return CLI_EXIT_USAGE;
    }
    viewer v;
    memset(&v, 0, sizeof v);
    v.options = &o;
    view_script *script = NULL;
    if (o.script && !view_script_load(o.script, NULL, &script, why, sizeof why)) {
        fprintf(stderr, "betelgeuse view: %s\n", why);
        return CLI_EXIT_USAGE;
    }
    cli_load_logs logs = {o.quiet, o.strict, 0};
    int status = cli_scene_load(o.scene, &o.model, &logs, &v.inputs, &v.scene, &v.file, NULL, 0);
    if (status == CLI_EXIT_OK && !view_watch_set(&v.watch, &v.inputs)) {
        fprintf(stderr, "betelgeuse view: out of memory listing the scene's files\n");
        status = CLI_EXIT_FAILED;
    }
    if (status == CLI_EXIT_OK) {
        plan_session(&v, &o);
        char text[256];
        if (o.benchmark) {
            view_benchmark_script(text, sizeof text, v.width, v.height);
            if (!view_script_load("--benchmark", text, &script, why, sizeof why)) {
                fprintf(stderr, "betelgeuse view: %s\n", why);
                status = CLI_EXIT_FAILED;
            }
        }
    }
    if (status == CLI_EXIT_OK) {
        status = view_session(&v, script);
        if (o.benchmark)
            view_report_benchmark(&v);
        else if (o.script || o.verbose)
            view_report_frames(&v);
    }
    view_script_free(script);
    view_times_free(&v.moving_times);
    view_watch_free(&v.watch);
    cli_inputs_free(&v.inputs);
    bg_scene_destroy(v.scene);
    return status;
}
