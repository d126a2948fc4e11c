/* Renders the Stanford bunny (a 3674-triangle mesh, examples/scenes/bunny_scene.h) on a white floor,
 * lit by two point lights with shadows, on the GPU through a headless OpenGL 2.1 context (the mesh
 * walked from float textures in the fused tree plan), and writes it as a PNG.
 *
 * Usage: bg_bunny [out.png [size]]   (-h, --help: the usage)
 *   out.png     default bg_bunny.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * The mesh is read from $BG_BUNNY, or tests/data/bunny.ply under the current folder.
 */
#include "scenes/bunny_scene.h"
#include "scenes/gpu_example.h"

static bg_status build(bg_scene *scene, void *user)
{
    (void)user;
    return bunny_scene_build(scene, "bg_bunny");
}

int main(int argc, char **argv)
{
    return gpu_example_run(argc, argv, "bg_bunny",
                           "Ray traces the Stanford bunny (a 3674-triangle mesh) on a white floor on the GPU.",
                           build, NULL);
}
