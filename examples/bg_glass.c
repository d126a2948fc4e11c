/* Renders a glass sphere and a mirror sphere over a checkered plane (SCENE_GLASS), reflection and
 * refraction traced to the default 5 bounce levels, on the GPU through a headless OpenGL 2.1 context,
 * and writes it as a PNG.
 *
 * Usage: bg_glass [out.png [size]]   (-h, --help: the usage)
 *   out.png     default bg_glass.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * Example: make examples && build/release/examples/bg_glass /tmp/bg_glass.png 1024
 * The scene comes from examples/scenes and the calls from gpu_example.c; standalone_gpu.c shows
 * every call of a GPU render in one file, built against the installed library alone.
 */
#include "scenes/gpu_example.h"

int main(int argc, char **argv)
{
    return gpu_example_main(argc, argv, "bg_glass",
                            "Ray traces mirror and glass spheres over a checkered plane on the GPU, "
                            "5 bounce levels.",
                            SCENE_GLASS);
}
