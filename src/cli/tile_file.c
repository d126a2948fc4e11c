/* Tile PNGs and PFMs (tile_file.h). The library's own PNG writer goes through libpng's simplified
 * API, which writes no text chunks; the placement needs one, so the command uses libpng's full API
 * here, with its errors turned into messages through setjmp. */
#include "tile_file.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "betelgeuse/io/open_input.h"
#include "numbers.h"

#define TILE_KEY "Betelgeuse-Tile"

static bool fail(char *why, size_t size, const char *format, const char *path, const char *detail)
{
    snprintf(why, size, format, path, detail);
    return false;
}

/* libpng's error callback: keeps the message and unwinds to the caller's setjmp. */
static void on_png_error(png_structp png, png_const_charp message)
{
    char *keep = png_get_error_ptr(png);
    snprintf(keep, 256, "%s", message);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message; /* a warning changes nothing the command writes or reads */
}

/* libpng's own writer reports a short write as a bare "Write Error"; this one says why (a full
 * disk, a file-size limit), while errno still holds the reason. */
static void write_data(png_structp png, png_bytep data, size_t length)
{
    if (fwrite(data, 1, length, png_get_io_ptr(png)) != length)
        png_error(png, strerror(errno));
}

static void flush_data(png_structp png)
{
    (void)png; /* cli_output_finish flushes and checks the stream once at the end */
}

/* A PNG being written row by row. libpng reports errors by longjmp to the last setjmp: each call
 * below that enters libpng sets its own, and after an error the stream only remembers it. */
struct cli_png_stream {
    png_structp png;
    png_infop info;
    const char *name;
    int width, height;
    int next;          /* the first row not yet written */
    bool failed;
    char message[256]; /* libpng's error, or the rule broken */
};

static bool stream_fail(cli_png_stream *s, const char *message)
{
    /* libpng's own errors are in s->message already (on_png_error). */
    if (!s->failed && message != s->message)
        snprintf(s->message, sizeof s->message, "%s", message);
    s->failed = true;
    return false;
}

bool cli_png_stream_begin(cli_png_stream **out, FILE *f, const char *name, int width, int height,
                          const cli_placement *where, char *why, size_t why_size)
{
    *out = NULL;
    cli_png_stream *s = calloc(1, sizeof *s);
    if (!s)
        return fail(why, why_size, "%s: %s", name, "out of memory");
    s->name = name;
    s->width = width;
    s->height = height;
    s->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, s->message, on_png_error, on_png_warning);
    s->info = s->png ? png_create_info_struct(s->png) : NULL;
    if (!s->png || !s->info) {
        cli_png_stream_abort(s);
        return fail(why, why_size, "%s: %s", name, "out of memory");
    }
    if (setjmp(png_jmpbuf(s->png))) {
        fail(why, why_size, "%s: cannot write: %s", name, s->message);
        cli_png_stream_abort(s);
        return false;
    }
    png_set_write_fn(s->png, f, write_data, flush_data);
    png_set_IHDR(s->png, s->info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB_ALPHA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    char text[96];
    snprintf(text, sizeof text, "%d %d %d %d", where->x, where->y, where->frame_width, where->frame_height);
    png_text t;
    memset(&t, 0, sizeof t);
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = (png_charp)TILE_KEY;
    t.text = text;
    png_set_text(s->png, s->info, &t, 1);
    /* zlib's fastest level: at 1024x1024 (llvmpipe, 2 busy cores) level 6, libpng's default, took
     * 185-465 ms to encode, longer than the frame (150-210 ms for paper_earth_shadow), and level 1
     * 36-140 ms, for files 8 to 52 % larger (docs/benchmarks.md, "The command's own cost"). */
    png_set_compression_level(s->png, 1);
    png_write_info(s->png, s->info);
    *out = s;
    return true;
}

bool cli_png_stream_rows(cli_png_stream *s, const bg_image *image, int y0, int y1)
{
    if (s->failed)
        return false;
    /* Rows go into a PNG once, in order: a gap or an overlap is a bug in who tells them. */
    if (y0 != s->next || y1 < y0 || y1 > s->height || image->width != s->width || image->height != s->height)
        return stream_fail(s, "rows told out of order");
    size_t stride = image->stride ? image->stride : (size_t)image->width * 4;
    if (setjmp(png_jmpbuf(s->png)))
        return stream_fail(s, s->message);
    for (int y = y0; y < y1; y++)
        png_write_row(s->png, (png_const_bytep)image->pixels + (size_t)y * stride);
    s->next = y1;
    return true;
}

bool cli_png_stream_failed(const cli_png_stream *s)
{
    return s && s->failed;
}

bool cli_png_stream_end(cli_png_stream *s, const bg_image *image, char *why, size_t why_size)
{
    bool ok = cli_png_stream_rows(s, image, s->next, s->height);
    if (ok) {
        if (setjmp(png_jmpbuf(s->png)))
            ok = stream_fail(s, s->message);
        else
            png_write_end(s->png, NULL);
    }
    if (!ok)
        fail(why, why_size, "%s: cannot write: %s", s->name, s->message);
    cli_png_stream_abort(s);
    return ok;
}

