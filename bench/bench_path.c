/* The path integrator (docs/shading.md 13) on the Cornell box scene files: what one camera sample
 * costs, and how fast its noise falls as samples add up.
 *
 * Usage: bench_path [out_dir]                           (default bench/out)
 *        bench_path --render SCENE.json SIZE SAMPLES OUT.pfm
 * Cases (BENCH_CASES): cornell_box, cornell_glossy (examples/scenes/json/<case>.json, read from the
 * folder the program runs in, the repository root under `make bench`).
 *
 * Time per sample, at TIME_SIZE x TIME_SIZE: the CPU reference on every core and the GPU under
 * BG_PLAN_AUTO, each with the path integrator and, as the baseline, with Whitted's of the same scene
 * file (which then lights by the rectangle light's inverse-square term, its "attenuation" [0, 0, 1]);
 * one warm-up frame each, then interleaved rounds (bench_interleave). A frame renders time_samples
 * samples and its time is divided by that count. Until a GPU plan draws the path integrator,
 * bg_render_gpu refuses it with BG_ERR_LIMIT: the GPU's path column then says "not available", with
 * the renderer's reason, and the rest runs.
 * Error against samples: linear radiance (RGB of RGBA32F) against a CPU reference of
 * REFERENCE_SCALE^2 x 256 samples a pixel, at 1, 2, 4 ... SERIES_MAX samples. One call takes at most
 * BG_MAX_SAMPLES (256), so a count n above it is the frame at k times the side with n / k^2 samples,
 * each k x k block averaged in linear float: the same box over the pixel, and the pattern of n samples
 * up to the 2^-10 rounding (docs/shading.md 1.1; 1024 = 2 x 2 blocks of 256). The big frame renders
 * in bands (windows of it, pixel-exact), so the reference needs no 4096^2 image. Each point is the RMSE
 * over all pixels and channels, and over the pixels away from the light (away_from_emitters); the
 * reference's own noise adds its variance, 1/16 of the largest point's (REFERENCE_SCALE 8 against
 * 1024), so that point reads at most 3 % high. The least-squares slope of log RMSE over log samples is
 * -1/2 for plain Monte Carlo noise.
 *
 * Sizes: TIME_SIZE 512 always. The error series costs (REFERENCE_SCALE^2 x 256 + 2047) camera paths a
 * pixel, 18431, and the CPU reference traces about 2e5 paths a second a core on the Cornell box (a
 * 2-core Xeon), so `make bench` runs it at 32 x 32 (19e6 paths a scene, one to two minutes);
 * QUICK=1 at 16 x 16 up to 256 samples against 4096; BENCH_PATH_FULL=1 at 512 x 512 (4.8e9 paths a
 * scene: hours on 2 cores, about an hour on 16) with 16 samples a timed frame and 7 rounds.
 *
 * Writes out_dir/path_time.csv, out_dir/path_error.csv, and each case's image at the largest series
 * point, out_dir/path_<case>.png (sRGB) and .pfm (linear float, bottom row first, as PFM has it).
 *
 * --render: one CPU render of the scene file with the path integrator (the file's max_depth) at
 * SIZE x SIZE and SAMPLES a pixel (a power of two up to 65536, as above), written as linear PFM;
 * what bench/mitsuba_compare.py compares with Mitsuba. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "betelgeuse_scenefile.h"
#include "lib/bench_measure.h"
#include "lib/bench_select.h"

#define SCENE_DIR "examples/scenes/json"
static const char *const case_names[] = {"cornell_box", "cornell_glossy"};
#define CASE_COUNT (int)(sizeof case_names / sizeof case_names[0])
#define CASE_NAMES "cornell_box, cornell_glossy"

#define TIME_SIZE 512
#define REFERENCE_SUBSAMPLES 256
/* The biggest frame one band of a render holds: 2^20 pixels, 16 MiB of RGBA32F. */
#define BAND_PIXELS (1L << 20)
#define MAX_POINTS 16

/* What one run measures, from QUICK and BENCH_PATH_FULL. */
typedef struct run_config {
    int runs, time_samples, error_size, reference_scale, series_max;
} run_config;

static run_config config_of(void)
{
    const char *full = getenv("BENCH_PATH_FULL");
    if (full && *full && strcmp(full, "0") != 0)
        return (run_config){7, 16, 512, 8, 1024};
    if (bench_quick())
        return (run_config){3, 1, 16, 4, 256};
    return (run_config){5, 4, 32, 8, 1024};
}

