/* Radiance .hdr decoding: stb_image compiled into this library from the packaged header, as stb is
 * meant to be used, with only its HDR decoder and every function static. A distribution's prebuilt
 * libstb is not used: Debian unstable's libstb.so.0 left the odd rows of a run-length coded file
 * unwritten, so the result depended on how a distribution built a library rather than on the file.
 *
 * Before stb allocates anything, the header is read here and the size it declares is held against
 * the file: the smallest encoding of a W x H image (every scanline one run-length record of
 * maximal runs) must fit in what the file holds, so a 40-byte file cannot make the decoder
 * allocate gigabytes. */
#include "scenefile_internal.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
/* stb's own code, not ours: its unused static entry points and its style are not this project's
 * warnings to fix. GCC reports static functions never defined or used at the end of the unit, after
 * any pop, so that one warning stays off for this whole (small) file. */
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wshift-negative-value"
#pragma GCC diagnostic ignored "-Wtype-limits"
#include <stb_image.h>
#pragma GCC diagnostic pop

/* stb_image's input from a file, noting a read past its end: stb fills what the file lacks with
 * zeros and reports success, so a truncated .hdr would load as black rows otherwise. */
typedef struct hdr_input {
    FILE *file;
    bool past_end;
} hdr_input;

static int hdr_read(void *user, char *data, int size)
{
    hdr_input *in = user;
    size_t n = fread(data, 1, (size_t)size, in->file);
    if (n == 0)
        in->past_end = true;
    return (int)n;
}

static void hdr_skip(void *user, int n)
{
    hdr_input *in = user;
    if (fseek(in->file, n, SEEK_CUR) != 0)
        in->past_end = true;
}

static int hdr_eof(void *user)
{
    hdr_input *in = user;
    return feof(in->file) ? 1 : 0;
}

/* Reads one header line (without its newline) into line; false at the end of the file or for a
 * line longer than the buffer, which no Radiance header has. */
static bool read_line(FILE *f, char *line, size_t size)
{
    size_t n = 0;
    for (int c; (c = fgetc(f)) != EOF;) {
        if (c == '\n') {
            line[n] = '\0';
            return true;
        }
        if (n + 1 >= size)
            return false;
        line[n++] = (char)c;
    }
    return false;
}

/* The image size the header declares ("-Y H +X W", the one orientation stb reads), and the bytes
 * that follow the header; false with why filled when the header is not one. */
static bool read_header(FILE *f, int *w, int *h, long *data_bytes, char *why, size_t why_size)
{
    char line[256];
    bool blank = false;
    while (!blank) {
        if (!read_line(f, line, sizeof line)) {
            snprintf(why, why_size, "the header ends before its blank line");
            return false;
        }
        blank = line[0] == '\0';
    }
    long hh = 0, ww = 0;
    char tail = 0;
    if (!read_line(f, line, sizeof line) || sscanf(line, "-Y %ld +X %ld%c", &hh, &ww, &tail) != 2) {
        snprintf(why, why_size, "the resolution line is not \"-Y height +X width\"");
        return false;
    }
    if (hh < 1 || ww < 1 || hh > INT_MAX || ww > INT_MAX) {
        snprintf(why, why_size, "the resolution %ld x %ld is not a positive size", ww, hh);
        return false;
    }
    long here = ftell(f);
    if (here < 0 || fseek(f, 0, SEEK_END) != 0) {
        snprintf(why, why_size, "the file cannot be measured");
        return false;
    }
    *data_bytes = ftell(f) - here;
    *w = (int)ww;
    *h = (int)hh;
    return true;
}

/* The fewest bytes that can hold a w x h image: flat scanlines take 4 bytes a pixel; a run-length
 * scanline (8 to 32767 pixels wide) takes a 4-byte record and, per channel, two bytes a run of at
 * most 127 pixels. */
static double smallest_encoding(int w, int h)
{
    double per_line = w >= 8 && w < 32768 ? 4.0 + 4.0 * 2.0 * ((w + 126) / 127) : 4.0 * w;
    return per_line * h;
}

float *bgi_sf_hdr_decode(FILE *file, int *out_w, int *out_h, char *why, size_t why_size)
{
    int w = 0, h = 0;
    long data_bytes = 0;
    if (!read_header(file, &w, &h, &data_bytes, why, why_size))
        return NULL;
    if ((double)data_bytes < smallest_encoding(w, h)) {
        snprintf(why, why_size, "its %d x %d pixels need at least %.0f bytes after the header, the file holds %ld",
                 w, h, smallest_encoding(w, h), data_bytes);
        return NULL;
    }
    rewind(file);
    hdr_input in = {file, false};
    const stbi_io_callbacks io = {hdr_read, hdr_skip, hdr_eof};
    int channels = 0;
    float *texels = stbi_loadf_from_callbacks(&io, &in, out_w, out_h, &channels, 4);
    if (!texels) {
        snprintf(why, why_size, "%s", stbi_failure_reason());
        return NULL;
    }
    if (in.past_end) {
        stbi_image_free(texels);
        snprintf(why, why_size, "the file ends before its %d x %d pixels", *out_w, *out_h);
        return NULL;
    }
    return texels;
}

void bgi_sf_hdr_free(float *texels)
{
    stbi_image_free(texels);
}
