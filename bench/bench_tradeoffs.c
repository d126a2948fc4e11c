/* Run time against error for every setting of the multipass plan that trades one for the other,
 * side by side per scene:
 * 24-bit against 32-bit float depth, RGBA32F against RGBA16F G-buffer slots, dmax automatic against
 * 10x and 1000x looser, and each skip of docs/gpu_pipeline.md switched off.
 *
 * Usage: bench_tradeoffs [out_dir]   (default bench/out; QUICK=1 for fewer runs and pixels)
 * Every variant has a renderer of its own (a renderer's caches are keyed on its settings, so sharing
 * one would recompile at every switch). After one warm-up frame each, the variants are timed in
 * rounds, one frame of each per round, so that the machine's drift falls on all of them alike; each
 * ratio is against the baseline's median. "baseline_again" is a second renderer with the baseline's
 * settings: its ratio shows how far two identical configurations differ on this machine.
 * Writes out_dir/tradeoffs.csv. */
#include <string.h>

#include "lib/bench_measure.h"
#include "scenes/scenes.h"

typedef enum variant_kind { V_BASELINE, V_FLOAT_DEPTH, V_HALF_GBUFFER, V_DMAX, V_SKIP_OFF } variant_kind;

typedef struct variant {
    const char *name;
    variant_kind kind;
    double dmax_factor; /* V_DMAX: times the largest automatic dmax of the frame */
    unsigned skip;      /* V_SKIP_OFF: the BG_SKIP_* bit switched off */
} variant;

static const variant variants[] = {
    {"baseline", V_BASELINE, 0, 0},
    {"float_depth_32", V_FLOAT_DEPTH, 0, 0},
    {"gbuffer_rgba16f", V_HALF_GBUFFER, 0, 0},
    {"dmax_x10", V_DMAX, 10.0, 0},
    {"dmax_x1000", V_DMAX, 1000.0, 0},
    {"no_specialize", V_SKIP_OFF, 0, BG_SKIP_SPECIALIZE},
    {"no_bounce_cull", V_SKIP_OFF, 0, BG_SKIP_BOUNCE_CULL},
    {"no_occlusion", V_SKIP_OFF, 0, BG_SKIP_OCCLUSION},
    {"no_stencil", V_SKIP_OFF, 0, BG_SKIP_STENCIL},
    {"no_scissor", V_SKIP_OFF, 0, BG_SKIP_SCISSOR},
    {"no_shadow_cull", V_SKIP_OFF, 0, BG_SKIP_SHADOW_CULL},
    {"no_facing", V_SKIP_OFF, 0, BG_SKIP_FACING},
    {"no_batch", V_SKIP_OFF, 0, BG_SKIP_BATCH},
    {"no_skips_at_all", V_SKIP_OFF, 0, BG_SKIP_ALL},
    {"baseline_again", V_BASELINE, 0, 0}, /* a second renderer, same settings: the noise floor */
};
#define VARIANT_COUNT (int)(sizeof variants / sizeof variants[0])

/* What one variant measured. */
typedef struct variant_result {
    bg_render_settings settings;
    bench_times times;
    bg_render_stats stats;
    bench_error error;
    long changed; /* pixels that differ from the baseline image */
} variant_result;

/* Pixels whose RGBA8 value differs from the baseline image in some channel. */
static long pixels_changed(const bg_image *a, const bg_image *b)
{
    const unsigned char *p = a->pixels, *q = b->pixels;
    long n = 0;
    for (long i = 0; i < (long)a->width * a->height; i++)
        n += memcmp(p + 4 * i, q + 4 * i, 3) != 0;
    return n;
}

/* The settings and renderer options of a variant; dmax_auto is the baseline's largest automatic dmax. */
static void variant_setup(const variant *var, double dmax_auto, bg_render_settings *settings, bg_renderer_desc *desc)
{
    /* Every setting traded here belongs to the multipass plan (docs/gpu_pipeline.md, "Plans"): the
     * baseline is that plan too, forced, so each ratio compares a multipass with a multipass. */
    *settings = bg_render_settings_init();
    settings->gpu_plan = BG_PLAN_MULTIPASS;
    memset(desc, 0, sizeof *desc);
    desc->float_depth = var->kind == V_FLOAT_DEPTH;
    desc->half_gbuffer = var->kind == V_HALF_GBUFFER;
    if (var->kind == V_DMAX)
        settings->dmax = var->dmax_factor * dmax_auto;
    if (var->kind == V_SKIP_OFF)
        settings->gpu_disable_skips = var->skip;
}

/* The automatic dmax of a frame: the largest over its levels. */
static double largest_dmax(bg_renderer *r)
{
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    double d = 0.0;
    for (int l = 0; l <= stats.levels && l < BG_STATS_MAX_LEVELS; l++)
        if (stats.dmax[l] > d)
            d = stats.dmax[l];
    return d;
}