/* ---- scenes and renders ---- */

static bg_scene *load_scene(const char *path, bg_scenefile_result *result)
{
    bg_scene *scene = NULL;
    char message[1024];
    if (bg_scene_create(NULL, &scene) != BG_OK) {
        fprintf(stderr, "cannot create a scene\n");
        return NULL;
    }
    if (bg_scenefile_load(path, NULL, scene, result, message, sizeof message) != BG_OK) {
        fprintf(stderr, "%s\n", message);
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

/* The file's settings (max_depth, background) under the given integrator. */
static bg_render_settings settings_of(const bg_scenefile_result *r, bg_integrator integrator)
{
    bg_render_settings s = r->settings;
    s.integrator = integrator;
    return s;
}

/* The frame scale k and the samples per call for n samples a pixel: n itself up to BG_MAX_SAMPLES,
 * else the least k (a power of two) with n / k^2 <= BG_MAX_SAMPLES. False when n is not a power of two
 * or needs a frame over BG_MAX_IMAGE_SIDE. */
static bool split_samples(int n, int size, int *scale, int *per_call)
{
    if (n < 1 || (n & (n - 1)) != 0)
        return false;
    int k = 1;
    while (n / (k * k) > BG_MAX_SAMPLES)
        k *= 2;
    *scale = k;
    *per_call = n / (k * k);
    return (long)size * k <= BG_MAX_IMAGE_SIDE;
}

/* Renders n samples a pixel into out (RGBA32F, size x size) on the CPU, or on the GPU when renderer is
 * not NULL: the frame at scale k in bands of whole k-rows of out, each k x k block averaged in double.
 * On failure prints the reason (message holds the GPU's) and returns the status. */
static bg_status render_samples(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *base, int n,
                                bg_image *out)
{
    const int size = out->width;
    int k, per_call;
    if (!split_samples(n, size, &k, &per_call)) {
        fprintf(stderr, "%d samples a pixel at %dx%d: not a power of two, or a frame over %d pixels a side\n", n,
                size, size, BG_MAX_IMAGE_SIDE);
        return BG_ERR_INVALID_ARGUMENT;
    }
    bg_render_settings s = *base;
    s.samples = per_call;
    if (k == 1)
        return renderer ? bg_render_gpu(renderer, scene, &s, out) : bg_render_cpu(scene, &s, out);
    long rows = BAND_PIXELS / ((long)size * k * k);
    const int band_rows = rows < 1 ? 1 : rows > size ? size : (int)rows; /* rows of out a band covers */
    bg_image band;
    if (!bench_image_alloc(&band, size * k, band_rows * k, BG_PIXEL_RGBA32F))
        return BG_ERR_OUT_OF_MEMORY;
    s.frame_width = s.frame_height = size * k;
    s.window_x = 0;
    bg_status st = BG_OK;
    for (int y0 = 0; y0 < size && st == BG_OK; y0 += band_rows) {
        const int h = size - y0 < band_rows ? size - y0 : band_rows;
        band.height = h * k;
        s.window_y = y0 * k;
        st = renderer ? bg_render_gpu(renderer, scene, &s, &band) : bg_render_cpu(scene, &s, &band);
        const float *p = band.pixels;
        float *q = out->pixels;
        for (int y = 0; y < h && st == BG_OK; y++)
            for (int x = 0; x < size; x++)
                for (int c = 0; c < 4; c++) {
                    double sum = 0.0;
                    for (int j = 0; j < k; j++)
                        for (int i = 0; i < k; i++)
                            sum += p[4 * ((long)(y * k + j) * band.width + x * k + i) + c];
                    q[4 * ((long)(y0 + y) * size + x) + c] = (float)(sum / (k * k));
                }
    }
    band.height = band_rows * k;
    bench_image_free(&band);
    if (st != BG_OK)
        fprintf(stderr, "%s render of %d samples failed: %s%s%s\n", renderer ? "GPU" : "CPU", n,
                bg_status_string(st), renderer ? ": " : "", renderer ? bg_renderer_error_message(renderer) : "");
    return st;
}

/* RMSE of the RGB channels of two RGBA32F images of one size over the pixels where keep is NULL or
 * true; with b NULL, a's RMS. */
static double rmse_where(const bg_image *a, const bg_image *b, const bool *keep)
{
    const float *p = a->pixels, *q = b ? b->pixels : NULL;
    const long n = (long)a->width * a->height;
    double sum = 0.0;
    long count = 0;
    for (long i = 0; i < n; i++) {
        if (keep && !keep[i])
            continue;
        count++;
        for (int c = 0; c < 3; c++) {
            double d = (double)p[4 * i + c] - (q ? q[4 * i + c] : 0.0f);
            sum += d * d;
        }
    }
    return count ? sqrt(sum / (3.0 * (double)count)) : 0.0;
}

static double rmse(const bg_image *a, const bg_image *b)
{
    return rmse_where(a, b, NULL);
}

/* The pixels away from the emitters: no channel of the reference above EMITTER_LEVEL at the pixel or
 * its 8 neighbours. The Cornell light (radiance 17, 12, 4) is a strip a few pixels tall at 32 x 32,
 * and the error of the pixels its edge crosses is the pixel pattern's coverage of that edge, which
 * refines only when the pattern gains rows (1.1), not path noise; the walls stay below 1. */
#define EMITTER_LEVEL 1.0
static bool *away_from_emitters(const bg_image *reference, long *count)
{
    const int w = reference->width, h = reference->height;
    const float *p = reference->pixels;
    bool *keep = malloc((size_t)w * (size_t)h);
    if (!keep)
        return NULL;
    *count = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            bool k = true;
            for (int j = y - 1; j <= y + 1; j++)
                for (int i = x - 1; i <= x + 1; i++)
                    if (i >= 0 && j >= 0 && i < w && j < h)
                        for (int c = 0; c < 3; c++)
                            k = k && !(p[4 * ((long)j * w + i) + c] > EMITTER_LEVEL);
            keep[(long)y * w + x] = k;
            *count += k;
        }
    return keep;
}

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
    return n > 1 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
}

