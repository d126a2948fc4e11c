/* Timed renders and their error: the one way every benchmark measures a case, so that numbers from
 * different programs mean the same thing. */
#ifndef BENCH_MEASURE_H
#define BENCH_MEASURE_H

#include <stdio.h>

#include "bench_util.h"
#include "scenes/image_metrics.h"

/* Silhouette threshold of the comparisons (0..255): a reference pixel whose neighbour differs by more
 * is a silhouette pixel, left out of the "interior" set. The same value the paper benchmark always used. */
#define BENCH_SILHOUETTE 24

/* A case whose warm-up render takes longer than BENCH_SLOW_MS is timed BENCH_SLOW_RUNS times at most,
 * so that the slowest points of a series do not take most of the run (bench_times.runs says how many). */
#define BENCH_SLOW_MS 1500.0
#define BENCH_SLOW_RUNS 3

/* One untimed warm-up render (shader compilation, allocation, llvmpipe's first-use variants), then
 * `runs` timed renders back to back (fewer for slow cases, above). GPU times are wall times of
 * bg_render_gpu, including the read-back into the caller's image. On failure prints the renderer's
 * message and returns false. */
bool bench_time_gpu(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings, bg_image *image,
                    int runs, bench_times *out);
/* The same for the CPU reference renderer. */
bool bench_time_cpu(bg_scene *scene, const bg_render_settings *settings, bg_image *image, int runs,
                    bench_times *out);

/* The error columns every table and CSV uses, from a comparison against the CPU reference. */
typedef struct bench_error {
    double psnr_db;     /* over all pixels; IMAGE_METRICS_PSNR_IDENTICAL when identical */
    double max_abs;     /* largest channel error, 0..255 */
    double mean_abs;    /* mean channel error, 0..255 */
    double over_share;  /* share of pixels with a channel off by more than 8/255 */
    double interior_max;/* largest channel error away from silhouettes */
} bench_error;
/* Compares test against reference (RGBA8 images of one size). */
bench_error bench_error_of(const bg_image *reference, const bg_image *test);

/* "psnr_db,max_abs,mean_abs,over_share,interior_max" for CSV headers, and the matching row values. */
#define BENCH_ERROR_CSV_HEADER "psnr_db,max_abs,mean_abs,over_share,interior_max"
void bench_error_csv(FILE *f, const bench_error *e);
/* A short human-readable form: "PSNR 71.1 dB, max 2, mean 0.005, over 0.0%". */
char *bench_error_text(const bench_error *e, char *buffer, size_t size);

/* Passes of every kind the last frame drew. */
int bench_total_passes(const bg_render_stats *stats);

/* The machine, GL renderer and thread settings, printed at the top of every benchmark's output. */
void bench_print_setup(FILE *f, const bench_gpu *gpu, int runs);

#endif
