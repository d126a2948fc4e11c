/* PNG files through libpng's simplified API (png_image): size, load, save, and textures.
 * libpng keeps its message in the png_image the caller owns and never prints from here. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "../common/image.h"
#include "../scene/scene_private.h"

static bg_status io_fail(const char *path, const png_image *png, const char *what,
                         char *message, size_t size)
{
    char buf[BG_MESSAGE_SIZE];
    snprintf(buf, sizeof buf, "%s: %s: %s", path, what, png->message[0] ? png->message : "unknown libpng error");
    bg_message_copy(message, size, buf);
    return BG_ERR_IO;
}

static bg_status arg_fail(const char *text, char *message, size_t size)
{
    bg_message_copy(message, size, text);
    return BG_ERR_INVALID_ARGUMENT;
}

/* The checks load and save share: a path, a valid image, and a stride libpng can take. */
static bg_status check_file_and_image(const char *fn, const char *path, const bg_image *image,
                                      size_t *stride, char *message, size_t size)
{
    bg_message_copy(message, size, "");
    char buf[BG_MESSAGE_SIZE], detail[256];
    if (!path) {
        snprintf(buf, sizeof buf, "%s: path is NULL", fn);
        return arg_fail(buf, message, size);
    }
    if (bg_image_check(image, stride, detail, sizeof detail) != BG_OK) {
        snprintf(buf, sizeof buf, "%s: %s", fn, detail);
        return arg_fail(buf, message, size);
    }
    if (*stride > 0x7fffffff) {
        snprintf(buf, sizeof buf, "%s: image stride is too large for libpng", fn);
        return arg_fail(buf, message, size);
    }
    return BG_OK;
}

/* Opens path and reads its header into png; on failure png is already freed by libpng. */
static bg_status begin_read(const char *path, png_image *png, char *message, size_t size)
{
    memset(png, 0, sizeof *png);
    png->version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(png, path))
        return io_fail(path, png, "cannot read PNG header", message, size);
    if (png->width == 0 || png->height == 0 || png->width > BG_MAX_IMAGE_SIDE ||
        png->height > BG_MAX_IMAGE_SIDE) {
        char buf[BG_MESSAGE_SIZE];
        snprintf(buf, sizeof buf, "%s: PNG size %ux%u is outside [1, %d] per side", path,
                 (unsigned)png->width, (unsigned)png->height, BG_MAX_IMAGE_SIDE);
        png_image_free(png);
        bg_message_copy(message, size, buf);
        return BG_ERR_IO;
    }
    png->format = PNG_FORMAT_RGBA;
    return BG_OK;
}

bg_status bg_png_size(const char *path, int *width, int *height, char *message, size_t message_size)
{
    bg_message_copy(message, message_size, "");
    if (!path || !width || !height)
        return arg_fail("bg_png_size: path, width and height must not be NULL", message, message_size);
    png_image png;
    bg_status st = begin_read(path, &png, message, message_size);
    if (st != BG_OK)
        return st;
    *width = (int)png.width;
    *height = (int)png.height;
    png_image_free(&png);
    return BG_OK;
}

/* Reads the whole file as 8-bit RGBA into pixels with the given byte stride (GL order is not
 * applied here: row 0 is the top of the file, as in bg_image). */
static bg_status finish_read(const char *path, png_image *png, void *pixels, size_t stride,
                             char *message, size_t size)
{
    if (!png_image_finish_read(png, NULL, pixels, (png_int_32)stride, NULL)) {
        bg_status st = io_fail(path, png, "cannot read PNG data", message, size);
        png_image_free(png);
        return st;
    }
    png_image_free(png);
    return BG_OK;
}

bg_status bg_png_load(const char *path, bg_image *image, char *message, size_t message_size)
{
    size_t stride;
    bg_status st = check_file_and_image("bg_png_load", path, image, &stride, message, message_size);
    if (st != BG_OK)
        return st;
    char buf[BG_MESSAGE_SIZE];
    png_image png;
    if ((st = begin_read(path, &png, message, message_size)) != BG_OK)
        return st;
    if ((int)png.width != image->width || (int)png.height != image->height) {
        snprintf(buf, sizeof buf, "bg_png_load: %s is %ux%u but image is %dx%d", path,
                 (unsigned)png.width, (unsigned)png.height, image->width, image->height);
        png_image_free(&png);
        return arg_fail(buf, message, message_size);
    }
    if (image->format == BG_PIXEL_RGBA8)
        return finish_read(path, &png, image->pixels, stride, message, message_size);

    /* RGBA32F: read the bytes, then store them divided by 255 (still encoded, as documented). */
    static const bg_allocator heap = {NULL, NULL, NULL, NULL};
    size_t row = (size_t)image->width * 4;
    unsigned char *tmp = bg_alloc(&heap, row * (size_t)image->height);
    if (!tmp) {
        png_image_free(&png);
        bg_message_copy(message, message_size, "bg_png_load: out of memory");
        return BG_ERR_OUT_OF_MEMORY;
    }
    st = finish_read(path, &png, tmp, row, message, message_size);
    if (st == BG_OK) {
        for (int y = 0; y < image->height; y++) {
            float *dst = (float *)((unsigned char *)image->pixels + (size_t)y * stride);
            for (size_t i = 0; i < row; i++)
                dst[i] = (float)(tmp[(size_t)y * row + i] / 255.0);
        }
    }
    bg_free(&heap, tmp);
    return st;
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
        tmp = bg_alloc(&heap, row_stride * (size_t)image->height);
        if (!tmp) {
            bg_message_copy(message, message_size, "bg_png_save: out of memory");
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
    bg_free(&heap, tmp);
    if (!ok) {
        st = io_fail(path, &png, "cannot write PNG", message, message_size);
        png_image_free(&png);
        return st;
    }
    png_image_free(&png);
    return BG_OK;
}

bg_status bg_scene_load_texture_png(bg_scene *scene, const char *path, const bg_texture_desc *desc,
                                    uint32_t *out_texture)
{
    static const char where[] = "bg_scene_load_texture_png";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!path)
        return bg_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: path is NULL", where);
    if (!out_texture)
        return bg_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: out_texture is NULL", where);
    char msg[BG_MESSAGE_SIZE];
    png_image png;
    bg_status st = begin_read(path, &png, msg, sizeof msg);
    if (st != BG_OK)
        return bg_scene_fail(scene, st, "%s: %s", where, msg);
    bg_image image = {(int)png.width, (int)png.height, BG_PIXEL_RGBA8, 0, NULL};
    size_t bytes = (size_t)image.width * (size_t)image.height * 4;
    image.pixels = bg_alloc(&scene->allocator, bytes);
    if (!image.pixels) {
        png_image_free(&png);
        return bg_scene_fail(scene, BG_ERR_OUT_OF_MEMORY, "%s: %s: out of memory", where, path);
    }
    st = finish_read(path, &png, image.pixels, (size_t)image.width * 4, msg, sizeof msg);
    if (st != BG_OK)
        bg_scene_fail(scene, st, "%s: %s", where, msg);
    else
        st = bg_texture_add(scene, where, &image, desc, out_texture);
    bg_free(&scene->allocator, image.pixels);
    return st;
}
