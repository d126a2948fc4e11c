/* PNG files: size, load, save, and textures. Loading goes through one reader (png_read.h) that
 * keeps the file's encoding; 16-bit samples are reduced to 8 bits here, or kept as floats. Saving
 * goes through libpng's simplified API (png_image), which keeps its message in the png_image the
 * caller owns and never prints from here. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "../common/image.h"
#include "../common/srgb.h"
#include "../scene/scene_private.h"
#include "png_read.h"

static bg_status io_fail(const char *path, const png_image *png, const char *what,
                         char *message, size_t size)
{
    char buf[BG_MESSAGE_SIZE];
    snprintf(buf, sizeof buf, "%s: %s: %s", path, what, png->message[0] ? png->message : "unknown libpng error");
    bgi_message_copy(message, size, buf);
    return BG_ERR_IO;
}

static bg_status arg_fail(const char *text, char *message, size_t size)
{
    bgi_message_copy(message, size, text);
    return BG_ERR_INVALID_ARGUMENT;
}

/* The checks load and save share: a path, a valid image, and a stride libpng can take. */
static bg_status check_file_and_image(const char *fn, const char *path, const bg_image *image,
                                      size_t *stride, char *message, size_t size)
{
    bgi_message_copy(message, size, "");
    char buf[BG_MESSAGE_SIZE], detail[256];
    if (!path) {
        snprintf(buf, sizeof buf, "%s: path is NULL", fn);
        return arg_fail(buf, message, size);
    }
    if (bgi_image_check(image, stride, detail, sizeof detail) != BG_OK) {
        snprintf(buf, sizeof buf, "%s: %s", fn, detail);
        return arg_fail(buf, message, size);
    }
    if (*stride > 0x7fffffff) {
        snprintf(buf, sizeof buf, "%s: image stride is too large for libpng", fn);
        return arg_fail(buf, message, size);
    }
    return BG_OK;
}

bg_status bg_png_size(const char *path, int *width, int *height, char *message, size_t message_size)
{
    bgi_message_copy(message, message_size, "");
    if (!path)
        return arg_fail("bg_png_size: path is NULL", message, message_size);
    if (!width || !height)
        return arg_fail(!width ? "bg_png_size: width is NULL (it receives the image width)"
                               : "bg_png_size: height is NULL (it receives the image height)",
                        message, message_size);
    bg_png_reader r;
    bg_status st = bgi_png_reader_open(&r, path, message, message_size);
    if (st != BG_OK)
        return st;
    *width = r.width;
    *height = r.height;
    bgi_png_reader_close(&r);
    return BG_OK;
}

/* Reads the opened file's samples into a new tightly packed buffer from a (row 0 is the top of the
 * file, as in bg_image); the reader is closed whatever happens. */
static bg_status read_samples(bg_png_reader *r, const bg_allocator *a, unsigned char **out, char *message,
                              size_t size)
{
    size_t row = bgi_png_reader_row_bytes(r);
    *out = bgi_alloc(a, row * (size_t)r->height);
    if (!*out) {
        char buf[BG_MESSAGE_SIZE];
        snprintf(buf, sizeof buf, "%s: out of memory for %dx%d %d-bit RGBA samples", r->path, r->width,
                 r->height, r->bits);
        bgi_message_copy(message, size, buf);
        bgi_png_reader_close(r);
        return BG_ERR_OUT_OF_MEMORY;
    }
    bg_status st = bgi_png_reader_read(r, *out, row, message, size);
    bgi_png_reader_close(r);
    if (st != BG_OK) {
        bgi_free(a, *out);
        *out = NULL;
    }
    return st;
}

/* A 16-bit sample as the file stores it (big-endian). */
static unsigned sample_16(const unsigned char *p)
{
    return (unsigned)p[0] << 8 | p[1];
}