/* PFM (Portable Float Map): the RGB of an RGBA32F image, little endian, bottom row first. */
static bool write_pfm(const char *path, const bg_image *image)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "cannot write %s\n", path);
        return false;
    }
    fprintf(f, "PF\n%d %d\n-1.0\n", image->width, image->height);
    const float *p = image->pixels;
    bool ok = true;
    for (int y = image->height - 1; y >= 0 && ok; y--)
        for (int x = 0; x < image->width && ok; x++)
            ok = fwrite(p + 4 * ((long)y * image->width + x), sizeof(float), 3, f) == 3;
    ok = fclose(f) == 0 && ok;
    if (!ok)
        fprintf(stderr, "cannot write %s\n", path);
    return ok;
}

/* An sRGB PNG of an RGBA32F image, for a look. */
static void write_png(const char *path, const bg_image *image)
{
    bg_image png;
    if (!bench_image_alloc(&png, image->width, image->height, BG_PIXEL_RGBA8))
        return;
    const float *p = image->pixels;
    unsigned char *q = png.pixels;
    for (long i = 0; i < (long)image->width * image->height; i++)
        for (int c = 0; c < 4; c++) {
            double v = p[4 * i + c];
            v = !(v > 0.0) ? 0.0 : v >= 1.0 ? 1.0 : c == 3 ? v
                : v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055; /* sRGB's curve */
            q[4 * i + c] = (unsigned char)floor(255.0 * v + 0.5);
        }
    char message[256];
    if (bg_png_save(path, &png, message, sizeof message) != BG_OK)
        fprintf(stderr, "%s: %s\n", path, message);
    bench_image_free(&png);
}

/* ---- time per sample ---- */

enum { CPU_PATH, GPU_PATH, CPU_WHITTED, GPU_WHITTED, CONTESTANTS };
static const char *const contestant_names[CONTESTANTS] = {"CPU path", "GPU path", "CPU Whitted", "GPU Whitted"};

typedef struct time_run {
    bench_contestant c[CONTESTANTS];
    bg_image images[CONTESTANTS];
    bench_gpu_job gpu[2]; /* path, Whitted */
    bench_cpu_job cpu[2];
    char gpu_path_note[512]; /* why the GPU path column is empty, or "" */
} time_run;

/* gpu NULL: no GPU session, every GPU column empty. whitted_renderer: a second renderer on gpu's
 * context for the Whitted frames, so that each keeps its compiled programs between rounds. */
