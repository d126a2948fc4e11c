/* `betelgeuse assemble TILE... -o OUT.png`: the tiles of one frame (each PNG carries its place,
 * tile_file.h) put together. Every pixel of the frame must come from exactly one tile: a gap, an
 * overlap or tiles of different frames are refused, naming the file, and nothing is written; so is
 * an -o that names one of the tiles. The frame replaces OUT.png only once it is fully written. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "inputs.h"
#include "output.h"
#include "tile_file.h"

static int usage_error(const char *message)
{
    fprintf(stderr, "betelgeuse assemble: %s\n(see betelgeuse --help)\n", message);
    return CLI_EXIT_USAGE;
}

/* The exit code for out against the tiles, with the message printed: 2 when out is one of them
 * (by identity: any spelling or link of it), as the frame would replace a tile it is made from. */
static int check_output(const char *out, char **paths, int tiles)
{
    cli_inputs inputs;
    memset(&inputs, 0, sizeof inputs);
    for (int t = 0; t < tiles; t++)
        cli_inputs_add(&inputs, paths[t]);
    char why[1024];
    int status = CLI_EXIT_OK;
    if (inputs.out_of_memory) {
        fprintf(stderr, "betelgeuse assemble: out of memory listing the tiles\n");
        status = CLI_EXIT_FAILED;
    } else if (!cli_inputs_allow(&inputs, "-o", out, why, sizeof why)) {
        fprintf(stderr, "betelgeuse assemble: %s\n", why);
        status = CLI_EXIT_USAGE;
    }
    cli_inputs_free(&inputs);
    return status;
}

/* The whole frame into a temporary beside out, put in place only when fully written. */
static bool write_frame(const char *out, const bg_image *frame, char *why, size_t size)
{
    cli_placement whole = {0, 0, frame->width, frame->height};
    cli_output file;
    bool ok = cli_output_open(&file, out, why, size) && cli_png_write(file.file, out, frame, &whole, why, size) &&
              cli_output_finish(&file, why, size) && cli_outputs_commit(&file, 1, why, size);
    cli_output_discard(&file);
    return ok;
}

int cli_assemble(int argc, char **argv)
{
    const char *out = NULL;
    int tiles = 0;
    char **paths = calloc((size_t)argc + 1, sizeof *paths);
    if (!paths)
        return CLI_EXIT_FAILED;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--output") == 0) {
            if (i + 1 >= argc) {
                free(paths);
                return usage_error("-o needs a file name");
            }
            out = argv[++i];
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            char message[160];
            snprintf(message, sizeof message, "unknown option %s", argv[i]);
            free(paths);
            return usage_error(message);
        } else {
            paths[tiles++] = argv[i];
        }
    }
    if (!out || tiles == 0) {
        free(paths);
        return usage_error(!out ? "-o OUT.png is required" : "no tiles given");
    }
    int checked = check_output(out, paths, tiles);
    if (checked != CLI_EXIT_OK) {
        free(paths);
        return checked;
    }
    int status = CLI_EXIT_OK;
    bg_image frame = {0, 0, BG_PIXEL_RGBA8, 0, NULL};
    unsigned char *covered = NULL;
    cli_placement first = {0, 0, 0, 0};
    char why[512];
    for (int t = 0; t < tiles && status == CLI_EXIT_OK; t++) {
        bg_image tile;
        cli_placement at;
        if (!cli_png_read(paths[t], &tile, &at, why, sizeof why)) {
            fprintf(stderr, "betelgeuse assemble: %s\n", why);
            status = CLI_EXIT_USAGE;
            break;
        }
        if (t == 0) {
            first = at;
            frame.width = at.frame_width;
            frame.height = at.frame_height;
            frame.pixels = calloc((size_t)frame.width * (size_t)frame.height, 4);
            covered = calloc((size_t)frame.width * (size_t)frame.height, 1);
            if (!frame.pixels || !covered) {
                fprintf(stderr, "betelgeuse assemble: out of memory for a %dx%d frame\n", frame.width, frame.height);
                status = CLI_EXIT_FAILED;
            }
        } else if (at.frame_width != first.frame_width || at.frame_height != first.frame_height) {
            fprintf(stderr, "betelgeuse assemble: %s: a tile of a %dx%d frame, but %s is of a %dx%d frame\n", paths[t],
                    at.frame_width, at.frame_height, paths[0], first.frame_width, first.frame_height);
            status = CLI_EXIT_USAGE;
        }
        for (int y = 0; y < tile.height && status == CLI_EXIT_OK; y++) {
            size_t row = (size_t)(at.y + y) * (size_t)frame.width + (size_t)at.x;
            for (int x = 0; x < tile.width; x++)
                if (covered[row + (size_t)x]) {
                    fprintf(stderr, "betelgeuse assemble: %s: pixel (%d, %d) of the frame is in another tile too\n",
                            paths[t], at.x + x, at.y + y);
                    status = CLI_EXIT_USAGE;
                    break;
                }
            if (status != CLI_EXIT_OK)
                break;
            memset(covered + row, 1, (size_t)tile.width);
            memcpy((unsigned char *)frame.pixels + row * 4, (unsigned char *)tile.pixels + (size_t)y * tile.width * 4,
                   (size_t)tile.width * 4);
        }
        free(tile.pixels);
    }
    for (size_t i = 0; status == CLI_EXIT_OK && i < (size_t)frame.width * (size_t)frame.height; i++)
        if (!covered[i]) {
            fprintf(stderr, "betelgeuse assemble: pixel (%zu, %zu) of the %dx%d frame is in no tile\n",
                    i % (size_t)frame.width, i / (size_t)frame.width, frame.width, frame.height);
            status = CLI_EXIT_USAGE;
        }
    if (status == CLI_EXIT_OK && !write_frame(out, &frame, why, sizeof why)) {
        fprintf(stderr, "betelgeuse assemble: %s\n", why);
        status = CLI_EXIT_FAILED;
    }
    free(frame.pixels);
    free(covered);
    free(paths);
    return status;
}
