/* Image comparison metrics (docs/architecture.md, "Tests"): two RGBA8 images of one size compared on their RGB
 * channels, once over every pixel and once without the silhouette pixels of the reference, where a
 * sub-pixel shift legitimately changes which object a ray hits. Alpha is ignored. */
#ifndef IMAGE_METRICS_H
#define IMAGE_METRICS_H

#include <stdbool.h>
#include <stddef.h>

#include "betelgeuse.h"

/* A pixel is "over" when some RGB channel differs by more than this (in 0..255 units: 8/255). */
#define IMAGE_METRICS_OVER 8
/* The PSNR reported for identical pixel sets (the true value is infinite). */
#define IMAGE_METRICS_PSNR_IDENTICAL 999.0

/* Differences over one set of pixels; errors in 0..255 units. */
typedef struct image_diff {
    long pixels;          /* pixels in the set */
    double max_abs[3];    /* largest absolute error per channel (R, G, B) */
    double mean_abs[3];   /* mean absolute error per channel */
    double psnr_db;       /* over all RGB values of the set; IMAGE_METRICS_PSNR_IDENTICAL if equal */
    long over_count;      /* pixels with a channel differing by more than IMAGE_METRICS_OVER */
    double over_share;    /* over_count / pixels (0 for an empty set) */
    int worst_x, worst_y; /* a pixel with the largest channel error (row 0 is the first in memory) */
} image_diff;

/* The comparison of a test image against a reference image. */
typedef struct image_metrics {
    int width, height;
    int silhouette_threshold; /* the threshold the silhouette mask was built with */
    image_diff all;           /* every pixel */
    image_diff interior;      /* every pixel that is not a silhouette pixel of the reference */
    long silhouette_pixels;   /* pixels left out of interior */
} image_metrics;

/* Compares test against reference (both RGBA8, same size, any stride). A pixel is a silhouette pixel
 * when one of its (up to 8) neighbours in the reference differs from it by more than
 * silhouette_threshold (0..255) in some RGB channel. Returns false, leaving *out zeroed, when an
 * argument is NULL or the images are not two RGBA8 images of one size. */
bool image_metrics_compare(const bg_image *reference, const bg_image *test, int silhouette_threshold,
                           image_metrics *out);

/* Acne: the failure of float32 self-intersection rules and offsets, as opposed to plain error. A lit
 * surface point that wrongly finds itself (or a touching neighbour) in the way of its light goes
 * dark, and where that happens only now and then it leaves isolated wrong pixels. So, over the
 * pixels that are not silhouette pixels of the reference (the same rule as image_metrics_compare:
 * there a sub-pixel shift legitimately changes which object is seen, and a shadow edge of a point
 * light is as sharp as a silhouette, so it is left out the same way):
 *   shadowed  the test pixel is darker than the reference by more than IMAGE_METRICS_OVER in some
 *             RGB channel and brighter by at most IMAGE_METRICS_ACNE_ROUNDING in none. Blocking a
 *             light removes an additive, non-negative term, so every channel drops or stays (dark
 *             channels of saturated colours cannot drop by 8; requiring it of every channel would
 *             miss acne on a red surface), while ordinary float error moves channels either way.
 *   speckle   some channel differs by more than IMAGE_METRICS_OVER, darker or brighter, while every
 *             neighbour (up to 8) agrees within it in every channel: a lone wrong pixel (a light
 *             leak, or a single self-shadowed one), which a shifted edge or texture never makes.
 * A pixel counts once even when it is both. A uniformly darker image counts as shadowed everywhere:
 * it is an error too large for the thresholds anyway, so the two measures never hide each other. */
#define IMAGE_METRICS_ACNE_ROUNDING 2

typedef struct image_acne {
    long shadowed;        /* interior pixels wrongly darker, as defined above */
    long speckles;        /* interior pixels differing alone */
    long pixels;          /* pixels that are either (the acne count) */
    long interior;        /* pixels examined: not silhouette pixels of the reference */
    int first_x, first_y; /* the first acne pixel in memory order, -1 if none */
} image_acne;

/* Counts the acne of test against reference (both RGBA8, same size, any stride) with the silhouette
 * rule of image_metrics_compare. Returns false, leaving *out zeroed, for bad arguments. */
bool image_metrics_acne(const bg_image *reference, const bg_image *test, int silhouette_threshold, image_acne *out);

/* Counts the non-finite values (NaN, +-Inf) in the four channels of an RGBA32F image; an image that is
 * not RGBA32F, or NULL, counts as (size_t)-1. */
size_t image_metrics_count_nonfinite(const bg_image *image);

/* Writes a one-line summary of m (no newline) into buffer, truncated to size bytes; returns buffer. */
char *image_metrics_format(const image_metrics *m, char *buffer, size_t size);

#endif
