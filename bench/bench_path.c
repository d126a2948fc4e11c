/* The path integrator's cost (docs/shading.md 13, docs/gpu_pipeline.md "The path integrator"): the
 * Cornell-like box (examples/scenes/path_box.c) at max_depth 5, rendered with BG_INTEGRATOR_PATH on
 * the GPU (both fused plans) and by the CPU reference, in milliseconds per sample (the median of
 * the timed renders of SAMPLES samples each, divided by SAMPLES), and the Whitted image of the same
 * box for scale.
 *
 * Usage: bench_path [out_dir]   (default bench/out; 256 x 256, QUICK=1 for 64 x 64)
 * Prints a table and writes out_dir/path.csv (renderer,integrator,size,samples,runs,median_ms,
 * ms_per_sample). */
#include <stdio.h>

#include "lib/bench_measure.h"
#include "lib/bench_util.h"
#include "scenes/path_box.h"

#define SAMPLES 4
#define RUNS 3
#define MAX_DEPTH 5

typedef struct path_case {
    const char *renderer;   /* "cpu", or the plan's name */
    bg_gpu_plan plan;
    bg_integrator integrator;
} path_case;

static const path_case cases[] = {
    {"fused", BG_PLAN_FUSED, BG_INTEGRATOR_PATH},
    {"fused_tree", BG_PLAN_FUSED_TREE, BG_INTEGRATOR_PATH},
    {"cpu", BG_PLAN_AUTO, BG_INTEGRATOR_PATH},
    {"fused", BG_PLAN_FUSED, BG_INTEGRATOR_WHITTED},
    {"cpu", BG_PLAN_AUTO, BG_INTEGRATOR_WHITTED},
};
#define CASE_COUNT (int)(sizeof cases / sizeof cases[0])

int main(int argc, char **argv)
{
    int size = bench_quick() ? 64 : 256;
    FILE *csv = bench_csv_open(bench_out_dir(argc, argv), "path.csv",
                               "renderer,integrator,size,samples,runs,median_ms,ms_per_sample");
    if (!csv)
        return 1;
    bench_gpu gpu;
    bg_scene *scene = NULL;
    bg_image image;
    if (!bench_gpu_open(&gpu)) {
        fclose(csv);
        return 1;
    }
    int status = 0;
    if (bg_scene_create(NULL, &scene) != BG_OK || path_box_cornell(scene) != BG_OK ||
        !bench_image_alloc(&image, size, size, BG_PIXEL_RGBA8)) {
        fprintf(stderr, "bench_path: cannot build the box: %s\n", scene ? bg_scene_error_message(scene) : "no scene");
        bg_scene_destroy(scene);
        bench_gpu_close(&gpu);
        fclose(csv);
        return 1;
    }
    printf("Cornell-like box, %dx%d, max_depth %d, %d samples a render, medians of %d (%s)\n", size, size, MAX_DEPTH,
           SAMPLES, RUNS, gpu.renderer_name);
    printf("%-12s %-8s %10s %14s\n", "renderer", "integ.", "median ms", "ms per sample");
    for (int c = 0; c < CASE_COUNT; c++) {
        const path_case *k = &cases[c];
        bg_render_settings set = bg_render_settings_init();
        set.samples = SAMPLES;
        set.max_depth = MAX_DEPTH;
        set.integrator = k->integrator;
        set.gpu_plan = k->plan;
        bench_times t;
        bool cpu = k->plan == BG_PLAN_AUTO;
        bool ok = cpu ? bench_time_cpu(scene, &set, &image, RUNS, &t)
                      : bench_time_gpu(gpu.renderer, scene, &set, &image, RUNS, &t);
        if (!ok) {
            status = 1;
            continue;
        }
        const char *integrator = k->integrator == BG_INTEGRATOR_PATH ? "path" : "whitted";
        printf("%-12s %-8s %10.1f %14.2f\n", k->renderer, integrator, t.median, t.median / SAMPLES);
        fprintf(csv, "%s,%s,%d,%d,%d,%.3f,%.3f\n", k->renderer, integrator, size, SAMPLES, t.runs, t.median,
                t.median / SAMPLES);
        fflush(stdout);
    }
    bench_image_free(&image);
    bg_scene_destroy(scene);
    bench_gpu_close(&gpu);
    if (fclose(csv) != 0) {
        fprintf(stderr, "bench_path: writing path.csv failed\n");
        status = 1;
    }
    return status;
}
