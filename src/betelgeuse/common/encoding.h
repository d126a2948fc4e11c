/* The output encoding of an 8-bit channel, the one rule both renderers write RGBA8 pixels by. */
#ifndef BG_ENCODING_H
#define BG_ENCODING_H

#include <stdint.h>

#include "betelgeuse.h"

/* An 8-bit channel: floor(clamp(x, 0, 1) * 255 + 0.5) after the encoding. */
uint8_t bgi_encode_channel(double linear, bg_output_encoding encoding);

#endif
