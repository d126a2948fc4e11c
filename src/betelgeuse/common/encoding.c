/* The output encoding of an 8-bit channel (docs/shading.md 10): the CPU reference writes its pixels
 * by it and the GPU renderer its averaged samples, so both give one byte for one radiance. */
#include <math.h>

#include "encoding.h"
#include "srgb.h"

uint8_t bgi_encode_channel(double linear, bg_output_encoding encoding)
{
    double x = linear < 0.0 ? 0.0 : (linear > 1.0 ? 1.0 : linear);
    if (encoding == BG_ENCODING_SRGB)
        x = bgi_linear_to_srgb(x);
    double y = floor(x * 255.0 + 0.5);
    return (uint8_t)(y < 0.0 ? 0.0 : (y > 255.0 ? 255.0 : y));
}
