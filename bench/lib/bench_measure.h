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

/* "psnr_db,max_abs,mean_abs,over_share,interior_max" for CSV headers, and the matching row values;
 * BENCH_ERROR_CSV_NAMED("gpu_") gives the same columns named for one renderer ("gpu_psnr_db,..."). */
#define BENCH_ERROR_CSV_NAMED(prefix) \
    prefix "psnr_db," prefix "max_abs," prefix "mean_abs," prefix "over_share," prefix "interior_max"
#define BENCH_ERROR_CSV_HEADER BENCH_ERROR_CSV_NAMED("")
void bench_error_csv(FILE *f, const bench_error *e);
/* A short human-readable form: "PSNR 71.1 dB, max 2, mean 0.005, over 0.0%". */
char *bench_error_text(const bench_error *e, char *buffer, size_t size);
/* A narrower one for tables with several error columns: "71.1 dB max 2" (or "identical"). */
char *bench_error_brief(const bench_error *e, char *buffer, size_t size);

/* The GL work of a frame (bg_render_stats.gl_work) in one short cell: "d 33 p 66 f 98 u 352 up 0
 * rb 4.0 B/px s 1 c 0": draws, program binds, framebuffer binds, uniform calls, bytes uploaded,
 * bytes read back per pixel of width x height, syncs, programs compiled. */
char *bench_work_text(const macs_work *w, int width, int height, char *buffer, size_t size);

/* Passes of every kind the last frame drew. */
int bench_total_passes(const bg_render_stats *stats);

/* The machine, GL renderer and thread settings, printed at the top of every benchmark's output. */
void bench_print_setup(FILE *f, const bench_gpu *gpu, int runs);

/* ---- Interleaved rounds ----
 * Several renderers of one case, timed one frame each per round in a fixed order, so that the slow
 * drift of a shared machine falls on all of them alike and their ratios are measured side by side. */

#define BENCH_MAX_ROUNDS 16

/* Renders one frame of a contestant into image; false (with the reason on stderr) on failure. */
typedef bool (*bench_frame_fn)(void *user, bg_image *image);

/* One renderer in a comparison. The caller fills name, frame, user and image; bench_warm_up sets
 * warm_ms; the caller then sets rounds (bench_rounds_after gives the usual slow-case rule; 0 leaves the
 * contestant out); bench_interleave fills ms and times. */
typedef struct bench_contestant {
    const char *name;
    bench_frame_fn frame;
    void *user;
    bg_image *image;               /* holds the contestant's last frame */
    double warm_ms;                /* the untimed warm-up frame */
    int rounds;                    /* rounds it takes part in, 0 .. BENCH_MAX_ROUNDS: the first ones */
    double ms[BENCH_MAX_ROUNDS];   /* per round, in round order */
    bench_times times;             /* over its rounds */
} bench_contestant;

/* One untimed frame (shader compilation, allocation, llvmpipe's first-use variants), its time in warm_ms. */
bool bench_warm_up(bench_contestant *c);
/* The rounds a case gets after a warm-up of warm_ms: runs, or BENCH_SLOW_RUNS for a slow case. */
int bench_rounds_after(double warm_ms, int runs);
/* Round r draws one frame of every contestant with r < rounds, in list order; label names the case
 * in the progress lines. False as soon as a frame fails. */
bool bench_interleave(bench_contestant *list, int count, const char *label);
/* a's time over b's in the rounds both ran: the median of the per-round ratios (0 when they share none). */
double bench_ratio(const bench_contestant *a, const bench_contestant *b);
/* "n median [min-max]" of a contestant, or "-" when it did not run, for a table cell. */
char *bench_contestant_text(const bench_contestant *c, char *buffer, size_t size);

/* A GPU contestant (bench_gpu_frame's user): one renderer, scene and settings. */
typedef struct bench_gpu_job {
    bg_renderer *renderer;
    bg_scene *scene;
    bg_render_settings settings;
    bg_render_stats stats;   /* of the last frame */
    int frames;              /* frames drawn */
    int recompiled_frames;   /* frames after the first that compiled a program: 0 when the renderer's
                                caches hold, so the timed rounds measure frames, not compilation */
} bench_gpu_job;
bool bench_gpu_frame(void *job, bg_image *image);
/* The CPU reference as a contestant (bench_cpu_frame's user). */
typedef struct bench_cpu_job {
    bg_scene *scene;
    bg_render_settings settings;
} bench_cpu_job;
bool bench_cpu_frame(void *job, bg_image *image);

/* "fused", "fused-tree" or "multipass". */
const char *bench_plan_name(bg_gpu_plan plan);

#endif
