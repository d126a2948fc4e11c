/* Which pixels of which frame a render computes, and where its camera rays go through them: the crop
 * window (settings.frame_*, window_*) and the sample pattern (settings.samples), both renderers
 * alike (docs/shading.md 1 and 1.1). */
#ifndef BG_RENDER_VIEW_H
#define BG_RENDER_VIEW_H

#include "betelgeuse.h"

/* Sample positions are multiples of 2^-BGI_SAMPLE_BITS of a pixel: x + position is then exact in
 * float for every pixel column or row x of a frame up to 2^(24 - BGI_SAMPLE_BITS) = 16384. */
#define BGI_SAMPLE_BITS 10

typedef struct bgi_render_view {
    int frame_width, frame_height; /* the full frame */
    int x0, y0;                    /* the image's top-left pixel in the frame */
    int width, height;             /* the image */
    int samples;                   /* per pixel, >= 1 */
    int sample_first, sample_count; /* the samples this call computes and averages (all of them on the
                                       CPU; one per pass on the GPU), counted in the order they are
                                       taken: k is sample bgi_sample_order(samples, k) */
} bgi_render_view;

/* Fills view from settings for an image of width x height (already checked), all samples; on bad
 * settings writes "<where>: settings.<field> ..." into message and returns BG_ERR_INVALID_ARGUMENT. */
bg_status bgi_render_view_make(const bg_render_settings *settings, int width, int height, const char *where,
                               bgi_render_view *view, char *message, size_t size);

/* The position of sample s (0 .. samples - 1) inside its pixel, from the pixel's top-left corner, x
 * right and y down, each in (0, 1) (docs/shading.md 1.1); (0.5, 0.5) for one sample. */
void bgi_sample_position(int samples, int s, double *px, double *py);

/* The sample of the pattern of `samples` (0 .. samples - 1, the s of bgi_sample_position and of the
 * distribution effects' points) taken k-th (k = 0 .. samples - 1): a permutation of the samples such
 * that every first k of them spread over the pixel (docs/shading.md 1.1). sample_first and
 * sample_count of a view count in this order; 0 for one sample. */
int bgi_sample_order(int samples, int k);
/* Step 2 of the order: index t's cell, its mixed-radix digits spread over the axes. */
int bgi_sample_index_cell(int samples, int t);

/* The rows of the pattern of n samples: the largest divisor of n not above sqrt(n); columns = n / rows. */
int bgi_sample_rows(int n);

/* Calls settings->progress (if any) with fraction; false when it asks to cancel. */
bool bgi_render_progress(const bg_render_settings *settings, double fraction);
/* Calls settings->rows_done (if any) with rows [y0, y1). */
void bgi_render_rows_done(const bg_render_settings *settings, int y0, int y1);

#endif