static bool time_case(time_run *run, bench_gpu *gpu, bg_renderer *whitted_renderer, bg_scene *scene,
                      const bg_scenefile_result *r, const char *label, const run_config *cfg)
{
    memset(run, 0, sizeof *run);
    bool ok = true;
    for (int i = 0; i < CONTESTANTS; i++) {
        ok = ok && bench_image_alloc(&run->images[i], TIME_SIZE, TIME_SIZE, BG_PIXEL_RGBA32F);
        run->c[i] = (bench_contestant){.name = contestant_names[i], .image = &run->images[i]};
    }
    const bg_integrator integrators[2] = {BG_INTEGRATOR_PATH, BG_INTEGRATOR_WHITTED};
    for (int k = 0; k < 2; k++) {
        bg_render_settings s = settings_of(r, integrators[k]);
        s.samples = cfg->time_samples;
        run->cpu[k] = (bench_cpu_job){scene, s};
        run->c[CPU_PATH + 2 * k].frame = bench_cpu_frame;
        run->c[CPU_PATH + 2 * k].user = &run->cpu[k];
        run->gpu[k] = (bench_gpu_job){.renderer = !gpu ? NULL : k == 0 ? gpu->renderer : whitted_renderer,
                                      .scene = scene, .settings = s};
        run->c[GPU_PATH + 2 * k].frame = bench_gpu_frame;
        run->c[GPU_PATH + 2 * k].user = &run->gpu[k];
    }
    /* The GPU's path frame is tried first by hand: a refusal is a result here, not a failure. */
    bool gpu_path = gpu != NULL;
    if (!gpu)
        snprintf(run->gpu_path_note, sizeof run->gpu_path_note, "no GPU session");
    else if (ok) {
        bg_status st = bg_render_gpu(gpu->renderer, scene, &run->gpu[0].settings, &run->images[GPU_PATH]);
        if (st != BG_OK) {
            gpu_path = false;
            snprintf(run->gpu_path_note, sizeof run->gpu_path_note, "%s: %s", bg_status_string(st),
                     bg_renderer_error_message(gpu->renderer));
        }
    }
    for (int i = 0; i < CONTESTANTS && ok; i++) {
        if ((i == GPU_PATH && !gpu_path) || (i == GPU_WHITTED && !whitted_renderer))
            continue;
        ok = bench_warm_up(&run->c[i]);
        run->c[i].rounds = bench_rounds_after(run->c[i].warm_ms, cfg->runs);
    }
    return ok && bench_interleave(run->c, CONTESTANTS, label);
}

static void free_time_run(time_run *run)
{
    for (int i = 0; i < CONTESTANTS; i++)
        bench_image_free(&run->images[i]);
}

static char *per_sample_text(const bench_contestant *c, int samples, char *buffer, size_t size)
{
    if (c->rounds == 0)
        snprintf(buffer, size, "not available");
    else
        snprintf(buffer, size, "%2d %8.2f [%.2f-%.2f]", c->rounds, c->times.median / samples, c->times.min / samples,
                 c->times.max / samples);
    return buffer;
}

#define TIME_FORMAT "%-15s | %-28s | %-28s | %-28s | %-28s | %-9s\n"
#define TIME_CSV_HEADER                                                                                      \
    "scene,size,samples,max_depth,cpu_path_ms_per_sample,cpu_path_min,cpu_path_max,gpu_path_ms_per_sample,"  \
    "cpu_whitted_ms_per_sample,gpu_whitted_ms_per_sample,cpu_path_over_whitted,cpu_runs,gpu_path_note"

static void time_row(FILE *csv, const char *name, const time_run *run, int samples)
{
    char cell[CONTESTANTS][64], ratio[16];
    for (int i = 0; i < CONTESTANTS; i++)
        per_sample_text(&run->c[i], samples, cell[i], sizeof cell[i]);
    const double pw = bench_ratio(&run->c[CPU_PATH], &run->c[CPU_WHITTED]);
    snprintf(ratio, sizeof ratio, "%.2f", pw);
    printf(TIME_FORMAT, name, cell[CPU_PATH], cell[GPU_PATH], cell[CPU_WHITTED], cell[GPU_WHITTED], ratio);
    if (run->gpu_path_note[0])
        printf("  (%s: GPU path not available: %s)\n", name, run->gpu_path_note);
    fflush(stdout);
    double ms[CONTESTANTS];
    for (int i = 0; i < CONTESTANTS; i++)
        ms[i] = run->c[i].rounds ? run->c[i].times.median / samples : NAN;
    char note[512];
    snprintf(note, sizeof note, "%s", run->gpu_path_note);
    for (char *p = note; *p; p++)
        if (*p == ',' || *p == '\n' || *p == '"')
            *p = ';';
    fprintf(csv, "%s,%d,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%d,%s\n", name, TIME_SIZE, samples,
            run->cpu[0].settings.max_depth, ms[CPU_PATH], run->c[CPU_PATH].times.min / samples,
            run->c[CPU_PATH].times.max / samples, ms[GPU_PATH], ms[CPU_WHITTED], ms[GPU_WHITTED], pw,
            run->c[CPU_PATH].rounds, note);
}

