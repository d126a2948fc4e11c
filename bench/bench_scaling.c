/* Scaling series on the GPU path, each point with its time and its error against the CPU reference:
 * objects (many_spheres: N spheres in front of a wall), lights (many_lights), bounce depth (glass),
 * resolution (paper_earth_shadow) and diffuse (diffuse_spheres: N spheres up to 65536, no bounces,
 * with the time of the commit that builds their object tree).
 *
 * Usage: bench_scaling [out_dir]   (default bench/out; QUICK=1 for fewer points, runs and pixels;
 *                                   SCALING_SERIES=diffuse,lights runs only the series named)
 * Writes out_dir/scaling_{objects,lights,depth,resolution,diffuse}.csv. */
#include <stdlib.h>
#include <string.h>

#include "lib/bench_measure.h"
#include "lib/diffuse_spheres.h"
#include "scenes/scenes.h"

typedef enum series_kind {
    SERIES_OBJECTS, SERIES_LIGHTS, SERIES_DEPTH, SERIES_RESOLUTION, SERIES_DIFFUSE, SERIES_DIFFUSE_CLOUD
} series_kind;

/* The series that build diffuse_spheres scenes of their own, and in which layout. */
static bool builds_diffuse(series_kind kind)
{
    return kind == SERIES_DIFFUSE || kind == SERIES_DIFFUSE_CLOUD;
}

typedef struct series {
    series_kind kind;
    const char *name;    /* CSV file scaling_<name>.csv, and the name SCALING_SERIES lists */
    const char *x_label; /* what x counts */
    scene_id scene;      /* the shared scene it varies; SERIES_DIFFUSE builds its own */
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
    {SERIES_DIFFUSE, "diffuse", "diffuse spheres in a layer, 2 lights, no bounces", SCENE_COUNT,
     {1, 16, 256, 4096, 65536}, 5, {1, 256, 4096}, 3},
    {SERIES_DIFFUSE_CLOUD, "diffuse_cloud", "diffuse spheres in a cube, 2 lights, no bounces", SCENE_COUNT,
     {1, 16, 256, 4096, 65536}, 5, {1, 256, 4096}, 3},
};

#define SERIES_COUNT (int)(sizeof all_series / sizeof all_series[0])

/* Up to this many objects a multipass frame is timed like any other (the objects series goes to 64).
 * Beyond it the diffuse series probes which plan BG_PLAN_AUTO takes and skips the frame where it is
 * the multipass: that plan draws intersection and shadow passes per batch of objects, thousands of
 * them at the series' 65536 spheres, and would take most of the run. */
#define MULTIPASS_TIMED_OBJECTS 32
/* The probe's image side: small enough that even a multipass frame costs little beyond its passes. */
#define PROBE_SIZE 16
/* First commits timed per diffuse point, the median reported. */
#define COMMIT_RUNS 5
#define QUICK_COMMIT_RUNS 3

/* ---- choosing series ---- */

/* Steps through a comma list: the next name's start and length, false at the end of the list. */
static bool next_name(const char **list, const char **name, size_t *length)
{
    if (!**list)
        return false;
    *name = *list;
    *length = strcspn(*list, ",");
    *list += *length + ((*list)[*length] ? 1 : 0);
    return true;
}

static bool name_is(const char *name, size_t length, const char *series_name)
{
    return strlen(series_name) == length && strncmp(name, series_name, length) == 0;
}

/* Whether SCALING_SERIES names the series (unset or empty names every one). */
static bool series_selected(const char *list, const char *series_name)
{
    if (!list || !*list)
        return true;
    const char *name;
    size_t length;
    while (next_name(&list, &name, &length))
        if (name_is(name, length, series_name))
            return true;
    return false;
}