static void print_row(FILE *csv, scene_id id, int size, int v, const variant_result *res, double baseline_ms)
{
    char text[128];
    printf("%-19s %-16s | %8.1f [%7.1f-%7.1f] | %5.2f | %7ld | %2d %2d | %s\n", scenes_name(id), variants[v].name,
           res->times.median, res->times.min, res->times.max, res->times.median / baseline_ms, res->changed,
           res->stats.depth_bits, res->stats.gbuffer_half_targets, bench_error_text(&res->error, text, sizeof text));
    fprintf(csv, "%s,%s,%d,%.3f,%.3f,%.3f,%.4f,%ld,%d,%d,%g,", scenes_name(id), variants[v].name, size,
            res->times.median, res->times.min, res->times.max, res->times.median / baseline_ms, res->changed,
            res->stats.depth_bits, res->stats.gbuffer_half_targets, res->settings.dmax);
    bench_error_csv(csv, &res->error);
    fputc('\n', csv);
}

static bool run_scene(bench_gpu *gpu, scene_id id, int size, int runs, FILE *csv)
{
    bg_scene *scene = bench_scene(id, NULL);
    bg_image ref, base, img;
    bool ok = scene && bench_image_alloc(&ref, size, size, BG_PIXEL_RGBA8);
    ok = ok && bench_image_alloc(&base, size, size, BG_PIXEL_RGBA8);
    ok = ok && bench_image_alloc(&img, size, size, BG_PIXEL_RGBA8);
    bg_render_settings cpu_settings = bg_render_settings_init();
    ok = ok && bg_render_cpu(scene, &cpu_settings, &ref) == BG_OK;
    bg_renderer *renderer[VARIANT_COUNT] = {NULL};
    variant_result results[VARIANT_COUNT];
    double times[VARIANT_COUNT][16];
    memset(results, 0, sizeof results);
    /* Warm-up: the baseline first, since the dmax variants derive from its automatic dmax. */
    double dmax_auto = 0.0;
    for (int v = 0; v < VARIANT_COUNT && ok; v++) {
        bg_renderer_desc desc;
        variant_setup(&variants[v], dmax_auto, &results[v].settings, &desc);
        renderer[v] = bench_gpu_renderer(gpu, desc);
        ok = renderer[v] && bg_render_gpu(renderer[v], scene, &results[v].settings, v ? &img : &base) == BG_OK;
        if (!ok && renderer[v])
            fprintf(stderr, "tradeoffs: %s: %s\n", variants[v].name, bg_renderer_error_message(renderer[v]));
        if (ok && v == 0)
            dmax_auto = largest_dmax(renderer[0]);
    }
    if (!ok)
        fprintf(stderr, "tradeoffs: warm-up of %s failed\n", scenes_name(id));
    for (int r = 0; r < runs && ok; r++) {
        bench_progress("tradeoffs: %s, round %d of %d", scenes_name(id), r + 1, runs);
        for (int v = 0; v < VARIANT_COUNT && ok; v++) {
            double t0 = bench_now_ms();
            ok = bg_render_gpu(renderer[v], scene, &results[v].settings, &img) == BG_OK;
            times[v][r] = bench_now_ms() - t0;
        }
    }
    /* One more frame each for the image, the error and the stats. */
    for (int v = 0; v < VARIANT_COUNT && ok; v++) {
        variant_result *res = &results[v];
        ok = bg_render_gpu(renderer[v], scene, &res->settings, &img) == BG_OK;
        res->times = bench_times_of(times[v], runs);
        bg_renderer_get_stats(renderer[v], &res->stats);
        res->error = bench_error_of(&ref, &img);
        res->changed = pixels_changed(&base, &img);
    }
    if (!ok)
        fprintf(stderr, "tradeoffs: a GPU render of %s failed\n", scenes_name(id));
    for (int v = 0; v < VARIANT_COUNT && ok; v++)
        print_row(csv, id, size, v, &results[v], results[0].times.median);
    fflush(stdout);
    for (int v = 0; v < VARIANT_COUNT; v++)
        bg_renderer_destroy(renderer[v]);
    if (scene) {
        bench_image_free(&ref);
        bench_image_free(&base);
        bench_image_free(&img);
    }
    bg_scene_destroy(scene);
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const int runs = quick ? 3 : 7, size = quick ? 256 : 512;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    FILE *csv = bench_csv_open(dir, "tradeoffs.csv",
                               "scene,variant,size,gpu_median_ms,gpu_min_ms,gpu_max_ms,time_ratio,"
                               "pixels_changed,depth_bits,half_gbuffer_targets,dmax," BENCH_ERROR_CSV_HEADER);
    int status = !csv;
    if (csv) {
        printf("== Run time against error at %dx%d (time ratio: against the baseline, timed in the same rounds)\n",
               size, size);
        bench_print_setup(stdout, &gpu, runs);
        printf("%-19s %-16s | %-26s | %5s | %6s | %2s %2s | %s\n", "scene", "variant", "GPU ms median [min-max]",
               "ratio", "changed", "zb", "hf", "GPU error vs CPU");
        printf("(changed: pixels that differ from the baseline image; zb: depth bits; hf: RGBA16F G-buffer targets)\n");
        const scene_id full[3] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS, SCENE_TEXTURED_ANISO};
        for (int i = 0; i < 3 && !status; i++)
            status = !run_scene(&gpu, full[i], size, runs, csv);
        fclose(csv);
    }
    bench_gpu_close(&gpu);
    return status;
}
