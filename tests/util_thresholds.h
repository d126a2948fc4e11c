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

#endif
