/* Checks of caller-owned bg_image descriptions, shared by textures and PNG I/O. */
#ifndef BG_IMAGE_H
#define BG_IMAGE_H

#include "betelgeuse.h"

/* Bytes per pixel of a format (0 for unknown formats). */
size_t bgi_image_pixel_size(bg_pixel_format format);
/* Checks size (1 .. 16384 per side), format, pixels and stride; writes the row stride in bytes.
 * On failure writes a message naming the field (without a prefix) and returns
 * BG_ERR_INVALID_ARGUMENT. */
bg_status bgi_image_check(const bg_image *image, size_t *out_stride, char *message, size_t size);
/* Copies message into a caller buffer of size bytes (NULL or 0 is fine), truncating. */
void bgi_message_copy(char *dst, size_t size, const char *message);

#endif
