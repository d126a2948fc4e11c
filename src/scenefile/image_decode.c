/* Images of model files, from bytes in memory (a file read whole, or an image embedded in the model)
 * to an RGBA8 bg_image, the format told by its first bytes rather than by a name or a MIME type,
 * which exporters get wrong. PNG goes through libpng's simplified API and JPEG through
 * libjpeg-turbo's TurboJPEG API: both read from memory (what embedded images need) in a few calls
 * that return a status and a message, with no setjmp/longjmp error handling on our side, and
 * libjpeg-turbo is the libjpeg Debian ships. */
#include "scenefile_internal.h"

#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <turbojpeg.h>

bgi_sf_image_format bgi_sf_image_sniff(const unsigned char *data, size_t size)
{
    static const unsigned char png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char ktx2_sig[12] = {0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb, '\r', '\n', 0x1a, '\n'};
    if (size >= 8 && memcmp(data, png_sig, 8) == 0)
        return BGI_SF_IMAGE_PNG;
    if (size >= 3 && data[0] == 0xff && data[1] == 0xd8 && data[2] == 0xff)
        return BGI_SF_IMAGE_JPEG;
    if (size >= 12 && memcmp(data, ktx2_sig, 12) == 0)
        return BGI_SF_IMAGE_KTX2;
    if (size >= 12 && memcmp(data, "RIFF", 4) == 0 && memcmp(data + 8, "WEBP", 4) == 0)
        return BGI_SF_IMAGE_WEBP;
    return BGI_SF_IMAGE_UNKNOWN;
}

const char *bgi_sf_image_format_name(bgi_sf_image_format f)
{
    switch (f) {
    case BGI_SF_IMAGE_PNG: return "PNG";
    case BGI_SF_IMAGE_JPEG: return "JPEG";
    case BGI_SF_IMAGE_KTX2: return "KTX2";
    case BGI_SF_IMAGE_WEBP: return "WebP";
    case BGI_SF_IMAGE_UNKNOWN: break;
    }
    return "unknown-format";
}

/* The size checked before any allocation: a header may claim anything. */
static bool size_ok(const char *format, int w, int h, char *reason, size_t size)
{
    if (w >= 1 && h >= 1 && w <= BG_MAX_IMAGE_SIDE && h <= BG_MAX_IMAGE_SIDE)
        return true;
    snprintf(reason, size, "the %s header's size %d x %d is outside 1..%d", format, w, h, BG_MAX_IMAGE_SIDE);
    return false;
}

static bg_status alloc_rgba8(int w, int h, bg_image *out, char *reason, size_t size)
{
    *out = (bg_image){w, h, BG_PIXEL_RGBA8, (size_t)w * 4, malloc((size_t)w * h * 4)};
    if (out->pixels)
        return BG_OK;
    snprintf(reason, size, "out of memory for %d x %d texels", w, h);
    return BG_ERR_OUT_OF_MEMORY;
}

/* 16-bit samples are taken as sRGB-encoded, as 8-bit ones are: libpng would otherwise take a 16-bit
 * file without a gAMA chunk for linear and re-encode it, darkening it beside the same 8-bit image. */
static bg_status decode_png(const unsigned char *data, size_t n, bg_image *out, char *reason, size_t size)
{
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&pi, data, n)) {
        snprintf(reason, size, "not a readable PNG: %s", pi.message);
        png_image_free(&pi);
        return BG_ERR_IO;
    }
    if (!size_ok("PNG", (int)pi.width, (int)pi.height, reason, size)) {
        png_image_free(&pi);
        return BG_ERR_IO;
    }
    pi.format = PNG_FORMAT_RGBA;
    pi.flags |= PNG_IMAGE_FLAG_16BIT_sRGB;
    bg_status st = alloc_rgba8((int)pi.width, (int)pi.height, out, reason, size);
    if (st != BG_OK) {
        png_image_free(&pi);
        return st;
    }
    if (!png_image_finish_read(&pi, NULL, out->pixels, (png_int_32)out->stride, NULL)) {
        snprintf(reason, size, "cannot read PNG data: %s", pi.message);
        png_image_free(&pi);
        free(out->pixels);
        out->pixels = NULL;
        return BG_ERR_IO;
    }
    return BG_OK;
}

static bg_status decode_jpeg(const unsigned char *data, size_t n, bg_image *out, char *reason, size_t size)
{
    tjhandle tj = tjInitDecompress();
    if (!tj) {
        snprintf(reason, size, "cannot start the JPEG decoder: %s", tjGetErrorStr2(NULL));
        return BG_ERR_IO;
    }
    int w = 0, h = 0, subsamp = 0, colorspace = 0;
    bg_status st = BG_OK;
    if (n > (size_t)(unsigned long)-1 ||
        tjDecompressHeader3(tj, data, (unsigned long)n, &w, &h, &subsamp, &colorspace) != 0) {
        snprintf(reason, size, "not a readable JPEG: %s", tjGetErrorStr2(tj));
        st = BG_ERR_IO;
    } else if (!size_ok("JPEG", w, h, reason, size)) {
        st = BG_ERR_IO;
    } else if ((st = alloc_rgba8(w, h, out, reason, size)) == BG_OK &&
               tjDecompress2(tj, data, (unsigned long)n, out->pixels, w, (int)out->stride, h, TJPF_RGBA, 0) != 0) {
        /* Warnings (a truncated stream, whose missing rows libjpeg paints grey) are refused as well:
         * a damaged texture is better named than shown half grey. */
        snprintf(reason, size, "cannot read JPEG data: %s", tjGetErrorStr2(tj));
        free(out->pixels);
        out->pixels = NULL;
        st = BG_ERR_IO;
    }
    tjDestroy(tj);
    return st;
}

bg_status bgi_sf_image_decode(const unsigned char *data, size_t size, bg_image *out, char *reason,
                              size_t reason_size)
{
    memset(out, 0, sizeof *out);
    switch (bgi_sf_image_sniff(data, size)) {
    case BGI_SF_IMAGE_PNG: return decode_png(data, size, out, reason, reason_size);
    case BGI_SF_IMAGE_JPEG: return decode_jpeg(data, size, out, reason, reason_size);
    default: break;
    }
    snprintf(reason, reason_size, "%s images are not read (PNG and JPEG are)",
             bgi_sf_image_format_name(bgi_sf_image_sniff(data, size)));
    return BG_ERR_IO;
}
