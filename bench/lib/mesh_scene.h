/* The scene the mesh benchmarks time a mesh in (bench_mesh, bench_lean_walk): the mesh in a white
 * diffuse material under two point lights with shadows, seen by the caller's camera. */
#ifndef BENCH_MESH_SCENE_H
#define BENCH_MESH_SCENE_H

#include "betelgeuse.h"
#include "scenes/meshes.h"

/* Adds the material, the mesh, the two lights and sets the camera; the caller commits. */
bg_status bench_mesh_scene(bg_scene *scene, const mesh *m, const bg_camera *camera);

#endif
