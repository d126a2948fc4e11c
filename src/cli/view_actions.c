/* The viewer's actions (view.h): each changes the state only; the loop renders what it asks for, so
 * that an action that comes in the middle of a render (the progress callback polls the window) is as
 * safe as one between frames. */
#include "view.h"

#include <stdio.h>

#include "progress.h"
#include "view_camera.h"

void view_act(viewer *v, const view_action *a)
{
    switch (a->kind) {
    case VIEW_ORBIT:
        view_camera_orbit(&v->camera, a->dx, a->dy, v->window_height);
        break;
    case VIEW_PAN:
        view_camera_pan(&v->camera, a->dx, a->dy, v->window_height);
        break;
    case VIEW_DOLLY:
        view_camera_dolly(&v->camera, a->dy);
        break;
    case VIEW_FRAME:
        if (!view_camera_frame(&v->camera, &v->file.summary, (double)v->width / v->height))
            return; /* planes only: nothing to frame, nothing moved */
        break;
    case VIEW_RESET:
        v->camera = v->loaded;
        break;
    case VIEW_SCREENSHOT:
        v->screenshot_wanted = true;
        snprintf(v->screenshot_path, sizeof v->screenshot_path, "%s", a->path ? a->path : "");
        return;
    case VIEW_QUIT:
        v->quit = true;
        return;
    case VIEW_INTEGRATOR:
        v->settings.integrator =
            v->settings.integrator == BG_INTEGRATOR_PATH ? BG_INTEGRATOR_WHITTED : BG_INTEGRATOR_PATH;
        /* The frame starts again as after a move (the loop restarts the samples and cancels a render
           in progress), but at rest: nothing moved, so no reduced frames come first. */
        v->camera_changed = true;
        return;
    }
    v->camera_changed = true;
    v->last_input = cli_now();
}

bool view_moving(const viewer *v, double now)
{
    return v->last_input > 0 && now - v->last_input < VIEW_MOVING_SECONDS;
}

bool view_at_rest_done(const viewer *v, double now)
{
    return !view_moving(v, now) && !v->camera_changed && v->frames.samples >= v->samples &&
           v->frames.shown == v->frames.full;
}
