/* The loaded scene's summary: counts, and the world box of the bounded objects (each analytic
 * shape's prototype box under its transform, each mesh vertex placed). */
#include "scenefile_internal.h"

#include <math.h>

void bgi_sf_summary_reset(bg_scenefile_summary *s)
{
    *s = (bg_scenefile_summary){0};
    s->bounds_min = bg_vec3_make(INFINITY, INFINITY, INFINITY);
    s->bounds_max = bg_vec3_make(-INFINITY, -INFINITY, -INFINITY);
}

void bgi_sf_summary_point(bg_scenefile_summary *s, bg_mat4 m, double x, double y, double z)
{
    double p[3];
    for (int r = 0; r < 3; r++)
        p[r] = m.m[r][0] * x + m.m[r][1] * y + m.m[r][2] * z + m.m[r][3];
    s->bounds_min = bg_vec3_make(fmin(s->bounds_min.x, p[0]), fmin(s->bounds_min.y, p[1]), fmin(s->bounds_min.z, p[2]));
    s->bounds_max = bg_vec3_make(fmax(s->bounds_max.x, p[0]), fmax(s->bounds_max.y, p[1]), fmax(s->bounds_max.z, p[2]));
    s->bounded = true;
}

void bgi_sf_summary_shape(bg_scenefile_summary *s, bg_shape shape, bg_mat4 m)
{
    if (shape == BG_SHAPE_PLANE) {
        s->unbounded = true;
        return;
    }
    /* The prototypes lie in [-1, 1]^3 (the rectangle in y = 0): the corners' images bound them. */
    double ylo = shape == BG_SHAPE_RECTANGLE ? 0.0 : -1.0, yhi = shape == BG_SHAPE_RECTANGLE ? 0.0 : 1.0;
    for (int c = 0; c < 8; c++)
        bgi_sf_summary_point(s, m, c & 1 ? 1.0 : -1.0, c & 2 ? yhi : ylo, c & 4 ? 1.0 : -1.0);
}
