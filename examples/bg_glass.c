/* Renders a glass sphere and a mirror sphere over a checkered plane (SCENE_GLASS), reflection and
 * refraction traced to the default 5 bounce levels, on the GPU through a headless OpenGL 2.1 context,
 * and writes it as a PNG.
 *
 * Usage: bg_glass [output.png [size]]
 *   output.png  default bg_glass.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * Example: make examples && build/release/examples/bg_glass /tmp/bg_glass.png 1024
 */
#include "scenes/gpu_example.h"

int main(int argc, char **argv)
{
    return gpu_example_main(argc, argv, "bg_glass", SCENE_GLASS);
}
