/* The viewer's camera moves (view_camera.h). Each keeps look_at - position away from up, the one
 * thing bg_scene_set_camera refuses, so that no drag can produce a camera the scene rejects. */
#include "view_camera.h"

#include <math.h>

#define PI 3.14159265358979323846

static bg_vec3 add(bg_vec3 a, bg_vec3 b) { return bg_vec3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
static bg_vec3 sub(bg_vec3 a, bg_vec3 b) { return bg_vec3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
static bg_vec3 scale(bg_vec3 a, double s) { return bg_vec3_make(a.x * s, a.y * s, a.z * s); }
static double dot(bg_vec3 a, bg_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static bg_vec3 cross(bg_vec3 a, bg_vec3 b)
{
    return bg_vec3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static bg_vec3 unit(bg_vec3 a)
{
    double n = sqrt(dot(a, a));
    return n > 0 ? scale(a, 1.0 / n) : a;
}

/* v turned by angle about the unit axis k (Rodrigues' formula). */
static bg_vec3 rotate(bg_vec3 v, bg_vec3 k, double angle)
{
    double c = cos(angle), s = sin(angle);
    return add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1 - c)));
}

void view_camera_orbit(bg_camera *c, double dx, double dy, int window_height)
{
    bg_vec3 up = unit(c->up), offset = sub(c->position, c->look_at);
    double per_pixel = PI / (window_height > 0 ? 1.333 * window_height : 480);
    offset = rotate(offset, up, -dx * per_pixel);
    /* Pitch: the angle from up stays within [1, 179] degrees. */
    double r = sqrt(dot(offset, offset));
    double from_up = acos(fmax(-1.0, fmin(1.0, dot(offset, up) / r)));
    double limit = PI / 180.0;
    double pitch = -dy * per_pixel;
    double target = fmax(limit, fmin(PI - limit, from_up + pitch));
    bg_vec3 right = unit(cross(up, offset));
    if (dot(right, right) > 0)
        offset = rotate(offset, right, target - from_up);
    c->position = add(c->look_at, offset);
}

void view_camera_pan(bg_camera *c, double dx, double dy, int window_height)
{
    bg_vec3 forward = sub(c->look_at, c->position);
    double distance = sqrt(dot(forward, forward));
    forward = scale(forward, 1.0 / distance);
    bg_vec3 right = unit(cross(forward, c->up)), up = cross(right, forward);
    /* The view's height in world units at look_at: a pixel there moves with the mouse. */
    double height = c->projection == BG_PROJECTION_ORTHOGRAPHIC ? 2.0 * c->half_height
                                                                 : 2.0 * distance * tan(0.5 * c->fov_y_degrees * PI / 180.0);
    double per_pixel = height / (window_height > 0 ? window_height : 480);
    bg_vec3 move = add(scale(right, -dx * per_pixel), scale(up, dy * per_pixel));
    c->position = add(c->position, move);
    c->look_at = add(c->look_at, move);
}

void view_camera_dolly(bg_camera *c, double steps)
{
    bg_vec3 offset = sub(c->position, c->look_at);
    double factor = pow(0.9, steps);
    /* A camera on look_at would be refused: the distance only shrinks geometrically. */
    if (!(factor > 1e-6))
        factor = 1e-6;
    if (c->projection == BG_PROJECTION_ORTHOGRAPHIC) {
        /* Moving a parallel view changes nothing it shows: the wheel narrows the view instead, kept
         * inside the half-heights the scene takes. */
        double h = c->half_height * factor;
        c->half_height = h < 1e-90 ? 1e-90 : h > 1e90 ? 1e90 : h;
        return;
    }
    c->position = add(c->look_at, scale(offset, factor));
}

bool view_camera_frame(bg_camera *c, const bg_scenefile_summary *s, double aspect)
{
    if (!s->bounded)
        return false;
    bg_vec3 centre = scale(add(s->bounds_min, s->bounds_max), 0.5);
    bg_vec3 size = sub(s->bounds_max, s->bounds_min);
    double r = 0.5 * sqrt(dot(size, size));
    if (!(r > 0) || !isfinite(r))
        r = 1.0;
    bg_vec3 back = unit(sub(c->position, c->look_at));
    double d;
    if (c->projection == BG_PROJECTION_ORTHOGRAPHIC) {
        /* The bounding sphere within both half-sides, the view plane in front of all of it. */
        c->half_height = 1.05 * r / (aspect < 1 ? aspect : 1.0);
        d = 2.0 * r;
    } else {
        double half = 0.5 * c->fov_y_degrees * PI / 180.0;
        double limit = aspect < 1 ? atan(tan(half) * aspect) : half;
        d = 1.05 * r / sin(limit);
    }
    c->look_at = centre;
    c->position = add(centre, scale(back, d));
    return true;
}