/* ---- error against samples ---- */

typedef struct error_series {
    int points;
    double samples[MAX_POINTS], cpu[MAX_POINTS], gpu[MAX_POINTS], between[MAX_POINTS], cpu_ms[MAX_POINTS];
    double cpu_away[MAX_POINTS], gpu_away[MAX_POINTS]; /* over the pixels away from the emitters */
    double reference_rms, reference_rms_away, slope_cpu, slope_gpu, slope_cpu_away;
    long away_pixels;
    bool have_gpu;
} error_series;

/* last: the image at the largest point, kept for the files. */
static bool error_case(bench_gpu *gpu, bg_scene *scene, const bg_scenefile_result *r, const char *name,
                       const run_config *cfg, error_series *out, bg_image *last)
{
    const int size = cfg->error_size;
    const int reference_samples = cfg->reference_scale * cfg->reference_scale * REFERENCE_SUBSAMPLES;
    bg_image reference, gpu_image;
    bool ok = bench_image_alloc(&reference, size, size, BG_PIXEL_RGBA32F) &&
              bench_image_alloc(&gpu_image, size, size, BG_PIXEL_RGBA32F);
    const bg_render_settings s = settings_of(r, BG_INTEGRATOR_PATH);
    bench_progress("path: %s, CPU reference of %d samples at %dx%d", name, reference_samples, size, size);
    ok = ok && render_samples(NULL, scene, &s, reference_samples, &reference) == BG_OK;
    bool *away = ok ? away_from_emitters(&reference, &out->away_pixels) : NULL;
    ok = ok && away;
    if (ok) {
        out->reference_rms = rmse(&reference, NULL);
        out->reference_rms_away = rmse_where(&reference, NULL, away);
    }
    out->have_gpu = gpu != NULL;
    out->points = 0;
    for (int n = 1; n <= cfg->series_max && ok && out->points < MAX_POINTS; n *= 2) {
        const int p = out->points++;
        bench_progress("path: %s, %d samples", name, n);
        out->samples[p] = n;
        double t0 = bench_now_ms();
        ok = render_samples(NULL, scene, &s, n, last) == BG_OK;
        out->cpu_ms[p] = bench_now_ms() - t0;
        if (ok) {
            out->cpu[p] = rmse(&reference, last);
            out->cpu_away[p] = rmse_where(&reference, last, away);
        }
        if (ok && out->have_gpu) {
            /* A refusal (of a count the time runs did not try) leaves the GPU out of the series. */
            if (render_samples(gpu->renderer, scene, &s, n, &gpu_image) == BG_OK) {
                out->gpu[p] = rmse(&reference, &gpu_image);
                out->gpu_away[p] = rmse_where(&reference, &gpu_image, away);
                out->between[p] = rmse(last, &gpu_image);
            } else
                out->have_gpu = false;
        }
    }
    if (ok) {
        out->slope_cpu = log_slope(out->samples, out->cpu, out->points);
        out->slope_cpu_away = log_slope(out->samples, out->cpu_away, out->points);
        out->slope_gpu = out->have_gpu ? log_slope(out->samples, out->gpu, out->points) : NAN;
    }
    free(away);
    bench_image_free(&reference);
    bench_image_free(&gpu_image);
    if (!ok)
        fprintf(stderr, "path: the error series of %s failed\n", name);
    return ok;
}

#define ERROR_CSV_HEADER                                                                                  \
    "scene,size,samples,cpu_rmse,gpu_rmse,gpu_cpu_rmse,reference_rms,reference_samples,cpu_render_ms,"   \
    "cpu_rmse_away,gpu_rmse_away,reference_rms_away,away_pixels"

