/* The camera stage as both plans write it (bg_stage_camera.glsl, docs/shading.md 1 and 1.5): which
 * function makes a pixel's ray, and the view's half extents it scales the window point by. A
 * perspective camera's extents are at unit distance ahead (the tangents of half its fields of view),
 * an orthographic one's in world units; the horizontal one carries the full frame's aspect ratio. */
#include "shared.h"

const char *bgi_gpu_camera_function(bool orthographic)
{
    return orthographic ? "bg_camera_ray_parallel" : "bg_camera_ray";
}

void bgi_gpu_camera_half(const bg_scene_state *state, const gpu_view *view, float out[2])
{
    double aspect = (double)view->pixels.frame_width / (double)view->pixels.frame_height;
    out[0] = (float)(aspect * state->camera.half_y);
    out[1] = (float)state->camera.half_y;
}
