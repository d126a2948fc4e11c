/* The "diffuse spheres" scaling scene: N small Lambertian spheres filling a fixed square or cube in
 * front of the camera, lit by two point lights that make them shadow each other. Nothing in it can bounce,
 * so max_depth does nothing and the work per pixel is the camera ray and two shadow rays: what grows
 * with N is only the search for the nearest (and any occluding) sphere, i.e. the object tree. */
#ifndef DIFFUSE_SPHERES_H
#define DIFFUSE_SPHERES_H

#include "betelgeuse.h"

/* The largest N the builder takes (its grid side stays far below int range). */
#define DIFFUSE_SPHERES_MAX (1 << 20)

/* How the spheres fill space. In a layer (a square grid facing the camera, one sphere deep) a ray
 * meets about as many spheres at every N, so what grows with N is the depth of the object tree
 * alone: the series that shows how a tracer's cost follows log N. In a cloud (a cubic grid) a ray
 * crossing it meets N^(1/3) layers, work that grows for every tracer whatever its tree. */
typedef enum diffuse_layout { DIFFUSE_LAYER = 0, DIFFUSE_CLOUD } diffuse_layout;

/* Fills an empty scene with n spheres (1 .. DIFFUSE_SPHERES_MAX) in the layout, four shared
 * materials, two lights and a camera, without committing: the caller times the first commit, which
 * builds the object tree. Deterministic: the same n gives the same scene on every machine. */
bg_status diffuse_spheres_build(bg_scene *scene, int n, diffuse_layout layout);

#endif
