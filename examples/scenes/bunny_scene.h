/* The bunny scene of the bunny examples (bg_bunny on the GPU, bg_cpu_bunny on the CPU): the Stanford
 * bunny (tests/data/bunny.ply, 3674 triangles) with smooth normals computed from its faces, in a
 * clay material on a white floor, two point lights with shadows. */
#ifndef BUNNY_SCENE_H
#define BUNNY_SCENE_H

#include "betelgeuse.h"

/* Where the mesh is read from: $BG_BUNNY, or tests/data/bunny.ply under the current folder (the
 * source tree's root, where the README runs the examples from). */
const char *bunny_scene_path(void);

/* Reads the mesh and fills and commits scene. On failure the reason goes to stderr after
 * "<name>: " (a file that cannot be read) or into the scene's error. */
bg_status bunny_scene_build(bg_scene *scene, const char *name);

#endif
