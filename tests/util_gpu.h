/* Test helpers for the GPU renderer suites: a renderer on a MACS context, and shared scenes. */
#ifndef UTIL_GPU_H
#define UTIL_GPU_H

#include "betelgeuse.h"
#include "scenes/scenes.h"

/* A headless context, a MACS context on it and a renderer on that. */
typedef struct util_gpu {
    macs_headless *headless;
    macs_context *ctx;
    bg_renderer *renderer;
} util_gpu;

/* A renderer with default settings on ctx, with no stored error; fails the test on error. */
bg_renderer *util_renderer(macs_context *ctx);
/* Opens the whole stack (caps may be NULL); fails the test on error. */
void util_gpu_open(util_gpu *g, const macs_limits *caps);
/* Destroys what util_gpu_open made. */
void util_gpu_close(util_gpu *g);
/* A new scene built as the shared scene id and committed; fails the test on error. */
bg_scene *util_scene(scene_id id);

#endif
