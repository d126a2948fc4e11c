/* The body shared by the GPU examples (bg_earth, bg_earth_shadow, bg_glass, bg_bunny): parse the command line,
 * create a headless GL context, a MACS context and a renderer, build a shared scene, render it on the
 * GPU and write a PNG. */
#ifndef GPU_EXAMPLE_H
#define GPU_EXAMPLE_H

#include "scenes.h"

/* Runs "<name> [out.png [size]]" (example_args.h) for one shared scene with the default render
 * settings: writes <name>.png in the current folder unless a path is given, size x size pixels
 * (default 512). what is the line --help prints about the image. Returns the process exit status:
 * 0 on success and after --help, 1 when something failed (the reason goes to stderr), 2 for a bad
 * command line. */
int gpu_example_main(int argc, char **argv, const char *name, const char *what, scene_id id);

/* Fills and commits a new scene for gpu_example_run; the reason for a failure goes to stderr or
 * to the scene's error. */
typedef bg_status (*gpu_example_build_fn)(bg_scene *scene, void *user);

/* The same for a scene of the example's own, built by build(scene, user). */
int gpu_example_run(int argc, char **argv, const char *name, const char *what, gpu_example_build_fn build,
                    void *user);

#endif
