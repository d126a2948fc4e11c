/* What every benchmark and stress program shares: a clock, run statistics, a headless GPU session,
 * CSV output and progress lines. Timing belongs here, never in a pass/fail test (docs/architecture.md, "Tests"). */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <stdbool.h>
#include <stdio.h>

#include "betelgeuse.h"

/* Wall clock in milliseconds (CLOCK_MONOTONIC). */
double bench_now_ms(void);

/* Statistics of n timed runs; times is sorted in place. */
typedef struct bench_times {
    int runs;
    double median, min, max;
} bench_times;
bench_times bench_times_of(double *times, int n);

/* A headless GL context, a MACS context over it (float depth allowed) and a default renderer. */
typedef struct bench_gpu {
    macs_headless *headless;
    macs_context *context;
    bg_renderer *renderer;
    char renderer_name[128]; /* GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" */
} bench_gpu;
/* Opens the session on the backend MACS_TEST_BACKEND names (osmesa or egl; default OSMesa).
 * On failure prints the reason to stderr and returns false, with nothing left open. */
bool bench_gpu_open(bench_gpu *gpu);
void bench_gpu_close(bench_gpu *gpu);
/* A further renderer on the session's context; desc->context is filled in. NULL + stderr on failure. */
bg_renderer *bench_gpu_renderer(bench_gpu *gpu, bg_renderer_desc desc);

/* An RGBA8 or RGBA32F image with its own pixels; free with bench_image_free. */
bool bench_image_alloc(bg_image *image, int width, int height, bg_pixel_format format);
void bench_image_free(bg_image *image);

/* Builds a shared scene (examples/scenes) into a new scene; NULL + stderr on failure. */
struct scene_params;
bg_scene *bench_scene(int id, const struct scene_params *params);

/* The output folder every bench program takes as its first argument, default bench/out. */
const char *bench_out_dir(int argc, char **argv);

/* Opens dir/name for writing (creating dir) and writes the header line; NULL + stderr on failure. */
FILE *bench_csv_open(const char *dir, const char *name, const char *header);

/* Quick mode (QUICK=1 in the environment): fewer runs and smaller series. */
bool bench_quick(void);

/* A progress line on stderr, prefixed with the seconds since the program started. */
void bench_progress(const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

#endif
