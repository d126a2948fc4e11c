/* The PNG reader (png_read.h). libpng reports a failure by calling our error function, which keeps
 * the message and longjmps back to the setjmp of the call that was reading; warnings (a damaged
 * ancillary chunk, which libpng skips) are dropped, because the library never prints. The steps
 * that call libpng live in functions of their own, so no local of a setjmp frame changes after the
 * setjmp (what C leaves indeterminate after a longjmp). */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <string.h>

#include "../common/image.h"
#include "open_input.h"
#include "png_read.h"

static void keep_reason(bg_png_reader *r, const char *text)
{
    if (!r->reason[0])
        bgi_message_copy(r->reason, sizeof r->reason, text);
}

static void on_libpng_error(png_structp png, png_const_charp text)
{
    keep_reason(png_get_error_ptr(png), text);
    png_longjmp(png, 1);
}

static void on_libpng_warning(png_structp png, png_const_charp text)
{
    (void)png;
    (void)text;
}

/* What a short read means: a read error says why, otherwise the file ended early. */
static void short_read_reason(bg_png_reader *r)
{
    if (ferror(r->file)) {
        char buf[sizeof r->reason];
        snprintf(buf, sizeof buf, "read error: %s", strerror(errno));
        keep_reason(r, buf);
    } else {
        keep_reason(r, "file is truncated");
    }
}

/* libpng's input: the file, where running out of bytes is named for what it is ("file is
 * truncated") rather than libpng's "Read Error". */
static void read_from_file(png_structp png, png_bytep data, size_t length)
{
    bg_png_reader *r = png_get_io_ptr(png);
    if (fread(data, 1, length, r->file) != length) {
        short_read_reason(r);
        png_error(png, r->reason);
    }
}

void bgi_png_reader_close(bg_png_reader *r)
{
    if (r->png)
        png_destroy_read_struct(&r->png, r->info ? &r->info : NULL, NULL);
    r->png = NULL;
    r->info = NULL;
    if (r->file)
        fclose(r->file);
    r->file = NULL;
}

/* Formats into the caller's buffer of size bytes (NULL or 0 is fine), truncating. */
static void write_message(char *message, size_t size, const char *format, ...)
{
    if (!message || size == 0)
        return;
    va_list args;
    va_start(args, format);
    vsnprintf(message, size, format, args);
    va_end(args);
}

static bg_status reader_fail(bg_png_reader *r, bg_status status, const char *what, char *message, size_t size)
{
    write_message(message, size, "%s: %s: %s", r->path, what, r->reason[0] ? r->reason : "unknown libpng error");
    bgi_png_reader_close(r);
    return status;
}

/* The 8-byte signature, checked before libpng sees the file, so that a file of another kind is
 * called that rather than whatever libpng makes of its first chunk. */
static bool read_signature(bg_png_reader *r)
{
    png_byte sig[8];
    if (fread(sig, 1, sizeof sig, r->file) != sizeof sig) {
        short_read_reason(r);
        return false;
    }
    if (png_sig_cmp(sig, 0, sizeof sig) != 0) {
        keep_reason(r, "not a PNG file (no PNG signature)");
        return false;
    }
    return true;
}

/* Every colour type to RGBA: palettes looked up and their tRNS made alpha, grey below 8 bits scaled
 * exactly to 0..255, a grey or RGB tRNS key made alpha, grey copied to R, G and B, and a missing
 * alpha made opaque (the filler is 0xff at 8 bits, and libpng adds none where alpha exists). No
 * sample value is changed otherwise: no gamma is set, and 16 bits stay 16. */
static void request_rgba(png_structp png)
{
    png_set_expand(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xffff, PNG_FILLER_AFTER);
}

static void read_header(bg_png_reader *r)
{
    png_set_read_fn(r->png, r, read_from_file);
    png_set_sig_bytes(r->png, 8);
    png_read_info(r->png, r->info);
    request_rgba(r->png);
    r->passes = png_set_interlace_handling(r->png);
    png_read_update_info(r->png, r->info);
    r->width = (int)png_get_image_width(r->png, r->info);
    r->height = (int)png_get_image_height(r->png, r->info);
    r->bits = png_get_bit_depth(r->png, r->info);
    if (png_get_channels(r->png, r->info) != 4 || (r->bits != 8 && r->bits != 16))
        png_error(r->png, "libpng did not expand the file to 8- or 16-bit RGBA");
}

/* libpng checks the header's fields against its own limits before ours; a side it takes but we do
 * not is reported with the size. */
static bg_status check_size(bg_png_reader *r, char *message, size_t size)
{
    if (r->width >= 1 && r->height >= 1 && r->width <= BG_MAX_IMAGE_SIDE && r->height <= BG_MAX_IMAGE_SIDE)
        return BG_OK;
    snprintf(r->reason, sizeof r->reason, "PNG size %ux%u is outside [1, %d] per side", (unsigned)r->width,
             (unsigned)r->height, BG_MAX_IMAGE_SIDE);
    write_message(message, size, "%s: %s", r->path, r->reason);
    bgi_png_reader_close(r);
    return BG_ERR_IO;
}

bg_status bgi_png_reader_open(bg_png_reader *r, const char *path, char *message, size_t size)
{
    memset(r, 0, sizeof *r);
    r->path = path;
    char why[sizeof r->reason];
    r->file = bgi_open_input(path, why, sizeof why);
    if (!r->file) {
        write_message(message, size, "%s: %s", path, why);
        return BG_ERR_IO;
    }
    if (!read_signature(r))
        return reader_fail(r, BG_ERR_IO, "cannot read PNG header", message, size);
    r->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, r, on_libpng_error, on_libpng_warning);
    if (r->png)
        r->info = png_create_info_struct(r->png);
    if (!r->info) {
        keep_reason(r, "out of memory for libpng");
        return reader_fail(r, BG_ERR_OUT_OF_MEMORY, "cannot read PNG header", message, size);
    }
    if (setjmp(png_jmpbuf(r->png)))
        return reader_fail(r, BG_ERR_IO, "cannot read PNG header", message, size);
    read_header(r);
    return check_size(r, message, size);
}

size_t bgi_png_reader_row_bytes(const bg_png_reader *r)
{
    return (size_t)r->width * 4 * (size_t)(r->bits / 8);
}

/* Adam7 files come in 7 passes over the same rows, each filling in more of every row it touches,
 * so every row must stay in place until the last pass. */
static void read_rows(bg_png_reader *r, unsigned char *pixels, size_t stride)
{
    for (int pass = 0; pass < r->passes; pass++)
        for (int y = 0; y < r->height; y++)
            png_read_row(r->png, pixels + (size_t)y * stride, NULL);
    png_read_end(r->png, NULL);
}

bg_status bgi_png_reader_read(bg_png_reader *r, unsigned char *pixels, size_t stride, char *message, size_t size)
{
    if (setjmp(png_jmpbuf(r->png)))
        return reader_fail(r, BG_ERR_IO, "cannot read PNG data", message, size);
    read_rows(r, pixels, stride);
    return BG_OK;
}
