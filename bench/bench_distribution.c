/* Distribution ray tracing (docs/shading.md 1.3, 1.4, 7 and 9.1): what one camera sample costs on the
 * GPU and on the CPU reference, and how fast each effect's noise falls as samples add up, one scene
 * per effect (bench/lib/distribution_scenes.h): area lights, depth of field, glossy reflection.
 *
 * Usage: bench_distribution [out_dir]   (default bench/out; QUICK=1 for fewer samples a frame, fewer
 *                                        rounds and a smaller error series)
 * Time per sample, at 512x512: the GPU under BG_PLAN_AUTO and the CPU reference on every core, one
 * warm-up frame each, then interleaved rounds (a contestant whose warm-up took over BENCH_SLOW_MS takes
 * part in the first BENCH_SLOW_RUNS only). Each frame renders TIME_SAMPLES samples (QUICK:
 * QUICK_TIME_SAMPLES) and its time is divided by that count. A fixed count is what both renderers
 * take the same way: the CPU reference has no accumulation, and bg_render_gpu's multi-sample frames go
 * through the GPU's accumulation anyway. A frame's fixed costs (the read-back, the CPU's threads) then
 * weigh 1/TIME_SAMPLES as much as in a one-sample frame, as they do in a converging render; they are a
 * few ms against a sample's tens, so QUICK's fewer samples move a sample's time by a few per cent at
 * most. The ratio GPU/CPU is the median of the per-round ratios; the target is at most 0.5 on every
 * scene. Each scene's plain twin (the effect taken out) runs in the same rounds, so that a row also
 * shows what the scene costs without its effect on each renderer, and what the effect adds.
 * Error against samples, at 128x128 (QUICK: 64x64; the reference's 1024 samples a pixel cost most of
 * the run): a CPU reference of REFERENCE_SAMPLES per pixel, then the GPU and the CPU at 1, 2, 4 ...
 * BG_MAX_SAMPLES samples, each the RMSE of its linear radiance (RGBA32F, RGB) against the reference,
 * and the least-squares slopes of log RMSE over log samples (-1/2 for plain Monte Carlo noise).
 * Writes out_dir/distribution_time.csv, out_dir/distribution_error.csv, and each scene's GPU frame
 * at 512x512 as out_dir/distribution_<scene>.png. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/bench_measure.h"
#include "lib/distribution_scenes.h"

/* The scenes, one line each: a scene of another effect (an environment map) is one more line. */
typedef struct distribution_case {
    const char *name;
    bg_status (*build)(bg_scene *scene, bool effect);
} distribution_case;

static const distribution_case cases[] = {
    {"area_lights", distribution_area_lights},
    {"depth_of_field", distribution_depth_of_field},
    {"glossy", distribution_glossy},
    {"environment_importance", distribution_environment_importance},
    {"environment_uniform", distribution_environment_uniform},
};
#define CASE_COUNT (int)(sizeof cases / sizeof cases[0])

#define TIME_SIZE 512
#define TIME_SAMPLES 16
#define QUICK_TIME_SAMPLES 4
#define TARGET_RATIO 0.5
/* The reference: REFERENCE_SAMPLES per pixel, as a frame of REFERENCE_SCALE times the side at
 * REFERENCE_SUBSAMPLES each, every REFERENCE_SCALE^2 block averaged: the same box over the pixel (the
 * sub-pixels tile it, docs/shading.md 1.1), since one call takes at most 256 samples. (This
 * benchmark found that the first scramble paired a pixel's sub-pixel cells with its lens cells by one
 * rotation, so that one pixel's error stopped falling after 16 samples: 0.029, 0.027 and 0.027 at 16,
 * 64 and 256 on depth_of_field; the pairing is a permutation now, docs/shading.md 1.3.) */
#define REFERENCE_SCALE 8
#define REFERENCE_SUBSAMPLES 16
#define REFERENCE_SAMPLES (REFERENCE_SCALE * REFERENCE_SCALE * REFERENCE_SUBSAMPLES)
/* Points of the series: 1, 2, 4 ... BG_MAX_SAMPLES. */
#define SERIES_POINTS 9

/* The contestants of a time run: the scene's GPU and CPU frames, then its plain twin's
 * (distribution_scenes.h), interleaved, so that the effect's own cost is the difference of two
 * medians measured side by side. */
enum { GPU, CPU, PLAIN_GPU, PLAIN_CPU, CONTESTANTS };
static const char *const contestant_names[CONTESTANTS] = {"GPU", "CPU reference", "GPU, plain twin",
                                                          "CPU reference, plain twin"};