/* A 16-bit sample to 8 bits: round(v / 257). Since 65535 = 255 * 257, this is the 8-bit code at the
 * same place in the file's range, so the file's encoding (sRGB, another gamma, or linear) is kept
 * and only its precision is reduced. v / 257 is never halfway between two integers, so there is no
 * tie to break, and (v + 128) / 257 in integers is exactly that rounding. */
static unsigned char byte_from_16(unsigned v)
{
    return (unsigned char)((v + 128) / 257);
}

/* The samples (bits per channel, tightly packed) into the caller's image: RGBA8 takes 16-bit
 * samples reduced to 8 bits, RGBA32F takes every sample over its depth's largest value (255 or
 * 65535), still encoded. An RGBA8 image of an 8-bit file is read in place and never comes here. */
static void store_samples(const unsigned char *samples, int bits, const bg_image *image, size_t stride)
{
    size_t count = (size_t)image->width * 4, bytes = (size_t)(bits / 8);
    double max = bits == 16 ? 65535.0 : 255.0;
    for (int y = 0; y < image->height; y++) {
        const unsigned char *src = samples + (size_t)y * count * bytes;
        unsigned char *dst = (unsigned char *)image->pixels + (size_t)y * stride;
        for (size_t i = 0; i < count; i++) {
            unsigned v = bits == 16 ? sample_16(src + 2 * i) : src[i];
            if (image->format == BG_PIXEL_RGBA8)
                dst[i] = byte_from_16(v);
            else
                ((float *)dst)[i] = (float)(v / max);
        }
    }
}

bg_status bg_png_load(const char *path, bg_image *image, char *message, size_t message_size)
{
    size_t stride;
    bg_status st = check_file_and_image("bg_png_load", path, image, &stride, message, message_size);
    if (st != BG_OK)
        return st;
    bg_png_reader r;
    if ((st = bgi_png_reader_open(&r, path, message, message_size)) != BG_OK)
        return st;
    if (r.width != image->width || r.height != image->height) {
        char buf[BG_MESSAGE_SIZE];
        snprintf(buf, sizeof buf, "bg_png_load: %s is %dx%d but image is %dx%d", path, r.width, r.height,
                 image->width, image->height);
        bgi_png_reader_close(&r);
        return arg_fail(buf, message, message_size);
    }
    if (image->format == BG_PIXEL_RGBA8 && r.bits == 8) {
        st = bgi_png_reader_read(&r, image->pixels, stride, message, message_size);
        bgi_png_reader_close(&r);
        return st;
    }
    static const bg_allocator heap = {NULL, NULL, NULL, NULL};
    int bits = r.bits;
    unsigned char *samples;
    if ((st = read_samples(&r, &heap, &samples, message, message_size)) != BG_OK)
        return st;
    store_samples(samples, bits, image, stride);
    bgi_free(&heap, samples);
    return BG_OK;
}

/* Clamped to [0, 1], scaled by 255 and rounded to nearest; NaN becomes 0. */
static unsigned char to_byte(float v)
{
    if (!(v > 0.0f))
        return 0;
    if (v >= 1.0f)
        return 255;
    return (unsigned char)floor((double)v * 255.0 + 0.5);
}

