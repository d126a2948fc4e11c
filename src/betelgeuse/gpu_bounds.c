/* dmax per bounce level and the screen rectangles of bounded objects (DESIGN.md section 4).
 *
 * Depth is t / dmax, so dmax must hold every hit the depth test has to keep, and be no larger than
 * that, since the depth step is dmax / 2^24. Level k's rays start in a region R_k (the camera for
 * k = 0); a bounded object is reached within the farthest distance between R_k and the bounds B of
 * all bounded objects. Planes are unbounded: they are cut where the remaining sliver is thinner
 * than a quarter pixel seen from the camera (a factor 2 max(W, H) / tan(half fov) on the distance
 * to the plane). With planes, hit points (and so the next level's origins) can lie anywhere on them
 * within dmax of R_k, so R_{k+1} is B grown by that reach. */
#include <math.h>
#include <string.h>

#include "gpu_internal.h"

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

/* Largest distance from a corner of box to the plane of object. */
static double plane_reach(const bg_object_data *plane, const box3 *box)
{
    const double(*m)[4] = plane->to_world;
    const double(*nm)[3] = plane->normal_to_world;
    double n[3] = {nm[0][1], nm[1][1], nm[2][1]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0.0))
        return 0.0;
    double q[3] = {m[0][3], m[1][3], m[2][3]};
    double best = 0.0;
    for (int c = 0; c < 8; c++) {
        double p[3] = {(c & 1) ? box->hi[0] : box->lo[0], (c & 2) ? box->hi[1] : box->lo[1],
                       (c & 4) ? box->hi[2] : box->lo[2]};
        double d = fabs((p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] + (p[2] - q[2]) * n[2]) / len;
        best = d > best ? d : best;
    }
    return best;
}

void gpu_dmax_levels(const bg_scene_state *state, const bg_render_settings *settings, int width, int height,
                     double *dmax)
{
    int levels = settings->max_depth + 1;
    if (settings->dmax > 0.0) {
        for (int k = 0; k < levels; k++)
            dmax[k] = settings->dmax;
        return;
    }
    const double *e = &state->camera.camera.position.x;
    box3 region = {{e[0], e[1], e[2]}, {e[0], e[1], e[2]}};
    box3 bounds;
    memcpy(bounds.lo, state->bounds_min, sizeof bounds.lo);
    memcpy(bounds.hi, state->bounds_max, sizeof bounds.hi);
    bool planes = false;
    for (uint32_t i = 0; i < state->object_count; i++)
        planes |= !state->objects[i].bounded;
    double aspect = (double)width / (double)height;
    double tan_min = state->camera.tan_half_fov_y * (aspect < 1.0 ? aspect : 1.0);
    double side = width > height ? width : height;
    double cut = 2.0 * side / tan_min;

    for (int k = 0; k < levels; k++) {
        double d = state->has_bounded_objects ? box_reach(&region, &bounds) : 0.0;
        for (uint32_t i = 0; i < state->object_count; i++) {
            if (state->objects[i].bounded)
                continue;
            double p = cut * plane_reach(&state->objects[i], k == 0 ? &region : (state->has_bounded_objects ? &bounds : &region));
            d = p > d ? p : d;
        }
        /* Nothing to reach (an empty scene): any positive value works. */
        dmax[k] = d > 0.0 ? d : 1.0;
        if (k + 1 < levels) {
            box3 next = state->has_bounded_objects ? bounds : region;
            if (planes) {
                for (int i = 0; i < 3; i++) {
                    double lo = region.lo[i] - dmax[k], hi = region.hi[i] + dmax[k];
                    next.lo[i] = next.lo[i] < lo ? next.lo[i] : lo;
                    next.hi[i] = next.hi[i] > hi ? next.hi[i] : hi;
                }
            }
            region = next;
        }
    }
}

bool gpu_object_scissor(const bg_scene_state *state, uint32_t object, int width, int height, int rect[4])
{
    const bg_object_data *o = &state->objects[object];
    if (!o->bounded)
        return false;
    const bg_camera_data *cam = &state->camera;
    const double *e = &cam->camera.position.x;
    double aspect = (double)width / (double)height;
    double tx = aspect * cam->tan_half_fov_y, ty = cam->tan_half_fov_y;
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (int c = 0; c < 8; c++) {
        double p[3] = {(c & 1) ? o->bounds_max[0] : o->bounds_min[0], (c & 2) ? o->bounds_max[1] : o->bounds_min[1],
                       (c & 4) ? o->bounds_max[2] : o->bounds_min[2]};
        double v[3] = {p[0] - e[0], p[1] - e[1], p[2] - e[2]};
        double z = v[0] * cam->forward[0] + v[1] * cam->forward[1] + v[2] * cam->forward[2];
        /* A corner at or behind the camera plane projects without bound: no rectangle. */
        if (!(z > 1e-9 * (fabs(v[0]) + fabs(v[1]) + fabs(v[2]))))
            return false;
        double sx = (v[0] * cam->right[0] + v[1] * cam->right[1] + v[2] * cam->right[2]) / z;
        double sy = (v[0] * cam->up[0] + v[1] * cam->up[1] + v[2] * cam->up[2]) / z;
        /* Pixel centre x + 0.5 = (sx / tx + 1) W / 2; GL rows count from the bottom the same way. */
        double px = (sx / tx + 1.0) * 0.5 * width, py = (sy / ty + 1.0) * 0.5 * height;
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
