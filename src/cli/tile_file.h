/* The command's image files: an 8-bit RGBA PNG that may carry where it lies in a bigger frame (a
 * tile of `betelgeuse render --tile`, or a --crop window), read back by `betelgeuse assemble`, and
 * a PFM of the linear radiance. */
#ifndef CLI_TILE_FILE_H
#define CLI_TILE_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "betelgeuse.h"

/* Where an image lies in its frame: the window's top-left pixel and the frame's size. A whole
 * frame is {0, 0, width, height}. */
typedef struct cli_placement {
    int x, y;
    int frame_width, frame_height;
} cli_placement;

/* Writes an RGBA8 image as a PNG into f (an output.h temporary), with its placement in a
 * "Betelgeuse-Tile" text chunk ("x y frame_width frame_height"); false with the reason in why,
 * which names the file as name. f stays open. */
bool cli_png_write(FILE *f, const char *name, const bg_image *image, const cli_placement *where, char *why,
                   size_t why_size);

/* The same PNG written as its rows become final (a render's settings.rows_done), so that encoding
 * overlaps the render: begin (the header), rows [y0, y1) of image in order as they come, end (the
 * rows not yet written, then the end; the stream is freed either way), or abort (freed, the file
 * left for the caller to discard). A failed write or rows out of order make rows return false and
 * end report the reason, naming the file as name. */
typedef struct cli_png_stream cli_png_stream;
bool cli_png_stream_begin(cli_png_stream **out, FILE *f, const char *name, int width, int height,
                          const cli_placement *where, char *why, size_t why_size);
bool cli_png_stream_rows(cli_png_stream *s, const bg_image *image, int y0, int y1);
/* Whether a write failed already (NULL: no stream, false). */
bool cli_png_stream_failed(const cli_png_stream *s);
bool cli_png_stream_end(cli_png_stream *s, const bg_image *image, char *why, size_t why_size);
void cli_png_stream_abort(cli_png_stream *s);

/* Reads a PNG written by cli_png_write into *image (pixels allocated with malloc, RGBA8, rows
 * top-down) and its placement; a PNG without the chunk is a whole frame. False with the reason,
 * also for a path that is not a regular file (a directory, a FIFO) and for a placement outside
 * BG_MAX_IMAGE_SIDE. */
bool cli_png_read(const char *path, bg_image *image, cli_placement *where, char *why, size_t why_size);

/* Writes an RGBA32F image's RGB as a PFM into f (rows bottom-up, as the format has them; the
 * machine's byte order, given by the scale's sign). f stays open. */
bool cli_pfm_write(FILE *f, const char *name, const bg_image *image, char *why, size_t why_size);

#endif
