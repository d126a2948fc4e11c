/* The stratified, scrambled sample points the distribution effects spend (docs/shading.md 1.3): for
 * each frame pixel, camera sample s of n and dimension (the lens, one light), a point of the unit
 * square. Over a pixel's n samples every dimension visits each of the n cells of the pixel pattern's
 * grid once, in an order permuted per pixel and dimension, at a jittered place in the cell, so that
 * the dimensions are decorrelated from each other and from the sample's place in the pixel.
 * Everything is small integers held exactly in float, so that glsl110/bg_scramble.glsl computes
 * the same points in GLSL 1.10 (which has no integer bit operations) up to the rounding of the
 * last division. */
#ifndef BG_SCRAMBLE_H
#define BG_SCRAMBLE_H

#include <stdint.h>


/* Dimensions: the lens; light k of the committed order (odd); the glossy lobe of the reflection at
 * a hit of a level-L ray (even, from 2), so that neither kind runs into the other however many. */
#define BGI_DIMENSION_LENS 0
#define BGI_DIMENSION_LIGHT(k) (1 + 2 * (k))
#define BGI_DIMENSION_GLOSSY(level) (2 + 2 * (level))
/* The path integrator's (docs/shading.md 13.2): light slot k (the environment's is light_count) of
 * slots a level, the direction and the event of a hit at level L. Level 0 keeps the lights' and
 * the glossy lobe's dimensions above. */
#define BGI_DIMENSION_PATH_LIGHT(k, level, slots) (1 + 2 * ((k) + (level) * (slots)))
#define BGI_DIMENSION_PATH_DIRECTION(level) (2 + 4 * (level))
#define BGI_DIMENSION_PATH_EVENT(level) (4 + 4 * (level))

typedef struct bgi_sample_point {
    uint32_t pixel_hash; /* the frame pixel's hash, in [0, 4096) */
    int sample;          /* s, 0 .. samples - 1 */
    int samples;         /* n >= 1 */
    int columns, rows;   /* the pixel pattern's grid of n cells */
    int perm_bits;       /* k: the cells are permuted on [0, 2^k), 2^k the power of two >= n */
} bgi_sample_point;

/* Sample s of n of frame pixel (x, y) (x right, y down from the frame's top-left, each < 16384). */
void bgi_sample_point_make(int x, int y, int s, int n, bgi_sample_point *out);

/* The point of the unit square [0, 1)^2 of a dimension (>= 0) at this sample. */
void bgi_sample_square(const bgi_sample_point *point, int dimension, double uv[2]);

/* Shirley and Chiu's concentric map of the unit square onto the unit disc: strata stay compact. */
void bgi_sample_disc(const double uv[2], double xy[2]);

#endif
