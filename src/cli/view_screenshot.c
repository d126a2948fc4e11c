/* The viewer's screenshot (view.h): the shown frame, read back from the GPU, written as render
 * writes its images (tile_file.c's PNG with its Betelgeuse-Tile chunk, through output.c's temporary
 * and rename), so that a screenshot at rest is the file `betelgeuse render` gives. */
#include "view.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "output.h"
#include "tile_file.h"

bool view_screenshot(viewer *v, const char *path, char *why, size_t size)
{
    char numbered[64];
    if (!path || !path[0]) {
        /* The first free name, so that P never replaces an earlier screenshot. */
        for (int n = 1;; n++) {
            snprintf(numbered, sizeof numbered, "betelgeuse-view-%d.png", n);
            if (access(numbered, F_OK) != 0)
                break;
        }
        path = numbered;
    }
    if (!cli_inputs_allow(&v->inputs, "screenshot", path, why, size))
        return false;
    bg_image image;
    if (!view_frames_read(&v->frames, &image)) {
        snprintf(why, size, "%s: no frame to save yet (or out of memory reading it back)", path);
        return false;
    }
    cli_output out;
    cli_placement whole = {0, 0, image.width, image.height};
    bool ok = cli_output_open(&out, path, why, size) && cli_png_write(out.file, path, &image, &whole, why, size) &&
              cli_output_finish(&out, why, size) && cli_outputs_commit(&out, 1, why, size);
    cli_output_discard(&out);
    free(image.pixels);
    if (ok && !v->options->quiet)
        fprintf(stderr, "betelgeuse view: %dx%d frame (%d of %d samples) saved to %s\n", image.width, image.height,
                v->frames.shown == v->frames.full ? v->frames.samples : 1, v->samples, path);
    return ok;
}
