/* How the viewer's mouse moves its camera (view_camera.c): orbit about the point looked at, pan
 * across the view, dolly towards the point, and a framing of the scene's bounds. Pure geometry on a
 * bg_camera; the amounts are in window pixels so that a drag feels the same at every size. */
#ifndef CLI_VIEW_CAMERA_H
#define CLI_VIEW_CAMERA_H

#include <stdbool.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"

/* Turns the position about look_at: dx pixels about the camera's up axis (a full window width is
 * half a turn), dy about its right axis, stopping 1 degree short of the poles so that the view never
 * becomes parallel to up (which bg_scene_set_camera refuses). */
void view_camera_orbit(bg_camera *c, double dx, double dy, int window_height);

/* Moves position and look_at together so that the point looked at follows the mouse: dx, dy pixels
 * of a window window_height pixels tall, at the distance of look_at. */
void view_camera_pan(bg_camera *c, double dx, double dy, int window_height);

/* Moves the position towards look_at (steps > 0) or away, by 10% of the distance a step; never
 * closer than a millionth of the distance it started at. */
void view_camera_dolly(bg_camera *c, double steps);

/* Looks at the centre of the bounds from the direction the camera looks now, far enough that their
 * bounding sphere fits the vertical field of view and, for a frame narrower than tall, the horizontal
 * one (the rule of the scene-file library's framing camera, kept to the current direction so that F
 * does not turn the view). False and c unchanged when the scene has no bounded object. */
bool view_camera_frame(bg_camera *c, const bg_scenefile_summary *s, double aspect);

#endif
