/* `betelgeuse view` (docs/command.md): the viewer's state and the actions that change it. Every input,
 * the mouse and keys of the window (view_input.c) and the lines of a --script (view_script.c) alike,
 * becomes one of these actions; the main loop (view.c) only renders and shows what the state asks for. */
#ifndef CLI_VIEW_H
#define CLI_VIEW_H

#include <stdbool.h>
#include <stdint.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"
#include "macs.h"
#include "inputs.h"
#include "options.h"
#include "view_frames.h"
#include "view_resolution.h"
#include "view_watch.h"

/* The viewer counts a frame as moving while an input came in the last MOVING_SECONDS. */
#define VIEW_MOVING_SECONDS 0.1

typedef enum view_action_kind {
    VIEW_ORBIT,      /* dx, dy pixels about look_at */
    VIEW_PAN,        /* dx, dy pixels across the view */
    VIEW_DOLLY,      /* dy steps towards look_at (a wheel notch is one) */
    VIEW_FRAME,      /* frame the scene's bounds */
    VIEW_RESET,      /* back to the camera the file gave */
    VIEW_SCREENSHOT, /* save the shown frame: path, or NULL for the next free betelgeuse-view-N.png */
    VIEW_INTEGRATOR, /* switch between the Whitted and the path integrator; the samples start again */
    VIEW_QUIT
} view_action_kind;

typedef struct view_action {
    view_action_kind kind;
    double dx, dy;
    const char *path;
} view_action;

typedef enum view_button { VIEW_BUTTON_LEFT = 0, VIEW_BUTTON_RIGHT, VIEW_BUTTON_MIDDLE, VIEW_BUTTON_COUNT_ } view_button;

/* The drag state: which buttons are held and where the pointer was. */
typedef struct view_pointer {
    bool held[VIEW_BUTTON_COUNT_];
    double x, y;
} view_pointer;

/* Frame times kept for --benchmark and the script's report. */
typedef struct view_times {
    double *ms;
    int *divisors;
    int count, capacity;
} view_times;

typedef struct viewer {
    const cli_options *options;
    void *window; /* the GLFWwindow */
    int window_width, window_height;
    view_pointer pointer;
    view_frames frames;
    /* The scene, and the camera the viewer shows it from. */
    bg_scene *scene;
    bg_scenefile_result file;
    cli_inputs inputs;     /* the files it was read from: a screenshot never replaces one */
    view_watch watch;      /* the same files, watched for edits */
    bg_camera camera, loaded;
    bool camera_changed;   /* camera differs from what the scene holds */
    int width, height;     /* the full frame */
    int samples;           /* N: the samples at rest */
    bg_render_settings settings;
    /* What the loop does next. */
    double last_input;     /* when the last action came (seconds, cli_now) */
    int divisor;           /* the moving frames' resolution (view_resolution.h) */
    view_resolution resolution; /* what the rule has measured */
    bool quit;
    bool screenshot_wanted;
    char screenshot_path[1024]; /* "" for the next numbered one */
    bool redraw;           /* show the current frame again (the window was uncovered) */
    bool check_files;      /* look at the scene's files now (the script just edited one) */
    bool render_failed;    /* the last render failed: none again until the camera or the scene changes */
    double target_ms;      /* the moving frames' time to hold (--frame-ms) */
    char error[1024];      /* the last render or reload error, shown in the title ("" if none) */
    bool error_of_render;  /* error is a render's: the next frame that renders clears it (a reload's
                              stays until a good edit) */
    int exit_code;
    /* Counts, for the title, the script's report and --benchmark. */
    double last_frame_ms;
    long frames_moving, frames_rest, frames_rest_after_n;
    uint64_t compiled_mark; /* macs_context_programs_compiled at the last expect-compiled */
    double rest_started, rest_reached; /* when the last rest began and when it held N samples (0: not yet) */
    view_times moving_times;
    int reloads, reload_errors;
} viewer;

/* Applies one action to the state (view_actions.c); the next loop turn renders what it asks for. */
void view_act(viewer *v, const view_action *a);

/* True while the frame is a moving one. */
bool view_moving(const viewer *v, double now);

/* True when the shown frame holds all N samples and the camera rests. */
bool view_at_rest_done(const viewer *v, double now);

/* Reloads the scene after an edit (view_reload.c): a good file replaces the scene, a bad one keeps the
 * last good scene and image and puts the message in v->error (it is printed as render prints it). */
void view_reload(viewer *v);

/* Saves the shown frame as a PNG at path (view_screenshot.c), as render writes its images; false with
 * the reason. */
bool view_screenshot(viewer *v, const char *path, char *why, size_t why_size);

#endif