/* False, with the valid names on stderr, when SCALING_SERIES names a series there is not. */
static bool series_list_valid(const char *list)
{
    const char *name;
    size_t length;
    while (list && next_name(&list, &name, &length)) {
        bool known = false;
        for (int i = 0; i < SERIES_COUNT && !known; i++)
            known = name_is(name, length, all_series[i].name);
        if (!known) {
            fprintf(stderr, "SCALING_SERIES: unknown series '%.*s'; the series are:", (int)length, name);
            for (int i = 0; i < SERIES_COUNT; i++)
                fprintf(stderr, " %s", all_series[i].name);
            fputc('\n', stderr);
            return false;
        }
    }
    return true;
}

/* ---- a point's scene ---- */

/* A new diffuse scene and the time of its first commit. That commit validates and copies every
 * object and builds the object tree from nothing; later commits of the same scene only keep or
 * refit the tree, so they would not measure the build. */
static bg_scene *diffuse_scene_committed(int n, diffuse_layout layout, double *commit_ms)
{
    bg_scene *scene = NULL;
    if (bg_scene_create(NULL, &scene) != BG_OK) {
        fprintf(stderr, "cannot create a scene\n");
        return NULL;
    }
    bg_status st = diffuse_spheres_build(scene, n, layout);
    double t0 = bench_now_ms();
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    *commit_ms = bench_now_ms() - t0;
    if (st != BG_OK) {
        const char *message = bg_scene_error_message(scene);
        fprintf(stderr, "cannot build diffuse_spheres (%d): %s\n", n, *message ? message : bg_status_string(st));
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

/* Builds the diffuse scene `runs` times, each time timing its first commit; keeps the last scene
 * for rendering and gives the median commit time. */
static bg_scene *diffuse_scene_timed(int n, diffuse_layout layout, int runs, double *commit_ms)
{
    double times[COMMIT_RUNS];
    bg_scene *scene = NULL;
    for (int r = 0; r < runs; r++) {
        bg_scene_destroy(scene);
        scene = diffuse_scene_committed(n, layout, &times[r]);
        if (!scene)
            return NULL;
    }
    *commit_ms = bench_times_of(times, runs).median;
    return scene;
}

/* The point's committed scene, with x applied to the scene, the settings or the image side.
 * commit_ms is negative where the series does not time commits (the shared scenes commit inside
 * their builder). */
static bg_scene *point_scene(const series *s, int x, int commit_runs, bg_render_settings *settings, int *size,
                             double *commit_ms)
{
    scene_params params;
    memset(&params, 0, sizeof params);
    *commit_ms = -1.0;
    switch (s->kind) {
    case SERIES_OBJECTS: params.spheres = x; break;
    case SERIES_LIGHTS: params.lights = x; break;
    case SERIES_DEPTH: settings->max_depth = x; break;
    case SERIES_RESOLUTION: *size = x; break;
    case SERIES_DIFFUSE: return diffuse_scene_timed(x, DIFFUSE_LAYER, commit_runs, commit_ms);
    case SERIES_DIFFUSE_CLOUD: return diffuse_scene_timed(x, DIFFUSE_CLOUD, commit_runs, commit_ms);
    }
    return bench_scene(s->scene, &params);
}

static const char *series_scene_name(const series *s)
{
    return builds_diffuse(s->kind) ? "diffuse_spheres" : scenes_name(s->scene);
}

/* ---- measuring ---- */

/* What one point measured. */
typedef struct point_result {
    int x, size;
    double commit_ms;      /* median first commit; negative where not timed */
    bool gpu_measured;     /* false: the GPU frame was skipped as too slow (a multipass probe) */
    bench_times gpu, cpu;
    bg_render_stats stats; /* of the last GPU frame, or of the probe when skipped */
    bench_error error;     /* GPU against CPU, where the GPU was measured */
} point_result;

/* Whether the GPU frame is worth timing. Only the diffuse series goes far beyond
 * MULTIPASS_TIMED_OBJECTS; there a PROBE_SIZE frame with the settings' plan (BG_PLAN_AUTO) says
 * which plan the real frame would take, and only a fused one is timed. */
static bool gpu_frame_worth_timing(bench_gpu *gpu, const series *s, int x, bg_scene *scene,
                                   const bg_render_settings *settings, point_result *r)
{
    r->gpu_measured = true;
    if (!builds_diffuse(s->kind) || x <= MULTIPASS_TIMED_OBJECTS)
        return true;
    bg_image probe;
    if (!bench_image_alloc(&probe, PROBE_SIZE, PROBE_SIZE, BG_PIXEL_RGBA8))
        return false;
    bool ok = bg_render_gpu(gpu->renderer, scene, settings, &probe) == BG_OK;
    if (!ok)
        fprintf(stderr, "GPU probe failed: %s\n", bg_renderer_error_message(gpu->renderer));
    bg_renderer_get_stats(gpu->renderer, &r->stats);
    r->gpu_measured = r->stats.plan != BG_PLAN_MULTIPASS;
    bench_image_free(&probe);
    return ok;
}

/* Times both renderers on the point's scene (the GPU unless skipped) and compares their images. */
static bool measure_point(bench_gpu *gpu, const series *s, bg_scene *scene, const bg_render_settings *settings,
                          int gpu_runs, int cpu_runs, point_result *r)
{
    bg_image gi, ci;
    if (!bench_image_alloc(&gi, r->size, r->size, BG_PIXEL_RGBA8))
        return false;
    if (!bench_image_alloc(&ci, r->size, r->size, BG_PIXEL_RGBA8)) {
        bench_image_free(&gi);
        return false;
    }
    bool ok = gpu_frame_worth_timing(gpu, s, r->x, scene, settings, r);
    if (ok && r->gpu_measured) {
        ok = bench_time_gpu(gpu->renderer, scene, settings, &gi, gpu_runs, &r->gpu);
        bg_renderer_get_stats(gpu->renderer, &r->stats);
    }
    ok = ok && bench_time_cpu(scene, settings, &ci, cpu_runs, &r->cpu);
    if (ok && r->gpu_measured)
        r->error = bench_error_of(&ci, &gi);
    bench_image_free(&gi);
    bench_image_free(&ci);
    return ok;
}

/* ---- output ---- */

/* The table's columns: the header and every row share these widths. */
#define TABLE_FORMAT(x, number) "%-11s %5" x " %5" x " | %9s %-10s | %-28s | %8" number " | %7s | %-11s | %s\n"
#define CSV_HEADER                                                                                         \
    "x,size,gpu_median_ms,gpu_min_ms,gpu_max_ms,cpu_median_ms,cpu_over_gpu,passes,ray_sets,gpu_runs," \
    BENCH_ERROR_CSV_HEADER ",plan,commit_ms"

static void print_table_header(void)
{
    printf(TABLE_FORMAT("s", "s"), "series", "x", "size", "commit ms", "plan", "GPU ms median [min-max] n", "CPU ms",
           "CPU/GPU", "passes sets", "GPU error vs CPU");
}

/* A table row: "-" in the columns a point did not measure, and why the GPU was skipped. */
static void print_row(const series *s, const point_result *r)
{
    char commit[24] = "-", gpu[48] = "-", ratio[16] = "-", counts[24] = "-", error[160];
    if (r->commit_ms >= 0.0)
        snprintf(commit, sizeof commit, "%.2f", r->commit_ms);
    if (r->gpu_measured) {
        snprintf(gpu, sizeof gpu, "%8.1f [%7.1f-%7.1f] %d", r->gpu.median, r->gpu.min, r->gpu.max, r->gpu.runs);
        snprintf(ratio, sizeof ratio, "%.2f", r->cpu.median / r->gpu.median);
        snprintf(counts, sizeof counts, "%5d %4d", bench_total_passes(&r->stats), r->stats.ray_sets);
        bench_error_text(&r->error, error, sizeof error);
    } else {
        snprintf(error, sizeof error, "GPU skipped: a %dx%d probe ran the multipass (too slow beyond %d objects)",
                 PROBE_SIZE, PROBE_SIZE, MULTIPASS_TIMED_OBJECTS);
    }
    printf(TABLE_FORMAT("d", ".1f"), s->name, r->x, r->size, commit,
           bench_plan_name(r->stats.plan), gpu, r->cpu.median, ratio, counts, error);
    fflush(stdout);
}

/* The CSV row: empty fields where the point did not measure. */
static void write_row(FILE *csv, const point_result *r)
{
    fprintf(csv, "%d,%d,", r->x, r->size);
    if (r->gpu_measured)
        fprintf(csv, "%.3f,%.3f,%.3f,", r->gpu.median, r->gpu.min, r->gpu.max);
    else
        fputs(",,,", csv);
    fprintf(csv, "%.3f,", r->cpu.median);
    if (r->gpu_measured) {
        fprintf(csv, "%.3f,%d,%d,%d,", r->cpu.median / r->gpu.median, bench_total_passes(&r->stats),
                r->stats.ray_sets, r->gpu.runs);
        bench_error_csv(csv, &r->error);
    } else {
        fputs(",,,,,,,,", csv); /* the four GPU counts and the five error columns */
    }
    fprintf(csv, ",%s,", bench_plan_name(r->stats.plan));
    if (r->commit_ms >= 0.0)
        fprintf(csv, "%.3f", r->commit_ms);
    fputc('\n', csv);
}

/* ---- the series ---- */

typedef struct run_config {
    int size, gpu_runs, cpu_runs, commit_runs;
} run_config;

/* One point of a series: builds its scene, measures it, prints and writes a row. */
static bool run_point(bench_gpu *gpu, const series *s, int x, const run_config *config, FILE *csv)
{
    point_result r;
    memset(&r, 0, sizeof r);
    r.x = x;
    r.size = config->size;
    bg_render_settings settings = bg_render_settings_init();
    bg_scene *scene = point_scene(s, x, config->commit_runs, &settings, &r.size, &r.commit_ms);
    if (!scene)
        return false;
    bool ok = measure_point(gpu, s, scene, &settings, config->gpu_runs, config->cpu_runs, &r);
    if (ok) {
        print_row(s, &r);
        write_row(csv, &r);
    }
    bg_scene_destroy(scene);
    return ok;
}

static bool run_series(bench_gpu *gpu, const series *s, bool quick, const run_config *config, const char *dir)
{
    char name[64];
    snprintf(name, sizeof name, "scaling_%s.csv", s->name);
    FILE *csv = bench_csv_open(dir, name, CSV_HEADER);
    if (!csv)
        return false;
    const int *xs = quick ? s->quick_x : s->x;
    int count = quick ? s->quick_count : s->count;
    bool ok = true;
    for (int k = 0; k < count && ok; k++) {
        bench_progress("scaling: %s = %d (%s on %s)", s->name, xs[k], s->x_label, series_scene_name(s));
        ok = run_point(gpu, s, xs[k], config, csv);
    }
    fclose(csv);
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const char *selected = getenv("SCALING_SERIES");
    if (!series_list_valid(selected))
        return 1;
    const run_config config = {quick ? 256 : 512, quick ? 3 : 5, quick ? 1 : 3,
                               quick ? QUICK_COMMIT_RUNS : COMMIT_RUNS};
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    printf("== Scaling on the GPU path (%dx%d unless the series is resolution; CPU reference %d run%s; "
           "commit ms: median first commit of %d new scenes)\n",
           config.size, config.size, config.cpu_runs, config.cpu_runs > 1 ? "s" : "", config.commit_runs);
    bench_print_setup(stdout, &gpu, config.gpu_runs);
    print_table_header();
    int status = 0;
    for (int i = 0; i < SERIES_COUNT && !status; i++)
        if (series_selected(selected, all_series[i].name))
            status = !run_series(&gpu, &all_series[i], quick, &config, dir);
    bench_gpu_close(&gpu);
    return status;
}