/* ---- the scenes ---- */

static bg_scene *case_scene(const distribution_case *c, bool effect)
{
    bg_scene *scene = NULL;
    if (bg_scene_create(NULL, &scene) != BG_OK) {
        fprintf(stderr, "cannot create a scene\n");
        return NULL;
    }
    bg_status st = c->build(scene, effect);
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    if (st != BG_OK) {
        fprintf(stderr, "cannot build %s%s: %s (%s)\n", c->name, effect ? "" : " (plain)", bg_status_string(st),
                bg_scene_error_message(scene));
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

/* ---- time per sample ---- */

typedef struct time_run {
    bench_contestant c[CONTESTANTS];
    bg_image images[CONTESTANTS];
    bench_gpu_job gpu[2]; /* the scene's, the plain twin's */
    bench_cpu_job cpu[2];
    bench_error error; /* the GPU's last frame against the CPU's: the same samples, so float error only */
} time_run;

/* A frame's time per sample: the frames of a run render run->gpu[0].settings.samples each. */
static double per_sample(const time_run *run, double ms)
{
    return ms / run->gpu[0].settings.samples;
}

/* renderers: the scene's and the twin's, so that each keeps its compiled program between rounds. */
static bool time_case(time_run *run, bg_renderer *const renderers[2], bg_scene *scene, bg_scene *plain,
                      const char *label, int samples, int runs)
{
    memset(run, 0, sizeof *run);
    bg_render_settings settings = bg_render_settings_init();
    settings.samples = samples;
    bool ok = true;
    for (int i = 0; i < CONTESTANTS; i++) {
        ok = ok && bench_image_alloc(&run->images[i], TIME_SIZE, TIME_SIZE, BG_PIXEL_RGBA8);
        run->c[i] = (bench_contestant){.name = contestant_names[i], .image = &run->images[i]};
    }
    bg_scene *scenes[2] = {scene, plain};
    for (int k = 0; k < 2; k++) {
        run->gpu[k] = (bench_gpu_job){.renderer = renderers[k], .scene = scenes[k], .settings = settings};
        run->cpu[k] = (bench_cpu_job){scenes[k], settings};
        run->c[GPU + 2 * k].frame = bench_gpu_frame;
        run->c[GPU + 2 * k].user = &run->gpu[k];
        run->c[CPU + 2 * k].frame = bench_cpu_frame;
        run->c[CPU + 2 * k].user = &run->cpu[k];
    }
    for (int i = 0; i < CONTESTANTS && ok; i++) {
        ok = bench_warm_up(&run->c[i]);
        run->c[i].rounds = bench_rounds_after(run->c[i].warm_ms, runs);
    }
    ok = ok && bench_interleave(run->c, CONTESTANTS, label);
    if (ok)
        run->error = bench_error_of(&run->images[CPU], &run->images[GPU]);
    return ok;
}

static void free_time_run(time_run *run)
{
    for (int i = 0; i < CONTESTANTS; i++)
        bench_image_free(&run->images[i]);
}

/* "n median [min-max]" per sample. */
static char *per_sample_text(const time_run *run, const bench_contestant *c, char *buffer, size_t size)
{
    snprintf(buffer, size, "%2d %7.2f [%.2f-%.2f]", c->rounds, per_sample(run, c->times.median),
             per_sample(run, c->times.min), per_sample(run, c->times.max));
    return buffer;
}

#define TIME_FORMAT "%-22s %-10s | %-28s | %-28s | %7s | %-6s | %7s | %-13s | %s\n"
#define TIME_CSV_HEADER                                                                                      \
    "scene,size,samples,plan,gpu_median_ms,gpu_min_ms,gpu_max_ms,cpu_median_ms,cpu_min_ms,cpu_max_ms,"      \
    "gpu_ms_per_sample,cpu_ms_per_sample,gpu_over_cpu,target_met,gpu_runs,cpu_runs,gpu_recompiled_frames,"  \
    "plain_gpu_ms_per_sample,plain_cpu_ms_per_sample,plain_gpu_over_cpu,effect_gpu_ms_per_sample,"           \
    "effect_cpu_ms_per_sample," BENCH_ERROR_CSV_HEADER

static void print_time_header(const bench_gpu *gpu, int runs, int samples)
{
    printf("== Distribution ray tracing: time per sample at %dx%d, %d samples a frame, GPU (BG_PLAN_AUTO) against "
           "the CPU reference\n", TIME_SIZE, TIME_SIZE, samples);
    bench_print_setup(stdout, gpu, runs);
    printf("Rounds: GPU, CPU, and the same on the scene's plain twin (the effect taken out), interleaved; cells: n\n"
           "rounds, ms per sample median [min-max] (a frame's time / %d); GPU/CPU: median of the per-round ratios;\n"
           "target: GPU/CPU <= %.1f; plain: the twin's GPU/CPU; effect ms: the scene's median less the twin's, per\n"
           "sample, GPU / CPU. Under each row, the GPU frame's GL work (bg_render_stats.gl_work): d draws, p program\n"
           "binds, f framebuffer binds, u uniform calls, up bytes uploaded, rb bytes read back a pixel, s syncs, c\n"
           "programs compiled\n", samples, TARGET_RATIO);
    printf(TIME_FORMAT, "scene", "plan", "GPU: n ms/sample", "CPU: n ms/sample", "GPU/CPU", "target", "plain",
           "effect ms", "GPU error vs CPU (same samples)");
}

/* Prints and writes one scene's row; returns whether the target holds. */
static bool time_row(FILE *csv, const char *name, const time_run *run)
{
    char cell[2][64], ratio[16], plain[16], effect[32], error[128];
    for (int i = 0; i < 2; i++)
        per_sample_text(run, &run->c[i], cell[i], sizeof cell[i]);
    const double r = bench_ratio(&run->c[GPU], &run->c[CPU]), rp = bench_ratio(&run->c[PLAIN_GPU], &run->c[PLAIN_CPU]);
    const double effect_gpu = per_sample(run, run->c[GPU].times.median - run->c[PLAIN_GPU].times.median),
                 effect_cpu = per_sample(run, run->c[CPU].times.median - run->c[PLAIN_CPU].times.median);
    const bool met = r <= TARGET_RATIO;
    snprintf(ratio, sizeof ratio, "%.2f", r);
    snprintf(plain, sizeof plain, "%.2f", rp);
    snprintf(effect, sizeof effect, "%.1f / %.1f", effect_gpu, effect_cpu);
    const char *plan = bench_plan_name(run->gpu[0].stats.plan);
    printf(TIME_FORMAT, name, plan, cell[GPU], cell[CPU], ratio, met ? "met" : "MISSED", plain, effect,
           bench_error_text(&run->error, error, sizeof error));
    char work[160];
    printf("  (%s: GL work per GPU frame of %d samples: %s)\n", name, run->gpu[0].settings.samples,
           bench_work_text(&run->gpu[0].stats.gl_work, TIME_SIZE, TIME_SIZE, work, sizeof work));
    if (run->gpu[0].recompiled_frames > 0 || run->gpu[1].recompiled_frames > 0)
        printf("  (%s: %d GPU frames after the first compiled a program)\n", name,
               run->gpu[0].recompiled_frames + run->gpu[1].recompiled_frames);
    fflush(stdout);
    const bench_times *g = &run->c[GPU].times, *c = &run->c[CPU].times;
    fprintf(csv, "%s,%d,%d,%s,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.4f,%.4f,%.4f,%d,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,", name,
            TIME_SIZE, run->gpu[0].settings.samples, plan, g->median, g->min, g->max, c->median, c->min, c->max,
            per_sample(run, g->median), per_sample(run, c->median), r, met, g->runs, c->runs,
            run->gpu[0].recompiled_frames, per_sample(run, run->c[PLAIN_GPU].times.median),
            per_sample(run, run->c[PLAIN_CPU].times.median), rp, effect_gpu, effect_cpu);
    bench_error_csv(csv, &run->error);
    fputc('\n', csv);
    return met;
}

/* Saves the GPU's frame for a look at the scene (not needed by anything else). */
static void save_frame(const char *dir, const char *name, const bg_image *image)
{
    char path[1024], message[256];
    snprintf(path, sizeof path, "%s/distribution_%s.png", dir, name);
    if (bg_png_save(path, image, message, sizeof message) != BG_OK)
        fprintf(stderr, "%s: %s\n", path, message);
}

/* ---- error against samples ---- */

/* RMSE of the RGB channels of two RGBA32F images of one size (tightly packed). */
static double rmse(const bg_image *a, const bg_image *b)
{
    const float *p = a->pixels, *q = b->pixels;
    const long n = (long)a->width * a->height;
    double sum = 0.0;
    for (long i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double d = (double)p[4 * i + k] - q[4 * i + k];
            sum += d * d;
        }
    return sqrt(sum / (3.0 * (double)n));
}

/* The root mean square of an image's RGB: the scale the errors compare with. */
static double rms(const bg_image *a)
{
    bg_image black = *a;
    float *zero = calloc((size_t)a->width * (size_t)a->height, 16);
    if (!zero)
        return 0.0;
    black.pixels = zero;
    double v = rmse(a, &black);
    free(zero);
    return v;
}

/* Averages each scale x scale block of big into small (RGBA32F, small's size times scale). */
static void box_down(const bg_image *big, bg_image *small, int scale)
{
    const float *p = big->pixels;
    float *q = small->pixels;
    for (int y = 0; y < small->height; y++)
        for (int x = 0; x < small->width; x++)
            for (int k = 0; k < 4; k++) {
                double sum = 0.0;
                for (int j = 0; j < scale; j++)
                    for (int i = 0; i < scale; i++)
                        sum += p[4 * ((long)(y * scale + j) * big->width + x * scale + i) + k];
                q[4 * ((long)y * small->width + x) + k] = (float)(sum / (scale * scale));
            }
}

static bool reference_image(bg_scene *scene, int size, bg_image *reference)
{
    bg_image big;
    if (!bench_image_alloc(&big, size * REFERENCE_SCALE, size * REFERENCE_SCALE, BG_PIXEL_RGBA32F))
        return false;
    bg_render_settings settings = bg_render_settings_init();
    settings.samples = REFERENCE_SUBSAMPLES;
    bg_status st = bg_render_cpu(scene, &settings, &big);
    if (st == BG_OK)
        box_down(&big, reference, REFERENCE_SCALE);
    else
        fprintf(stderr, "reference render failed: %s\n", bg_status_string(st));
    bench_image_free(&big);
    return st == BG_OK;
}

/* The least-squares slope of log y over log x. */
static double log_slope(const double *x, const double *y, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; i++) {
        double lx = log(x[i]), ly = log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* The ranges slopes are fitted over, as first and last point: the whole series, and its halves, since
 * where the pattern's error levels off (REFERENCE_SCALE's comment) the whole series' slope hides it. */
#define SLOPES 3
static const int slope_ranges[SLOPES][2] = {{0, SERIES_POINTS - 1}, {0, 4}, {4, SERIES_POINTS - 1}};

typedef struct error_series {
    double samples[SERIES_POINTS], rmse[CONTESTANTS][SERIES_POINTS], between[SERIES_POINTS];
    double reference_rms;
    double slope[CONTESTANTS][SLOPES]; /* over the points of each range of slope_ranges */
} error_series;

static bool error_case(bg_renderer *renderer, bg_scene *scene, const char *name, int size, error_series *out)
{
    bg_image reference, image[CONTESTANTS];
    memset(image, 0, sizeof image);
    bool ok = bench_image_alloc(&reference, size, size, BG_PIXEL_RGBA32F);
    for (int i = 0; i < CONTESTANTS; i++)
        ok = ok && bench_image_alloc(&image[i], size, size, BG_PIXEL_RGBA32F);
    bench_progress("distribution: %s, CPU reference of %d samples at %dx%d", name, REFERENCE_SAMPLES, size, size);
    ok = ok && reference_image(scene, size, &reference);
    if (ok)
        out->reference_rms = rms(&reference);
    bg_render_settings settings = bg_render_settings_init();
    for (int p = 0, n = 1; p < SERIES_POINTS && ok; p++, n *= 2) {
        bench_progress("distribution: %s, %d samples", name, n);
        settings.samples = n;
        bg_status st = bg_render_gpu(renderer, scene, &settings, &image[GPU]);
        if (st != BG_OK)
            fprintf(stderr, "GPU render failed: %s\n", bg_renderer_error_message(renderer));
        ok = st == BG_OK && bg_render_cpu(scene, &settings, &image[CPU]) == BG_OK;
        out->samples[p] = n;
        for (int i = 0; i < CONTESTANTS && ok; i++)
            out->rmse[i][p] = rmse(&reference, &image[i]);
        if (ok)
            out->between[p] = rmse(&image[CPU], &image[GPU]);
    }
    for (int i = 0; i < CONTESTANTS && ok; i++)
        for (int r = 0; r < SLOPES; r++) {
            const int first = slope_ranges[r][0], count = slope_ranges[r][1] - first + 1;
            out->slope[i][r] = log_slope(out->samples + first, out->rmse[i] + first, count);
        }
    bench_image_free(&reference);
    for (int i = 0; i < CONTESTANTS; i++)
        bench_image_free(&image[i]);
    if (!ok)
        fprintf(stderr, "distribution: the error series of %s failed\n", name);
    return ok;
}

#define ERROR_CSV_HEADER "scene,size,samples,gpu_rmse,cpu_rmse,gpu_cpu_rmse,reference_rms,reference_samples"

static void print_error_header(int size)
{
    printf("\n== RMSE against samples at %dx%d: linear radiance (RGB of RGBA32F) against a CPU reference of %d "
           "samples\n", size, size, REFERENCE_SAMPLES);
    printf("(%dx%d sub-pixels of %d samples each); GPU-CPU: the RMSE between the two at the same samples (the same\n"
           "sample points: float error only); slopes: least squares of log RMSE over log samples, GPU (CPU),\n"
           "-0.5 for plain Monte Carlo noise; RMS: the reference's own RMS radiance, the scale of the errors\n",
           REFERENCE_SCALE, REFERENCE_SCALE, REFERENCE_SUBSAMPLES);
    printf("%-15s %7s | %10s %10s %10s\n", "scene", "samples", "GPU RMSE", "CPU RMSE", "GPU-CPU");
}

static void error_rows(FILE *csv, const char *name, int size, const error_series *s)
{
    for (int p = 0; p < SERIES_POINTS; p++) {
        printf("%-15s %7.0f | %10.5f %10.5f %10.6f\n", name, s->samples[p], s->rmse[GPU][p], s->rmse[CPU][p],
               s->between[p]);
        fprintf(csv, "%s,%d,%.0f,%.6g,%.6g,%.6g,%.6g,%d\n", name, size, s->samples[p], s->rmse[GPU][p],
                s->rmse[CPU][p], s->between[p], s->reference_rms, REFERENCE_SAMPLES);
    }
    printf("%-15s slopes:", name);
    for (int r = 0; r < SLOPES; r++)
        printf(" %.0f-%.0f %.3f (%.3f)%s", s->samples[slope_ranges[r][0]], s->samples[slope_ranges[r][1]],
               s->slope[GPU][r], s->slope[CPU][r], r + 1 < SLOPES ? "," : "");
    printf("; RMS %.4f\n", s->reference_rms);
    fflush(stdout);
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const int runs = quick ? 3 : 7, time_samples = quick ? QUICK_TIME_SAMPLES : TIME_SAMPLES,
              error_size = quick ? 64 : 128;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    bg_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    bg_renderer *renderers[2] = {gpu.renderer, bench_gpu_renderer(&gpu, desc)};
    FILE *time_csv = renderers[1] ? bench_csv_open(dir, "distribution_time.csv", TIME_CSV_HEADER) : NULL;
    FILE *error_csv = time_csv ? bench_csv_open(dir, "distribution_error.csv", ERROR_CSV_HEADER) : NULL;
    int status = !error_csv;
    bg_scene *scenes[CASE_COUNT] = {NULL}, *plain[CASE_COUNT] = {NULL};
    for (int s = 0; s < CASE_COUNT && !status; s++)
        status = !(scenes[s] = case_scene(&cases[s], true)) || !(plain[s] = case_scene(&cases[s], false));
    int met = 0;
    if (!status)
        print_time_header(&gpu, runs, time_samples);
    for (int s = 0; s < CASE_COUNT && !status; s++) {
        char label[96];
        snprintf(label, sizeof label, "distribution: %s %dx%d", cases[s].name, TIME_SIZE, TIME_SIZE);
        bench_progress("%s: warm-up", label);
        time_run *run = malloc(sizeof *run);
        status = !run || !time_case(run, renderers, scenes[s], plain[s], label, time_samples, runs);
        if (!status) {
            met += time_row(time_csv, cases[s].name, run);
            save_frame(dir, cases[s].name, &run->images[GPU]);
        }
        if (run)
            free_time_run(run);
        free(run);
    }
    if (!status) {
        printf("Target (GPU at most %.1fx the CPU's time per sample): met on %d of %d scenes\n", TARGET_RATIO, met,
               CASE_COUNT);
        print_error_header(error_size);
    }
    for (int s = 0; s < CASE_COUNT && !status; s++) {
        error_series series;
        memset(&series, 0, sizeof series);
        status = !error_case(gpu.renderer, scenes[s], cases[s].name, error_size, &series);
        if (!status)
            error_rows(error_csv, cases[s].name, error_size, &series);
    }
    for (int s = 0; s < CASE_COUNT; s++) {
        bg_scene_destroy(scenes[s]);
        bg_scene_destroy(plain[s]);
    }
    if (time_csv)
        fclose(time_csv);
    if (error_csv)
        fclose(error_csv);
    bg_renderer_destroy(renderers[1]);
    bench_gpu_close(&gpu);
    return status;
}
