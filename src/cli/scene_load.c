/* The command's one scene loader (scene_load.h). */
#include "scene_load.h"

#include <stdio.h>
#include <string.h>

#include "cli.h"

/* Warnings (what a model's materials lose) unless --quiet, each counted; errors come back as messages. */
static void on_log(bg_log_level level, const char *message, void *user)
{
    cli_load_logs *logs = user;
    if (level != BG_LOG_WARNING)
        return;
    logs->warnings++;
    if (!logs->quiet)
        fprintf(stderr, "betelgeuse: warning: %s\n", message);
}

int cli_scene_load(const char *path, const cli_model_options *model, cli_load_logs *logs, cli_inputs *inputs,
                   bg_scene **out, bg_scenefile_result *file, char *why_out, size_t why_size)
{
    *out = NULL;
    bg_scene *scene = NULL;
    if (bg_scene_create(NULL, &scene) != BG_OK) {
        fprintf(stderr, "betelgeuse: out of memory creating the scene\n");
        if (why_out)
            snprintf(why_out, why_size, "out of memory creating the scene");
        return CLI_EXIT_FAILED;
    }
    bg_scenefile_desc fd;
    memset(&fd, 0, sizeof fd);
    fd.logger.func = on_log;
    fd.logger.user = logs;
    cli_model_options_desc(model, &fd);
    if (inputs) {
        /* The scene file is added here too, so that it is protected whatever the library reports. */
        cli_inputs_add(inputs, path);
        fd.inputs.func = cli_inputs_on_read;
        fd.inputs.user = inputs;
    }
    char why[1024] = "";
    bg_status st = bg_scenefile_load_any(path, &fd, scene, file, why, sizeof why);
    if (st != BG_OK) {
        cli_model_options_rename(why);
        fprintf(stderr, "betelgeuse: %s\n", why[0] ? why : bg_status_string(st));
        if (why_out)
            snprintf(why_out, why_size, "%s", why[0] ? why : bg_status_string(st));
        bg_scene_destroy(scene);
        return st == BG_ERR_OUT_OF_MEMORY ? CLI_EXIT_FAILED : CLI_EXIT_USAGE;
    }
    if (logs->strict && logs->warnings > 0) {
        char message[256];
        snprintf(message, sizeof message, "%s: %d warning%s while loading, fatal under --strict", path,
                 logs->warnings, logs->warnings == 1 ? "" : "s");
        fprintf(stderr, "betelgeuse: %s\n", message);
        if (why_out)
            snprintf(why_out, why_size, "%s", message);
        bg_scene_destroy(scene);
        return CLI_EXIT_USAGE;
    }
    *out = scene;
    return CLI_EXIT_OK;
}
