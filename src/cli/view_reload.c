/* Reloading the scene after an edit (view.h). The new file goes into a new scene, so that a bad edit
 * leaves the last good scene, its camera and its image untouched; the renderer's program cache
 * (MACS's) outlives the scene, so an edit of values (a colour, a position) compiles nothing. */
#include "view.h"

#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "scene_load.h"

static bool same_camera(const bg_camera *a, const bg_camera *b)
{
    return a->position.x == b->position.x && a->position.y == b->position.y && a->position.z == b->position.z &&
           a->look_at.x == b->look_at.x && a->look_at.y == b->look_at.y && a->look_at.z == b->look_at.z &&
           a->up.x == b->up.x && a->up.y == b->up.y && a->up.z == b->up.z && a->fov_y_degrees == b->fov_y_degrees &&
           a->aperture_radius == b->aperture_radius && a->focus_distance == b->focus_distance;
}

void view_reload(viewer *v)
{
    cli_inputs inputs;
    memset(&inputs, 0, sizeof inputs);
    cli_load_logs logs = {v->options->quiet, v->options->strict, 0};
    bg_scene *scene = NULL;
    bg_scenefile_result file;
    char why[1024] = "";
    int status = cli_scene_load(v->options->scene, &v->options->model, &logs, &inputs, &scene, &file, why, sizeof why);
    /* Watched from now on: what this load read, so that fixing the file (or the model it names) is seen. */
    if (inputs.count > 0)
        view_watch_set(&v->watch, &inputs);
    if (status != CLI_EXIT_OK) {
        snprintf(v->error, sizeof v->error, "%s", why);
        v->error_of_render = false;
        v->reload_errors++;
        cli_inputs_free(&inputs);
        return;
    }
    /* The user's view stays across edits of the scene, unless the edit changed the file's camera (its
     * lens too, so that an edited aperture shows at once). */
    if (!same_camera(&file.camera, &v->file.camera))
        v->camera = file.camera;
    v->loaded = file.camera;
    bg_scene_destroy(v->scene);
    v->scene = scene;
    int samples = v->settings.samples;
    int width = v->settings.frame_width, height = v->settings.frame_height;
    /* The integrator the user shows (--integrator, or the I key) stays too, unless the edit changed
       the file's; --max-depth still overrides the file's. */
    bg_integrator integrator =
        file.settings.integrator != v->file.settings.integrator ? file.settings.integrator : v->settings.integrator;
    v->file = file;
    v->settings = file.settings;
    v->settings.samples = samples;
    v->settings.frame_width = width;
    v->settings.frame_height = height;
    v->settings.integrator = integrator;
    if (v->options->max_depth >= 0)
        v->settings.max_depth = v->options->max_depth;
    cli_inputs_free(&v->inputs);
    v->inputs = inputs;
    v->camera_changed = true;
    v->render_failed = false;
    v->error[0] = '\0';
    v->error_of_render = false;
    v->reloads++;
    if (v->options->verbose)
        fprintf(stderr, "betelgeuse view: reloaded %s\n", v->options->scene);
}