static void error_rows(FILE *csv, const char *name, const run_config *cfg, const error_series *s)
{
    const int reference_samples = cfg->reference_scale * cfg->reference_scale * REFERENCE_SUBSAMPLES;
    for (int p = 0; p < s->points; p++) {
        char gpu[32] = "-", between[32] = "-", gpu_away[32] = "-";
        if (s->have_gpu) {
            snprintf(gpu, sizeof gpu, "%.5f", s->gpu[p]);
            snprintf(between, sizeof between, "%.6f", s->between[p]);
            snprintf(gpu_away, sizeof gpu_away, "%.5f", s->gpu_away[p]);
        }
        printf("%-15s %7.0f | %10.5f %8.4f %10.5f %8.4f %10.0f | %10s %10s\n", name, s->samples[p], s->cpu[p],
               s->cpu[p] / s->reference_rms, s->cpu_away[p], s->cpu_away[p] / s->reference_rms_away, s->cpu_ms[p],
               gpu, between);
        fprintf(csv, "%s,%d,%.0f,%.6g,%s,%s,%.6g,%d,%.1f,%.6g,%s,%.6g,%ld\n", name, cfg->error_size, s->samples[p],
                s->cpu[p], s->have_gpu ? gpu : "", s->have_gpu ? between : "", s->reference_rms, reference_samples,
                s->cpu_ms[p], s->cpu_away[p], s->have_gpu ? gpu_away : "", s->reference_rms_away, s->away_pixels);
    }
    printf("%-15s slope of log RMSE over log samples: CPU %.3f, away from the light %.3f", name, s->slope_cpu,
           s->slope_cpu_away);
    if (s->have_gpu)
        printf(", GPU %.3f", s->slope_gpu);
    printf("; reference RMS %.4f, away from the light %.4f (%ld pixels)\n", s->reference_rms,
           s->reference_rms_away, s->away_pixels);
    fflush(stdout);
}

/* ---- the two modes ---- */

