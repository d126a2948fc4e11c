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

bg_status bgi_gpu_read_back(bg_renderer *r, macs_texture *texture, bg_image *image, size_t stride, bool opaque)
{
    size_t w = (size_t)image->width, h = (size_t)image->height;
    bool as_float = image->format == BG_PIXEL_RGBA32F;
    size_t row = w * (as_float ? 16 : 4);
    const unsigned char *src = bgi_gpu_read_back_buffer(r, row * h);
    if (!src)
        return BG_ERR_OUT_OF_MEMORY;
    macs_status ms = macs_texture_read(texture, r->readback, 0);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "reading the image back");
    /* GL rows run bottom-up, the caller's top-down. */
    for (size_t y = 0; y < h; y++) {
        unsigned char *dst = (unsigned char *)image->pixels + y * stride;
        memcpy(dst, src + (h - 1 - y) * row, row);
        if (as_float && opaque) {
            /* The image is opaque; a plan's float target may use alpha for its own bookkeeping. */
            float one = 1.0f;
            for (size_t x = 0; x < w; x++)
                memcpy(dst + x * 16 + 12, &one, sizeof one);
        }
    }
    return BG_OK;
}
