/* The last step of a frame into the caller's image: a finished RGBA8 or RGBA32F texture read back. */
#include <string.h>

#include "../../common/alloc.h"
#include "shared.h"

void *bgi_gpu_read_back_buffer(bg_renderer *r, size_t bytes)
{
    if (r->readback_size >= bytes)
        return r->readback;
    bgi_free(&r->allocator, r->readback);
    r->readback = bgi_alloc(&r->allocator, bytes);
    r->readback_size = r->readback ? bytes : 0;
    if (!r->readback)
        bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the read-back buffer (%zu bytes)", bytes);
    return r->readback;
}

void bgi_gpu_copy_rows(const unsigned char *texels, size_t src_stride, int height, int x0, int width, int y0,
                       int count, size_t texel, bool opaque, unsigned char *dst, size_t stride)
{
    size_t bytes = (size_t)width * texel;
    for (int k = 0; k < count; k++) {
        /* GL rows run bottom-up, the caller's top-down. */
        const unsigned char *src = texels + (size_t)(height - 1 - (y0 + k)) * src_stride + (size_t)x0 * texel;
        unsigned char *d = dst + (size_t)k * stride;
        memcpy(d, src, bytes);
        if (texel == 16 && opaque) {
            /* The image is opaque; a plan's float target may use alpha for its own bookkeeping. */
            float one = 1.0f;
            for (int x = 0; x < width; x++)
                memcpy(d + (size_t)x * 16 + 12, &one, sizeof one);
        }
    }
}

bg_status bgi_gpu_read_back(bg_renderer *r, macs_texture *texture, bg_image *image, size_t stride, bool opaque)
{
    size_t w = (size_t)image->width, h = (size_t)image->height;
    size_t texel = image->format == BG_PIXEL_RGBA32F ? 16 : 4;
    size_t row = w * texel;
    const unsigned char *src = bgi_gpu_read_back_buffer(r, row * h);
    if (!src)
        return BG_ERR_OUT_OF_MEMORY;
    macs_status ms = macs_texture_read(texture, r->readback, 0);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "reading the image back");
    bgi_gpu_copy_rows(src, row, image->height, 0, image->width, 0, image->height, texel, opaque, image->pixels,
                      stride);
    return BG_OK;
}

bool bgi_gpu_read_park(bg_renderer *r, macs_texture *texture, bool opaque)
{
    if (!r->defer_reads)
        return false;
    r->parked = texture;
    r->parked_opaque = opaque;
    return true;
}

bg_status bgi_gpu_read_back_last(bg_renderer *r, macs_texture *texture, bg_image *image, size_t stride, bool opaque)
{
    if (bgi_gpu_read_park(r, texture, opaque))
        return BG_OK;
    return bgi_gpu_read_back(r, texture, image, stride, opaque);
}
