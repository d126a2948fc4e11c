/* Scaling series on the GPU path, each point with its time and its error against the CPU reference:
 * objects (many_spheres: N spheres in front of a wall), lights (many_lights), bounce depth (glass) and
 * resolution (paper_earth_shadow).
 *
 * Usage: bench_scaling [out_dir]   (default bench/out; QUICK=1 for fewer points, runs and pixels)
 * Writes out_dir/scaling_{objects,lights,depth,resolution}.csv. */
#include <string.h>

#include "lib/bench_measure.h"
#include "scenes/scenes.h"

typedef enum series_kind { SERIES_OBJECTS, SERIES_LIGHTS, SERIES_DEPTH, SERIES_RESOLUTION } series_kind;

typedef struct series {
    series_kind kind;
    const char *name;    /* CSV file scaling_<name>.csv */
    const char *x_label; /* what x counts */
    scene_id scene;
    int x[8], count;           /* the full series */
    int quick_x[8], quick_count;
} series;

static const series all_series[] = {
    {SERIES_OBJECTS, "objects", "spheres (plus one wall plane)", SCENE_MANY_SPHERES,
     {1, 2, 4, 8, 16, 32, 64}, 7, {1, 4, 16}, 3},
    {SERIES_LIGHTS, "lights", "point lights", SCENE_MANY_LIGHTS, {1, 2, 3, 4, 5, 6, 7, 8}, 8, {1, 2, 4, 8}, 4},
    {SERIES_DEPTH, "depth", "bounce levels (max_depth)", SCENE_GLASS, {0, 1, 2, 3, 4, 5, 6}, 7, {0, 2, 4, 6}, 4},
    {SERIES_RESOLUTION, "resolution", "image side (pixels)", SCENE_PAPER_EARTH_SHADOW, {256, 512, 1024, 2048}, 4,
     {256, 512, 1024}, 3},
};

/* One point of a series: builds its scene, times both renderers, prints and writes a row. */
static bool run_point(bench_gpu *gpu, const series *s, int x, int size, int gpu_runs, int cpu_runs, FILE *csv)
{
    scene_params params;
    memset(&params, 0, sizeof params);
    bg_render_settings settings = bg_render_settings_init();
    switch (s->kind) {
    case SERIES_OBJECTS: params.spheres = x; break;
    case SERIES_LIGHTS: params.lights = x; break;
    case SERIES_DEPTH: settings.max_depth = x; break;
    case SERIES_RESOLUTION: size = x; break;
    }
    bg_scene *scene = bench_scene(s->scene, &params);
    bg_image gi, ci;
    bool ok = scene && bench_image_alloc(&gi, size, size, BG_PIXEL_RGBA8);
    if (ok && !bench_image_alloc(&ci, size, size, BG_PIXEL_RGBA8)) {
        bench_image_free(&gi);
        ok = false;
    }
    if (!ok) {
        bg_scene_destroy(scene);
        return false;
    }
    bench_times tg, tc;
    bg_render_stats stats;
    ok = bench_time_gpu(gpu->renderer, scene, &settings, &gi, gpu_runs, &tg);
    bg_renderer_stats(gpu->renderer, &stats);
    ok = ok && bench_time_cpu(scene, &settings, &ci, cpu_runs, &tc);
    if (ok) {
        int passes = bench_total_passes(&stats);
        bench_error e = bench_error_of(&ci, &gi);
        char text[128];
        printf("%-11s %5d %5d | %8.1f [%7.1f-%7.1f] %d | %8.1f | %6.2f | %5d %4d | %s\n", s->name, x, size,
               tg.median, tg.min, tg.max, tg.runs, tc.median, tc.median / tg.median, passes, stats.ray_sets,
               bench_error_text(&e, text, sizeof text));
        fflush(stdout);
        fprintf(csv, "%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%d,%d,%d,", x, size, tg.median, tg.min, tg.max, tc.median,
                tc.median / tg.median, passes, stats.ray_sets, tg.runs);
        bench_error_csv(csv, &e);
        fputc('\n', csv);
    }
    bench_image_free(&gi);
    bench_image_free(&ci);
    bg_scene_destroy(scene);
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const int gpu_runs = quick ? 3 : 5, cpu_runs = quick ? 1 : 3, size = quick ? 256 : 512;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    printf("== Scaling on the GPU path (%dx%d unless the series is resolution; CPU reference %d run%s)\n", size,
           size, cpu_runs, cpu_runs > 1 ? "s" : "");
    bench_print_setup(stdout, &gpu, gpu_runs);
    printf("%-11s %5s %5s | %-28s | %8s | %6s | %5s %4s | %s\n", "series", "x", "size", "GPU ms median [min-max] n",
           "CPU ms", "CPU/GPU", "passes", "sets", "GPU error vs CPU");
    int status = 0;
    for (size_t i = 0; i < sizeof all_series / sizeof all_series[0] && !status; i++) {
        const series *s = &all_series[i];
        char name[64];
        snprintf(name, sizeof name, "scaling_%s.csv", s->name);
        FILE *csv = bench_csv_open(dir, name,
                                   "x,size,gpu_median_ms,gpu_min_ms,gpu_max_ms,cpu_median_ms,cpu_over_gpu,passes,"
                                   "ray_sets,gpu_runs," BENCH_ERROR_CSV_HEADER);
        if (!csv) {
            status = 1;
            break;
        }
        const int *xs = quick ? s->quick_x : s->x;
        int count = quick ? s->quick_count : s->count;
        for (int k = 0; k < count && !status; k++) {
            bench_progress("scaling: %s = %d (%s on %s)", s->name, xs[k], s->x_label, scenes_name(s->scene));
            status = !run_point(&gpu, s, xs[k], size, gpu_runs, cpu_runs, csv);
        }
        fclose(csv);
    }
    bench_gpu_close(&gpu);
    return status;
}
