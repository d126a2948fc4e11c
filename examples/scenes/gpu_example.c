/* The shared body of the GPU examples: every object is created in order and destroyed in reverse,
 * on success and on every failure alike. */
#include "gpu_example.h"

#include "example_args.h"

#include <stdio.h>
#include <stdlib.h>

/* Everything one run owns; zero means "not created yet". */
typedef struct example {
    const char *name;
    macs_headless *headless;
    macs_context *context;
    bg_renderer *renderer;
    bg_scene *scene;
    unsigned char *pixels;
} example;

static void example_free(example *e)
{
    free(e->pixels);
    bg_scene_destroy(e->scene);
    bg_renderer_destroy(e->renderer); /* before the MACS context that holds its GPU objects */
    macs_context_destroy(e->context);
    macs_headless_destroy(e->headless);
}

/* Prints a failed bg_* call with every message that may explain it. */
static void report_bg(const example *e, const char *what, bg_status st)
{
    fprintf(stderr, "%s: %s: %s\n", e->name, what, bg_status_string(st));
    if (e->renderer && bg_renderer_error(e->renderer) != BG_OK)
        fprintf(stderr, "%s: renderer: %s\n", e->name, bg_renderer_error_message(e->renderer));
    if (e->scene && bg_scene_error(e->scene) != BG_OK)
        fprintf(stderr, "%s: scene: %s\n", e->name, bg_scene_error_message(e->scene));
    if (e->context && macs_context_error(e->context) != MACS_OK)
        fprintf(stderr, "%s: MACS: %s\n", e->name, macs_context_error_message(e->context));
}

/* Creates everything and renders into e->pixels; false after printing why it failed. */
static bool example_render(example *e, gpu_example_build_fn build, void *user, int size)
{
    char message[1024];
    macs_status ms = macs_headless_create(NULL, &e->headless, message, sizeof message);
    if (ms != MACS_OK) {
        fprintf(stderr, "%s: headless OpenGL context: %s: %s\n", e->name, macs_status_string(ms), message);
        return false;
    }
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(e->headless);
    cd.get_proc_address_user = macs_headless_proc_user(e->headless);
    ms = macs_context_create(&cd, &e->context, message, sizeof message);
    if (ms != MACS_OK) {
        fprintf(stderr, "%s: MACS context: %s: %s\n", e->name, macs_status_string(ms), message);
        return false;
    }
    bg_renderer_desc rd = {0};
    rd.context = e->context;
    bg_status st = bg_renderer_create(&rd, &e->renderer, message, sizeof message);
    if (st != BG_OK) {
        fprintf(stderr, "%s: renderer: %s: %s\n", e->name, bg_status_string(st), message);
        return false;
    }
    st = bg_scene_create(NULL, &e->scene);
    if (st == BG_OK)
        st = build(e->scene, user);
    if (st != BG_OK) {
        report_bg(e, "building the scene", st);
        return false;
    }
    e->pixels = malloc((size_t)size * (size_t)size * 4);
    if (!e->pixels) {
        fprintf(stderr, "%s: out of memory for a %dx%d image\n", e->name, size, size);
        return false;
    }
    bg_image image = {size, size, BG_PIXEL_RGBA8, 0, e->pixels};
    bg_render_settings settings = bg_render_settings_init();
    st = bg_render_gpu(e->renderer, e->scene, &settings, &image);
    if (st != BG_OK) {
        report_bg(e, "rendering", st);
        return false;
    }
    return true;
}

int gpu_example_run(int argc, char **argv, const char *name, const char *what, gpu_example_build_fn build,
                    void *user)
{
    example_args args;
    int exit_now = example_args_parse(argc, argv, name, what, &args);
    if (exit_now >= 0)
        return exit_now;
    const char *path = args.path;
    int size = args.size;

    example e = {name, NULL, NULL, NULL, NULL, NULL};
    bool ok = example_render(&e, build, user, size);
    if (ok) {
        char message[512];
        bg_image image = {size, size, BG_PIXEL_RGBA8, 0, e.pixels};
        bg_status st = bg_png_save(path, &image, message, sizeof message);
        if (st != BG_OK) {
            fprintf(stderr, "%s: writing %s: %s: %s\n", name, path, bg_status_string(st), message);
            ok = false;
        }
    }
    example_free(&e);
    if (!ok)
        return 1;
    printf("wrote %s (%dx%d)\n", path, size, size);
    return 0;
}

static bg_status build_shared(bg_scene *scene, void *user)
{
    return scenes_build(*(const scene_id *)user, scene);
}

int gpu_example_main(int argc, char **argv, const char *name, const char *what, scene_id id)
{
    return gpu_example_run(argc, argv, name, what, build_shared, &id);
}
