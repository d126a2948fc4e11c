/* Renders the paper's second scene (an earth-textured sphere in front of a white plane, two point
 * lights) with the CPU reference renderer and writes it as a PNG.
 *
 * Usage: bg_cpu_earth [out.png [size]]   (-h, --help: the usage)
 *   out.png     default bg_cpu_earth.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * The scene comes from examples/scenes; standalone_cpu.c builds its own with the scene API, against
 * the installed library alone.
 */
#include <stdio.h>
#include <stdlib.h>

#include "betelgeuse.h"
#include "scenes/example_args.h"
#include "scenes/scenes.h"

int main(int argc, char **argv)
{
    example_args args;
    int exit_now = example_args_parse(argc, argv, "bg_cpu_earth",
                                      "Ray traces the paper's figure 2 (an earth-textured sphere casting its "
                                      "shadow on a white plane) with the CPU reference renderer.",
                                      &args);
    if (exit_now >= 0)
        return exit_now;
    const char *path = args.path;
    int size = args.size;

    bg_scene *scene = NULL;
    bg_status st = bg_scene_create(NULL, &scene);
    if (st != BG_OK) {
        fprintf(stderr, "bg_cpu_earth: %s\n", bg_status_string(st));
        return 1;
    }
    st = scenes_build(SCENE_PAPER_EARTH_SHADOW, scene);
    unsigned char *pixels = NULL;
    if (st == BG_OK) {
        pixels = malloc((size_t)size * (size_t)size * 4);
        if (!pixels) {
            fprintf(stderr, "bg_cpu_earth: out of memory\n");
            bg_scene_destroy(scene);
            return 1;
        }
        bg_image image = {size, size, BG_PIXEL_RGBA8, 0, pixels};
        bg_render_settings settings = bg_render_settings_init();
        st = bg_render_cpu(scene, &settings, &image);
        if (st == BG_OK) {
            char message[256];
            st = bg_png_save(path, &image, message, sizeof message);
            if (st != BG_OK)
                fprintf(stderr, "bg_cpu_earth: %s\n", message);
        }
    }
    if (st != BG_OK && bg_scene_error(scene) != BG_OK)
        fprintf(stderr, "bg_cpu_earth: %s\n", bg_scene_error_message(scene));
    free(pixels);
    bg_scene_destroy(scene);
    if (st != BG_OK)
        return 1;
    printf("wrote %s (%dx%d)\n", path, size, size);
    return 0;
}