bg_status bg_png_save(const char *path, const bg_image *image, char *message, size_t message_size)
{
    size_t stride;
    bg_status st = check_file_and_image("bg_png_save", path, image, &stride, message, message_size);
    if (st != BG_OK)
        return st;
    png_image png;
    memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = (png_uint_32)image->width;
    png.height = (png_uint_32)image->height;
    png.format = PNG_FORMAT_RGBA;

    static const bg_allocator heap = {NULL, NULL, NULL, NULL};
    const void *bytes = image->pixels;
    size_t row_stride = stride;
    unsigned char *tmp = NULL;
    if (image->format == BG_PIXEL_RGBA32F) {
        row_stride = (size_t)image->width * 4;
        tmp = bgi_alloc(&heap, row_stride * (size_t)image->height);
        if (!tmp) {
            bgi_message_copy(message, message_size, "bg_png_save: out of memory");
            return BG_ERR_OUT_OF_MEMORY;
        }
        for (int y = 0; y < image->height; y++) {
            const float *src = (const float *)((const unsigned char *)image->pixels + (size_t)y * stride);
            for (size_t i = 0; i < row_stride; i++)
                tmp[(size_t)y * row_stride + i] = to_byte(src[i]);
        }
        bytes = tmp;
    }
    int ok = png_image_write_to_file(&png, path, 0, bytes, (png_int_32)row_stride, NULL);
    bgi_free(&heap, tmp);
    if (!ok) {
        st = io_fail(path, &png, "cannot write PNG", message, message_size);
        png_image_free(&png);
        return st;
    }
    png_image_free(&png);
    return BG_OK;
}

/* A 16-bit file as the linear float RGBA image bgi_texture_add takes, keeping all 16 bits: colour as
 * desc's encoding says (the sRGB EOTF of v / 65535, or v / 65535 as it is), alpha always v / 65535.
 * That is bgi_texture_add's rule for 8-bit texels, at the file's precision; any encoding other than
 * sRGB is read as linear here and then rejected by bgi_texture_add if it is not a valid one. */
static bg_status texels_from_16(bg_scene *scene, const unsigned char *samples, const bg_texture_desc *desc,
                                bg_image *image)
{
    size_t count = (size_t)image->width * (size_t)image->height * 4;
    float *texels = bgi_alloc(&scene->allocator, count * sizeof(float));
    float *decode = bgi_alloc(&scene->allocator, 65536 * sizeof(float));
    if (!texels || !decode) {
        bgi_free(&scene->allocator, texels);
        bgi_free(&scene->allocator, decode);
        return BG_ERR_OUT_OF_MEMORY;
    }
    bool srgb = !desc || desc->encoding == BG_TEXTURE_SRGB;
    for (unsigned v = 0; v < 65536; v++)
        decode[v] = (float)(srgb ? bgi_srgb_to_linear(v / 65535.0) : v / 65535.0);
    for (size_t i = 0; i < count; i++) {
        unsigned v = sample_16(samples + 2 * i);
        texels[i] = i % 4 == 3 ? (float)(v / 65535.0) : decode[v];
    }
    bgi_free(&scene->allocator, decode);
    image->format = BG_PIXEL_RGBA32F;
    image->pixels = texels;
    return BG_OK;
}

bg_status bg_scene_load_texture_png(bg_scene *scene, const char *path, const bg_texture_desc *desc,
                                    uint32_t *out_texture)
{
    static const char where[] = "bg_scene_load_texture_png";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!path)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: path is NULL", where);
    if (!out_texture)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_texture is NULL", where);
    char msg[BG_MESSAGE_SIZE];
    bg_png_reader r;
    unsigned char *samples;
    bg_status st = bgi_png_reader_open(&r, path, msg, sizeof msg);
    if (st == BG_OK)
        st = read_samples(&r, &scene->allocator, &samples, msg, sizeof msg);
    if (st != BG_OK)
        return bgi_scene_fail(scene, st, "%s: %s", where, msg);
    /* 8-bit samples are an RGBA8 image as they stand; 16-bit ones become linear floats. */
    bg_image image = {r.width, r.height, BG_PIXEL_RGBA8, 0, samples};
    if (r.bits == 16 && texels_from_16(scene, samples, desc, &image) != BG_OK) {
        bgi_free(&scene->allocator, samples);
        return bgi_scene_fail(scene, BG_ERR_OUT_OF_MEMORY, "%s: %s: out of memory", where, path);
    }
    if (image.pixels != samples)
        bgi_free(&scene->allocator, samples);
    st = bgi_texture_add(scene, where, &image, desc, out_texture);
    bgi_free(&scene->allocator, image.pixels);
    return st;
}
