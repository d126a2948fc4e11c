/* The sRGB transfer functions (IEC 61966-2-1), exact piecewise form. */
#ifndef BG_SRGB_H
#define BG_SRGB_H

/* Encoded [0, 1] to linear: c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055)^2.4. */
double bgi_srgb_to_linear(double c);
/* Linear [0, 1] to encoded: l <= 0.0031308 ? 12.92 l : 1.055 l^(1/2.4) - 0.055. */
double bgi_linear_to_srgb(double l);
/* bgi_srgb_to_linear(k / 255.0) for every 8-bit code k (srgb_table.c): the one decode both
 * renderers apply to an sRGB RGBA8 texture's colour channels where they sample it. */
extern const double bgi_srgb_table[256];

#endif
