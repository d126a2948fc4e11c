/* Renders the Stanford bunny (a 3674-triangle mesh, examples/scenes/bunny_scene.h) on a white floor,
 * lit by two point lights with shadows, with the CPU reference renderer, and writes it as a PNG;
 * bg_bunny renders the same scene on the GPU.
 *
 * Usage: bg_cpu_bunny [out.png [size]]   (-h, --help: the usage)
 *   out.png     default bg_cpu_bunny.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 * The mesh is read from $BG_BUNNY, or tests/data/bunny.ply under the current folder.
 */
#include <stdio.h>
#include <stdlib.h>

#include "betelgeuse.h"
#include "scenes/bunny_scene.h"
#include "scenes/example_args.h"

#define NAME "bg_cpu_bunny"

int main(int argc, char **argv)
{
    example_args args;
    int exit_now = example_args_parse(argc, argv, NAME,
                                      "Ray traces the Stanford bunny (a 3674-triangle mesh) on a white floor "
                                      "with the CPU reference renderer.",
                                      &args);
    if (exit_now >= 0)
        return exit_now;

    bg_scene *scene = NULL;
    bg_status st = bg_scene_create(NULL, &scene);
    if (st == BG_OK)
        st = bunny_scene_build(scene, NAME);
    unsigned char *pixels = NULL;
    if (st == BG_OK) {
        pixels = malloc((size_t)args.size * (size_t)args.size * 4);
        if (!pixels) {
            fprintf(stderr, NAME ": out of memory\n");
            bg_scene_destroy(scene);
            return 1;
        }
        bg_image image = {args.size, args.size, BG_PIXEL_RGBA8, 0, pixels};
        bg_render_settings settings = bg_render_settings_init();
        st = bg_render_cpu(scene, &settings, &image);
        if (st == BG_OK) {
            char message[256];
            st = bg_png_save(args.path, &image, message, sizeof message);
            if (st != BG_OK)
                fprintf(stderr, NAME ": %s\n", message);
        }
    }
    if (st != BG_OK && scene && bg_scene_error(scene) != BG_OK)
        fprintf(stderr, NAME ": %s\n", bg_scene_error_message(scene));
    free(pixels);
    bg_scene_destroy(scene);
    if (st != BG_OK)
        return 1;
    printf("wrote %s (%dx%d)\n", args.path, args.size, args.size);
    return 0;
}
