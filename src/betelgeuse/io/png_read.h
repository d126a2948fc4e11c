/* Reading a PNG's samples through libpng's low-level API (png_read.c), for bg_png_size, bg_png_load
 * and bg_scene_load_texture_png alike. Every colour type, bit depth and interlace method becomes
 * RGBA at 8 or 16 bits per channel and nothing else changes: no gamma, colour-space or
 * significant-bits chunk is applied, so the samples keep the file's encoding. */
#ifndef BG_PNG_READ_H
#define BG_PNG_READ_H

#include <png.h>
#include <stdio.h>

#include "betelgeuse.h"

/* One file being read. reason holds libpng's (or the reader's) word on the first failure. */
typedef struct bg_png_reader {
    const char *path;
    FILE *file;
    png_structp png;
    png_infop info;
    int width, height;
    int bits;   /* 8 or 16 per channel, once expanded to RGBA */
    int passes; /* 7 for Adam7, else 1 */
    char reason[160];
} bg_png_reader;

/* Opens path and reads its header, checking the size against BG_MAX_IMAGE_SIDE. On failure writes
 * "path: what: reason" and leaves nothing open. */
bg_status bgi_png_reader_open(bg_png_reader *r, const char *path, char *message, size_t size);
/* Bytes of one row of samples: width * 4 channels * bits / 8. */
size_t bgi_png_reader_row_bytes(const bg_png_reader *r);
/* Reads every row as RGBA into pixels, rows stride bytes apart, 16-bit samples big-endian as the
 * file stores them; then reads the rest of the file, so that truncation and bad CRCs are caught.
 * On failure writes "path: cannot read PNG data: reason" and closes the reader. */
bg_status bgi_png_reader_read(bg_png_reader *r, unsigned char *pixels, size_t stride, char *message, size_t size);
/* Frees what open allocated; safe after a failed open and when called twice. */
void bgi_png_reader_close(bg_png_reader *r);

#endif
