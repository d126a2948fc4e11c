/* Test helpers for the GPU threshold tables (gpu_thresholds.h). */
#ifndef UTIL_THRESHOLDS_H
#define UTIL_THRESHOLDS_H

#include "gpu_thresholds.h"

/* Checks that a table of bounds, one row per shared scene in scene_id order, is not blind: for every
 * scene, the CPU reference at width x height against a CPU render through a camera turned right by
 * half a pixel (the classic pixel-centre mistake) must break the scene's row. Fails the test when a
 * row is out of order or lets the offset pass; what names the table in the message. */
void util_thresholds_catch_half_pixel_offset(const gpu_threshold table[SCENE_COUNT], int width, int height,
                                             const char *what);

/* Two GPU renders of one scene (RGBA32F, width x height) by different programs over the same formulas:
 * a pass split into chunks, objects batched or one per pass, a generic shader against a specialised
 * one. GL promises bit-equal results only for the same program on the same inputs (GL 2.1 appendix
 * A, invariance rule 4), and a compiler may contract or order one program's float operations
 * otherwise than another's, so the error model (docs/architecture.md, "Tests") bounds their
 * difference like a float evaluation's from the exact one: both encoded to sRGB RGBA8 and compared
 * with row. Bit-equal images pass at once (as on Mesa, where every split and batch so far agrees to
 * the bit); others print their metrics under label. */
void util_expect_gpu_twins(const float *a, const float *b, int width, int height, const gpu_threshold *row,
                           const char *label);

#endif
