/* A high-contrast edge with a known answer, for the antialiasing tests of both renderers: a white
 * emissive rectangle filling a half-plane of the view on a black background, its edge slanted, no
 * lights, no bounces, so that every sample is exactly 0 or 1 and a pixel's exact value is the share
 * of its area on the bright side (docs/shading.md 1.1: the box filter). */
#ifndef UTIL_COVERAGE_H
#define UTIL_COVERAGE_H

#include "betelgeuse.h"

/* The edge's slant from the image's vertical, degrees. */
#define UTIL_EDGE_DEGREES 20.0

/* A new committed scene: the default camera (at (0, 0, 5) looking at the origin, fov 45), the
 * rectangle in the plane z = 0 covering every point p of the view with
 * cos(a) p.x + sin(a) p.y >= 0, a = UTIL_EDGE_DEGREES. */
bg_scene *util_edge_scene(void);

/* Settings for it: black background, max_depth 0, linear encoding. */
bg_render_settings util_edge_settings(int samples);

/* The exact share of pixel (x, y) of a width x height frame (row 0 at the top) on the bright side. */
double util_edge_coverage(int width, int height, int x, int y);

/* The largest and the mean |red - coverage| over an RGBA32F render of the whole frame. */
void util_edge_error(const float *rgba, int width, int height, double *max_error, double *mean_error);

#endif
