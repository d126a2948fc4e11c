/* Closed boxes for the path integrator's tests and benchmark (docs/shading.md 13): the six walls of
 * [-1, 1]^3 as thin rectangles, each a little larger than the box, so that no ray leaves through an
 * edge. Deterministic; every builder commits the scene. */
#ifndef PATH_BOX_H
#define PATH_BOX_H

#include "betelgeuse.h"

/* Adds the rectangle c + [0, 1] u + [0, 1] v of material mat (its front on the side of u x v). */
bg_status path_box_wall(bg_scene *s, bg_vec3 c, bg_vec3 u, bg_vec3 v, uint32_t mat);
/* Adds the six walls: the one at x = -1 of material left, at x = +1 of right, the others of rest. */
bg_status path_box_walls(bg_scene *s, uint32_t left, uint32_t right, uint32_t rest);
/* A Cornell-like box in an empty scene without ambient light: a red left wall, a green right one,
 * white others (Lambertian, r = 1), a visible rectangle light of 0.6 x 0.6 under the ceiling facing
 * down, a white sphere on the floor, and the camera at the front wall looking in and a little up
 * (75 degrees), so that the panel is in view. */
bg_status path_box_cornell(bg_scene *s);
/* A box of white Lambertian walls (C = 1, r = 1) that emit e, the camera inside: the path
 * integrator's exact case (every pixel e (max_depth + 1)). */
bg_status path_box_white(bg_scene *s, double e);

#endif
