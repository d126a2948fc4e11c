/* Run time against error for every setting that trades one for the other, side by side per scene:
 * 24-bit against 32-bit float depth, RGBA32F against RGBA16F G-buffer slots, dmax automatic against
 * 10x and 1000x looser, and each skip of DESIGN.md section 5 switched off.
 *
 * Usage: bench_tradeoffs [out_dir]   (default bench/out; QUICK=1 for fewer scenes, runs and pixels)
 * Every variant is timed in one block (warm-up, then runs back to back) right after the others, and
 * the baseline is timed first and again last; each ratio is against the mean of the two baseline
 * medians, and the drift between them shows the machine's noise. Writes out_dir/tradeoffs.csv. */
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
    {"no_skips_at_all", V_SKIP_OFF, 0, BG_SKIP_ALL},
    {"baseline_again", V_BASELINE, 0, 0},
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

/* Renderers that differ in creation-time options: index 0 default, 1 float depth, 2 half G-buffer. */
typedef struct renderers {
    bg_renderer *by_kind[3];
} renderers;

static bg_renderer *renderer_for(const renderers *rs, variant_kind kind)
{
    return kind == V_FLOAT_DEPTH ? rs->by_kind[1] : kind == V_HALF_GBUFFER ? rs->by_kind[2] : rs->by_kind[0];
}

/* Pixels whose RGBA8 value differs from the baseline image in some channel. */
static long pixels_changed(const bg_image *a, const bg_image *b)
{
    const unsigned char *p = a->pixels, *q = b->pixels;
    long n = 0;
    for (long i = 0; i < (long)a->width * a->height; i++)
        n += memcmp(p + 4 * i, q + 4 * i, 3) != 0;
    return n;
}

static bool run_scene(const renderers *rs, scene_id id, int size, int runs, FILE *csv)
{
    bg_scene *scene = bench_scene(id, NULL);
    bg_image ref, base, img;
    bool ok = scene && bench_image_alloc(&ref, size, size, BG_PIXEL_RGBA8);
    ok = ok && bench_image_alloc(&base, size, size, BG_PIXEL_RGBA8);
    ok = ok && bench_image_alloc(&img, size, size, BG_PIXEL_RGBA8);
    bg_render_settings settings = bg_render_settings_init();
    ok = ok && bg_render_cpu(scene, &settings, &ref) == BG_OK;
    /* The automatic dmax of the frame: the largest over its levels. */
    double dmax_auto = 0.0;
    ok = ok && bg_render_gpu(rs->by_kind[0], scene, &settings, &base) == BG_OK;
    if (ok) {
        bg_render_stats stats;
        bg_renderer_stats(rs->by_kind[0], &stats);
        for (int l = 0; l <= stats.levels && l < BG_STATS_MAX_LEVELS; l++)
            if (stats.dmax[l] > dmax_auto)
                dmax_auto = stats.dmax[l];
    }
    variant_result results[VARIANT_COUNT];
    double baseline_sum = 0.0;
    for (int v = 0; v < VARIANT_COUNT && ok; v++) {
        const variant *var = &variants[v];
        variant_result *res = &results[v];
        res->settings = settings;
        if (var->kind == V_DMAX)
            res->settings.dmax = var->dmax_factor * dmax_auto;
        if (var->kind == V_SKIP_OFF)
            res->settings.gpu_disable_skips = var->skip;
        bg_renderer *r = renderer_for(rs, var->kind);
        bench_progress("tradeoffs: %s, %s", scenes_name(id), var->name);
        ok = bench_time_gpu(r, scene, &res->settings, &img, runs, &res->times);
        if (!ok)
            break;
        bg_renderer_stats(r, &res->stats);
        if (var->kind == V_BASELINE)
            baseline_sum += res->times.median;
        res->error = bench_error_of(&ref, &img);
        res->changed = pixels_changed(&base, &img);
    }
    /* Ratios only once both baselines are in: each against their mean. */
    const double baseline_ms = baseline_sum / 2.0;
    for (int v = 0; v < VARIANT_COUNT && ok; v++) {
        const variant_result *res = &results[v];
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
    fflush(stdout);
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
    const char *dir = argc > 1 ? argv[1] : "bench/out";
    const bool quick = bench_quick();
    const int runs = quick ? 3 : 5, size = quick ? 256 : 512;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    renderers rs;
    bg_renderer_desc depth_desc, half_desc;
    memset(&depth_desc, 0, sizeof depth_desc);
    memset(&half_desc, 0, sizeof half_desc);
    depth_desc.float_depth = true;
    half_desc.half_gbuffer = true;
    rs.by_kind[0] = gpu.renderer;
    rs.by_kind[1] = bench_gpu_renderer(&gpu, depth_desc);
    rs.by_kind[2] = bench_gpu_renderer(&gpu, half_desc);
    FILE *csv = rs.by_kind[1] && rs.by_kind[2]
                    ? bench_csv_open(dir, "tradeoffs.csv",
                                     "scene,variant,size,gpu_median_ms,gpu_min_ms,gpu_max_ms,time_ratio,"
                                     "pixels_changed,depth_bits,half_gbuffer_targets,dmax," BENCH_ERROR_CSV_HEADER)
                    : NULL;
    int status = !csv;
    if (csv) {
        printf("== Run time against error at %dx%d (time ratio: against the mean of the two baseline medians)\n",
               size, size);
        bench_print_setup(stdout, &gpu, runs);
        printf("%-19s %-16s | %-26s | %5s | %6s | %2s %2s | %s\n", "scene", "variant", "GPU ms median [min-max]",
               "ratio", "changed", "zb", "hf", "GPU error vs CPU");
        printf("(changed: pixels that differ from the baseline image; zb: depth bits; hf: RGBA16F G-buffer targets)\n");
        const scene_id full[3] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS, SCENE_TEXTURED_ANISO};
        const int count = quick ? 2 : 3;
        for (int i = 0; i < count && !status; i++)
            status = !run_scene(&rs, full[i], size, runs, csv);
        fclose(csv);
    }
    bg_renderer_destroy(rs.by_kind[1]);
    bg_renderer_destroy(rs.by_kind[2]);
    bench_gpu_close(&gpu);
    return status;
}
