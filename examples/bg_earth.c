/* Renders the paper's figure 1, an earth-textured sphere lit by two point lights (SCENE_PAPER_EARTH),
 * on the GPU through a headless OpenGL 2.1 context, and writes it as a PNG.
 *
 * Usage: bg_earth [output.png [size]]
 *   output.png  default bg_earth.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * Example: make examples && build/release/examples/bg_earth /tmp/bg_earth.png 1024
 */
#include "scenes/gpu_example.h"

int main(int argc, char **argv)
{
    return gpu_example_main(argc, argv, "bg_earth", SCENE_PAPER_EARTH);
}
