/* Renders the paper's figure 1, an earth-textured sphere lit by two point lights (SCENE_PAPER_EARTH),
 * on the GPU through a headless OpenGL 2.1 context, and writes it as a PNG.
 *
 * Usage: bg_earth [out.png [size]]   (-h, --help: the usage)
 *   out.png     default bg_earth.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * Example: make examples && build/release/examples/bg_earth /tmp/bg_earth.png 1024
 * The scene comes from examples/scenes and the calls from gpu_example.c; standalone_gpu.c shows
 * every call of a GPU render in one file, built against the installed library alone.
 */
#include "scenes/gpu_example.h"

int main(int argc, char **argv)
{
    return gpu_example_main(argc, argv, "bg_earth",
                            "Ray traces the paper's figure 1 on the GPU: "
                            "an earth-textured sphere lit by two point lights.",
                            SCENE_PAPER_EARTH);
}
