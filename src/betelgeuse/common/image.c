/* Validation of caller-owned images. */
#include "image.h"

#include <stdio.h>
#include <string.h>


size_t bgi_image_pixel_size(bg_pixel_format format)
{
    switch (format) {
    case BG_PIXEL_RGBA8: return 4;
    case BG_PIXEL_RGBA32F: return 16;
    }
    return 0;
}

bg_status bgi_image_check(const bg_image *image, size_t *out_stride, char *message, size_t size)
{
    if (!image) {
        snprintf(message, size, "image is NULL");
        return BG_ERR_INVALID_ARGUMENT;
    }
    if (image->width <= 0 || image->width > BG_MAX_IMAGE_SIDE) {
        snprintf(message, size, "image width = %d is outside [1, %d]", image->width, BG_MAX_IMAGE_SIDE);
        return BG_ERR_INVALID_ARGUMENT;
    }
    if (image->height <= 0 || image->height > BG_MAX_IMAGE_SIDE) {
        snprintf(message, size, "image height = %d is outside [1, %d]", image->height, BG_MAX_IMAGE_SIDE);
        return BG_ERR_INVALID_ARGUMENT;
    }
    size_t pixel = bgi_image_pixel_size(image->format);
    if (pixel == 0) {
        snprintf(message, size, "image format = %d is not a bg_pixel_format", (int)image->format);
        return BG_ERR_INVALID_ARGUMENT;
    }
    if (!image->pixels) {
        snprintf(message, size, "image pixels is NULL");
        return BG_ERR_INVALID_ARGUMENT;
    }
    size_t row = (size_t)image->width * pixel;
    size_t stride = image->stride ? image->stride : row;
    if (stride < row) {
        snprintf(message, size, "image stride = %zu is smaller than a row (%zu bytes)", image->stride, row);
        return BG_ERR_INVALID_ARGUMENT;
    }
    if (image->format == BG_PIXEL_RGBA32F && stride % sizeof(float) != 0) {
        snprintf(message, size, "image stride = %zu is not a multiple of 4 for RGBA32F", image->stride);
        return BG_ERR_INVALID_ARGUMENT;
    }
    *out_stride = stride;
    return BG_OK;
}

void bgi_message_copy(char *dst, size_t size, const char *message)
{
    if (!dst || size == 0)
        return;
    size_t n = strlen(message);
    if (n >= size)
        n = size - 1;
    memcpy(dst, message, n);
    dst[n] = '\0';
}
