/* dmax per bounce level and the screen rectangles of bounded objects (docs/gpu_pipeline.md,
 * "Depth").
 *
 * Depth is t / (2 dmax) below dmax and 1 - dmax / (2 t) beyond it (bg_depth in bg_stage_hit.glsl):
 * one monotonic scale, linear and finest where the scene's bounded objects are, compressed beyond,
 * so planes reach the horizon instead of being cut. dmax is therefore the farthest distance from
 * where a level's rays start to the box B holding every bounded object and every plane's anchor
 * point: from the camera for camera rays (from anywhere on its lens, or on an orthographic camera's
 * view rectangle), and across B for secondary rays (which start on objects; those starting far out
 * on a plane are still right, only with coarser depth steps). */
#include <math.h>
#include <string.h>

#include "multipass.h"

typedef struct box3 {
    double lo[3], hi[3];
} box3;

static double box_reach(const box3 *from, const box3 *to)
{
    double s = 0.0;
    for (int i = 0; i < 3; i++) {
        double a = fabs(to->hi[i] - from->lo[i]), b = fabs(from->hi[i] - to->lo[i]);
        double m = a > b ? a : b;
        s += m * m;
    }
    return sqrt(s);
}

static void box_add(box3 *b, bool *empty, const double p[3])
{
    for (int i = 0; i < 3; i++) {
        b->lo[i] = *empty || p[i] < b->lo[i] ? p[i] : b->lo[i];
        b->hi[i] = *empty || p[i] > b->hi[i] ? p[i] : b->hi[i];
    }
    *empty = false;
}

void bgi_gpu_dmax_levels(const bg_scene_state *state, const bg_render_settings *settings, const gpu_view *view,
                         double *dmax)
{
    int levels = settings->max_depth + 1;
    if (settings->dmax > 0.0) {
        for (int k = 0; k < levels; k++)
            dmax[k] = settings->dmax;
        return;
    }
    const double *e = &state->camera.camera.position.x;
    /* Camera rays start anywhere on the lens, or on an orthographic view's rectangle (its half
     * diagonal bounds every start; the aspect is the settings' frame's). */
    double a = state->camera.camera.aperture_radius;
    if (state->camera.orthographic) {
        double hy = state->camera.half_y, hx = hy * view->pixels.frame_width / view->pixels.frame_height;
        a = sqrt(hx * hx + hy * hy);
    }
    box3 camera = {{e[0] - a, e[1] - a, e[2] - a}, {e[0] + a, e[1] + a, e[2] + a}};
    box3 scene = camera;
    bool empty = true;
    if (state->has_bounded_objects) {
        box_add(&scene, &empty, state->bounds_min);
        box_add(&scene, &empty, state->bounds_max);
    }
    for (uint32_t i = 0; i < state->object_count; i++) {
        if (state->objects[i].bounded)
            continue;
        const double(*m)[4] = state->objects[i].to_world;
        double anchor[3] = {m[0][3], m[1][3], m[2][3]};
        box_add(&scene, &empty, anchor);
    }
    for (int k = 0; k < levels; k++) {
        double d = empty ? 0.0 : box_reach(k == 0 ? &camera : &scene, &scene);
        /* Nothing to reach (an empty scene, or one plane through the camera): any positive value. */
        dmax[k] = d > 0.0 ? d : 1.0;
    }
}

bool bgi_gpu_object_scissor(const bg_scene_state *state, uint32_t object, const gpu_view *view, int rect[4])
{
    int frame_width = view->pixels.frame_width, frame_height = view->pixels.frame_height;
    int width = view->pixels.width, height = view->pixels.height;
    const bg_object_data *o = &state->objects[object];
    const bg_camera_data *cam = &state->camera;
    /* Through a lens, camera rays do not start at one point: no projection bounds them. */
    if (!o->bounded || cam->camera.aperture_radius > 0.0)
        return false;
    const double *e = &cam->camera.position.x;
    double aspect = (double)frame_width / (double)frame_height;
    double tx = aspect * cam->half_y, ty = cam->half_y;
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (int c = 0; c < 8; c++) {
        double p[3] = {(c & 1) ? o->bounds_max[0] : o->bounds_min[0], (c & 2) ? o->bounds_max[1] : o->bounds_min[1],
                       (c & 4) ? o->bounds_max[2] : o->bounds_min[2]};
        double v[3] = {p[0] - e[0], p[1] - e[1], p[2] - e[2]};
        double z = v[0] * cam->forward[0] + v[1] * cam->forward[1] + v[2] * cam->forward[2];
        /* A corner at or behind the camera plane projects without bound: no rectangle (parallel
         * rays project it like any other). */
        if (!cam->orthographic && !(z > 1e-9 * (fabs(v[0]) + fabs(v[1]) + fabs(v[2]))))
            return false;
        double sx = v[0] * cam->right[0] + v[1] * cam->right[1] + v[2] * cam->right[2];
        double sy = v[0] * cam->up[0] + v[1] * cam->up[1] + v[2] * cam->up[2];
        /* Parallel rays project without the division: a point's place on the view is its offset
         * across it. */
        if (!cam->orthographic) {
            sx /= z;
            sy /= z;
        }
        /* The frame's point (sx / tx + 1) W / 2 is the camera stage's gl_FragCoord + shift; GL rows count
         * from the bottom the same way. */
        double px = (sx / tx + 1.0) * 0.5 * frame_width - view->shift[0];
        double py = (sy / ty + 1.0) * 0.5 * frame_height - view->shift[1];
        xmin = px < xmin ? px : xmin;
        xmax = px > xmax ? px : xmax;
        ymin = py < ymin ? py : ymin;
        ymax = py > ymax ? py : ymax;
    }
    /* The box's projection holds every ray that meets the object; one pixel of margin absorbs the
     * float rounding of the rays themselves. */
    double x0 = floor(xmin) - 1.0, x1 = ceil(xmax) + 1.0, y0 = floor(ymin) - 1.0, y1 = ceil(ymax) + 1.0;
    x0 = x0 < 0.0 ? 0.0 : (x0 > width ? width : x0);
    y0 = y0 < 0.0 ? 0.0 : (y0 > height ? height : y0);
    x1 = x1 > width ? width : (x1 < 0.0 ? 0.0 : x1);
    y1 = y1 > height ? height : (y1 < 0.0 ? 0.0 : y1);
    rect[0] = (int)x0;
    rect[1] = (int)y0;
    rect[2] = x1 > x0 ? (int)(x1 - x0) : 0;
    rect[3] = y1 > y0 ? (int)(y1 - y0) : 0;
    return true;
}
