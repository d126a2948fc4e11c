/* The "diffuse spheres" scaling scene: N small Lambertian spheres filling a fixed cube in front of
 * the camera, lit by two point lights that make them shadow each other. Nothing in it can bounce,
 * so max_depth does nothing and the work per pixel is the camera ray and two shadow rays: what grows
 * with N is only the search for the nearest (and any occluding) sphere, i.e. the object tree. */
#ifndef DIFFUSE_SPHERES_H
#define DIFFUSE_SPHERES_H

#include "betelgeuse.h"

/* The largest N the builder takes (its grid side stays far below int range). */
#define DIFFUSE_SPHERES_MAX (1 << 20)

/* Fills an empty scene with n spheres (1 .. DIFFUSE_SPHERES_MAX), four shared materials, two lights
 * and a camera, without committing: the caller times the first commit, which builds the object
 * tree. Deterministic: the same n gives the same scene on every machine. */
bg_status diffuse_spheres_build(bg_scene *scene, int n);

#endif