static int render_mode(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: bench_path --render SCENE.json SIZE SAMPLES OUT.pfm\n");
        return 2;
    }
    const int size = atoi(argv[3]), samples = atoi(argv[4]);
    int k, per_call;
    if (size < 1 || size > BG_MAX_IMAGE_SIDE || !split_samples(samples, size, &k, &per_call)) {
        fprintf(stderr, "bench_path --render: SIZE must be 1 .. %d and SAMPLES a power of two whose frame fits "
                        "(got %s, %s)\n", BG_MAX_IMAGE_SIDE, argv[3], argv[4]);
        return 2;
    }
    bg_scenefile_result r;
    bg_scene *scene = load_scene(argv[2], &r);
    bg_image image;
    if (!scene || !bench_image_alloc(&image, size, size, BG_PIXEL_RGBA32F)) {
        bg_scene_destroy(scene);
        return 1;
    }
    const bg_render_settings s = settings_of(&r, BG_INTEGRATOR_PATH);
    double t0 = bench_now_ms();
    int status = render_samples(NULL, scene, &s, samples, &image) != BG_OK;
    if (!status) {
        printf("%s: %dx%d, %d samples (%d x %d frame of %d), max_depth %d, path integrator on the CPU: %.1f s\n",
               argv[2], size, size, samples, size * k, size * k, per_call, s.max_depth,
               (bench_now_ms() - t0) / 1000.0);
        status = !write_pfm(argv[5], &image);
    }
    bench_image_free(&image);
    bg_scene_destroy(scene);
    return status;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--render") == 0)
        return render_mode(argc, argv);
    const char *dir = bench_out_dir(argc, argv);
    const run_config cfg = config_of();
    bool selected[CASE_COUNT];
    for (int i = 0; i < CASE_COUNT; i++)
        selected[i] = bench_selected(case_names[i], 0);
    if (!bench_select_check("bench_path", CASE_NAMES))
        return 2;
    bench_gpu gpu_session;
    bench_gpu *gpu = &gpu_session;
    bg_renderer *whitted_renderer = NULL;
    if (!bench_gpu_open(gpu)) {
        printf("GPU: not available (no headless GL session, above): CPU columns only\n");
        gpu = NULL;
    } else {
        bg_renderer_desc desc;
        memset(&desc, 0, sizeof desc);
        whitted_renderer = bench_gpu_renderer(gpu, desc);
    }
    FILE *time_csv = bench_csv_open(dir, "path_time.csv", TIME_CSV_HEADER);
    FILE *error_csv = time_csv ? bench_csv_open(dir, "path_error.csv", ERROR_CSV_HEADER) : NULL;
    int status = !error_csv;
    bool gpu_path = gpu != NULL; /* the GPU draws the path integrator: the time runs found it did */
    bg_scene *scenes[CASE_COUNT] = {NULL};
    bg_scenefile_result results[CASE_COUNT];
    for (int i = 0; i < CASE_COUNT && !status; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s.json", SCENE_DIR, case_names[i]);
        status = selected[i] && !(scenes[i] = load_scene(path, &results[i]));
    }
    if (!status) {
        printf("== Path integrator: time per sample at %dx%d, %d samples a frame, CPU reference and GPU "
               "(BG_PLAN_AUTO), path against Whitted\n", TIME_SIZE, TIME_SIZE, cfg.time_samples);
        bench_print_setup(stdout, gpu, cfg.runs);
        bench_select_print(stdout);
        printf("Rounds: CPU path, GPU path, CPU Whitted, GPU Whitted, interleaved; cells: n rounds, ms per sample\n"
               "median [min-max] (a frame's time / %d); path/Whitted: the CPU's, median of the per-round ratios\n",
               cfg.time_samples);
        printf(TIME_FORMAT, "scene", "CPU path: n ms/sample", "GPU path: n ms/sample", "CPU Whitted",
               "GPU Whitted", "path/Wh.");
    }
    for (int i = 0; i < CASE_COUNT && !status; i++) {
        if (!scenes[i])
            continue;
        char label[96];
        snprintf(label, sizeof label, "path: %s %dx%d", case_names[i], TIME_SIZE, TIME_SIZE);
        bench_progress("%s: warm-up", label);
        time_run *run = malloc(sizeof *run);
        status = !run || !time_case(run, gpu, whitted_renderer, scenes[i], &results[i], label, &cfg);
        if (!status) {
            time_row(time_csv, case_names[i], run, cfg.time_samples);
            gpu_path = gpu_path && !run->gpu_path_note[0];
        }
        if (run)
            free_time_run(run);
        free(run);
    }
    if (!status) {
        printf("\n== RMSE against samples at %dx%d: linear radiance (RGB of RGBA32F) against a CPU reference of %d\n"
               "samples (%dx%d sub-pixels of %d); counts above %d are frames of k times the side, k x k blocks\n"
               "averaged; RMSE/RMS: over the reference's own RMS; away: over the pixels whose 3 x 3 block of\n"
               "the reference has no channel above %.0f (the light and the pixels its edge crosses left out);\n"
               "ms: that CPU render's wall time (one run); GPU-CPU: the RMSE between the two at the same samples\n",
               cfg.error_size, cfg.error_size, cfg.reference_scale * cfg.reference_scale * REFERENCE_SUBSAMPLES,
               cfg.reference_scale, cfg.reference_scale, REFERENCE_SUBSAMPLES, BG_MAX_SAMPLES, EMITTER_LEVEL);
        printf("%-15s %7s | %10s %8s %10s %8s %10s | %10s %10s\n", "scene", "samples", "CPU RMSE", "RMSE/RMS",
               "away RMSE", "/RMS", "CPU ms", "GPU RMSE", "GPU-CPU");
    }
    for (int i = 0; i < CASE_COUNT && !status; i++) {
        if (!scenes[i])
            continue;
        error_series series;
        bg_image last;
        memset(&series, 0, sizeof series);
        status = !bench_image_alloc(&last, cfg.error_size, cfg.error_size, BG_PIXEL_RGBA32F) ||
                 !error_case(gpu_path ? gpu : NULL, scenes[i], &results[i], case_names[i], &cfg, &series, &last);
        if (!status) {
            error_rows(error_csv, case_names[i], &cfg, &series);
            char path[1024];
            snprintf(path, sizeof path, "%s/path_%s.png", dir, case_names[i]);
            write_png(path, &last);
            snprintf(path, sizeof path, "%s/path_%s.pfm", dir, case_names[i]);
            write_pfm(path, &last);
        }
        bench_image_free(&last);
    }
    for (int i = 0; i < CASE_COUNT; i++)
        bg_scene_destroy(scenes[i]);
    if (time_csv)
        fclose(time_csv);
    if (error_csv)
        fclose(error_csv);
    bg_renderer_destroy(whitted_renderer);
    if (gpu)
        bench_gpu_close(gpu);
    return status;
}