void cli_png_stream_abort(cli_png_stream *s)
{
    if (!s)
        return;
    png_destroy_write_struct(&s->png, &s->info);
    free(s);
}

bool cli_png_write(FILE *f, const char *name, const bg_image *image, const cli_placement *where, char *why,
                   size_t why_size)
{
    cli_png_stream *s = NULL;
    return cli_png_stream_begin(&s, f, name, image->width, image->height, where, why, why_size) &&
           cli_png_stream_end(s, image, why, why_size);
}

/* The placement in the text chunks, if any; false when the chunk is there but malformed. */
static bool placement_of(png_structp png, png_infop info, const bg_image *image, cli_placement *where)
{
    *where = (cli_placement){0, 0, image->width, image->height};
    png_textp texts = NULL;
    int n = 0;
    png_get_text(png, info, &texts, &n);
    for (int i = 0; i < n; i++) {
        if (strcmp(texts[i].key, TILE_KEY) != 0)
            continue;
        /* A frame larger than any render could make is a forged or broken chunk, not a request to
         * allocate gigabytes; with every value bounded, the sums below cannot overflow. */
        int v[4];
        if (!cli_parse_ints(texts[i].text, ' ', 4, 0, BG_MAX_IMAGE_SIDE, v))
            return false;
        cli_placement p = {v[0], v[1], v[2], v[3]};
        if (p.frame_width < 1 || p.frame_height < 1 || p.x > p.frame_width - image->width ||
            p.y > p.frame_height - image->height)
            return false;
        *where = p;
    }
    return true;
}

bool cli_png_read(const char *path, bg_image *image, cli_placement *where, char *why, size_t why_size)
{
    memset(image, 0, sizeof *image);
    char reason[256];
    FILE *f = bgi_open_input(path, reason, sizeof reason);
    if (!f)
        return fail(why, why_size, "%s: %s", path, reason);
    unsigned char signature[8];
    if (fread(signature, 1, 8, f) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
        fclose(f);
        return fail(why, why_size, "%s: %s", path, "not a PNG file");
    }
    char message[256] = "";
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, message, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_read_struct(&png, NULL, NULL);
        fclose(f);
        return fail(why, why_size, "%s: %s", path, "out of memory");
    }
    unsigned char *volatile pixels = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        free(pixels);
        return fail(why, why_size, "%s: %s", path, message);
    }
    png_init_io(png, f);
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    /* Any PNG becomes 8-bit RGBA, so that tiles from other tools assemble too. */
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if (w == 0 || h == 0 || w > BG_MAX_IMAGE_SIDE || h > BG_MAX_IMAGE_SIDE ||
        png_get_rowbytes(png, info) != (size_t)w * 4) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        return fail(why, why_size, "%s: %s", path, "unsupported image size or layout");
    }
    pixels = malloc((size_t)w * h * 4);
    png_bytep *rows = pixels ? malloc(h * sizeof *rows) : NULL;
    if (!rows) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        free(pixels);
        return fail(why, why_size, "%s: %s", path, "out of memory");
    }
    for (png_uint_32 y = 0; y < h; y++)
        rows[y] = pixels + (size_t)y * w * 4;
    png_read_image(png, rows);
    png_read_end(png, info);
    free(rows);
    *image = (bg_image){(int)w, (int)h, BG_PIXEL_RGBA8, 0, pixels};
    bool placed = placement_of(png, info, image, where);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    if (!placed) {
        free(pixels);
        memset(image, 0, sizeof *image);
        return fail(why, why_size, "%s: %s", path, "malformed " TILE_KEY " text chunk");
    }
    return true;
}

bool cli_pfm_write(FILE *f, const char *name, const bg_image *image, char *why, size_t why_size)
{
    size_t stride = image->stride ? image->stride : (size_t)image->width * 16;
    /* The scale's sign gives the byte order of the floats: negative little-endian. */
    const uint16_t probe = 1;
    bool little = *(const unsigned char *)&probe == 1;
    bool ok = fprintf(f, "PF\n%d %d\n%s\n", image->width, image->height, little ? "-1.0" : "1.0") > 0;
    int err = errno;
    float *row = malloc((size_t)image->width * 3 * sizeof *row);
    if (!row)
        return fail(why, why_size, "%s: %s", name, "out of memory");
    for (int y = image->height - 1; y >= 0 && ok; y--) {
        const float *src = (const float *)((const unsigned char *)image->pixels + (size_t)y * stride);
        for (int x = 0; x < image->width; x++)
            memcpy(row + 3 * x, src + 4 * x, 3 * sizeof *row);
        ok = fwrite(row, sizeof *row, (size_t)image->width * 3, f) == (size_t)image->width * 3;
        err = errno;
    }
    free(row);
    if (!ok)
        return fail(why, why_size, "%s: cannot write: %s", name, strerror(err));
    return true;
}
