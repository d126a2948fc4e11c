/* Where a multipass frame's time goes: the renderer's per-phase wall times (settings.gpu_timing)
 * and pass counts, per scene, as medians over several frames. The multipass is forced: a fused plan
 * draws one pass, all of whose time is its intersection phase.
 *
 * Usage: bench_phases [out_dir]   (default bench/out; QUICK=1 for fewer scenes, runs and pixels)
 * Timing waits for the GPU between phases, so a timed frame is slower than an untimed one; both are
 * measured (untimed first) and printed, so the overhead is visible. Writes out_dir/phases.csv. */
#include <string.h>

#include "lib/bench_measure.h"
#include "scenes/scenes.h"

/* CSV names of the phases, and the short column heads of the table. */
static const char *const phase_names[BG_PHASE_COUNT_] = {"setup", "rays", "intersect", "shadow",
                                                         "light", "bounce", "resolve_readback"};
static const char *const phase_heads[BG_PHASE_COUNT_] = {"setup", "rays", "isect", "shadow",
                                                         "light", "bounce", "resolve"};

static bool run_scene(bench_gpu *gpu, scene_id id, int size, int runs, FILE *csv)
{
    bg_scene *scene = bench_scene(id, NULL);
    bg_image img;
    if (!scene || !bench_image_alloc(&img, size, size, BG_PIXEL_RGBA8)) {
        bg_scene_destroy(scene);
        return false;
    }
    bg_render_settings settings = bg_render_settings_init();
    settings.gpu_plan = BG_PLAN_MULTIPASS;
    bench_times untimed;
    bool ok = bench_time_gpu(gpu->renderer, scene, &settings, &img, runs, &untimed);
    settings.gpu_timing = true;
    /* The first timed frame compiles llvmpipe's variants for the timing queries: a second warm-up. */
    ok = ok && bg_render_gpu(gpu->renderer, scene, &settings, &img) == BG_OK;
    double phase[BG_PHASE_COUNT_][16], total[16];
    bg_render_stats stats;
    memset(&stats, 0, sizeof stats);
    for (int r = 0; r < runs && ok; r++) {
        ok = bg_render_gpu(gpu->renderer, scene, &settings, &img) == BG_OK;
        bg_renderer_get_stats(gpu->renderer, &stats);
        ok = ok && stats.timed;
        for (int p = 0; p < BG_PHASE_COUNT_ && ok; p++)
            phase[p][r] = stats.phase_ms[p];
        total[r] = stats.total_ms;
    }
    if (!ok)
        fprintf(stderr, "timed GPU render of %s failed: %s\n", scenes_name(id), bg_renderer_error_message(gpu->renderer));
    if (ok) {
        bench_times t = bench_times_of(total, runs);
        printf("%-19s | %8.1f | %8.1f |", scenes_name(id), untimed.median, t.median);
        for (int p = 0; p < BG_PHASE_COUNT_; p++) {
            bench_times pt = bench_times_of(phase[p], runs);
            printf(" %8.2f", pt.median);
            fprintf(csv, "%s,%d,%s,%.3f,%.4f,%.3f,%.3f\n", scenes_name(id), size, phase_names[p], pt.median,
                    t.median > 0 ? pt.median / t.median : 0.0, t.median, untimed.median);
        }
        int passes = bench_total_passes(&stats);
        printf(" | %5d %3d %4d %4d\n", passes, stats.ray_sets, stats.passes[BG_PASS_INTERSECT],
               stats.passes[BG_PASS_SHADOW]);
        fflush(stdout);
    }
    bench_image_free(&img);
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
    FILE *csv = bench_csv_open(dir, "phases.csv", "scene,size,phase,median_ms,share,timed_total_ms,untimed_total_ms");
    if (!csv) {
        bench_gpu_close(&gpu);
        return 1;
    }
    printf("== Where multipass GPU time goes at %dx%d: medians in ms (phase timing waits for the GPU between phases)\n",
           size, size);
    bench_print_setup(stdout, &gpu, runs);
    printf("%-19s | %8s | %8s |", "scene", "untimed", "timed");
    for (int p = 0; p < BG_PHASE_COUNT_; p++)
        printf(" %8s", phase_heads[p]);
    printf(" | passes sets isect shadow\n");
    const scene_id ids[] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW, SCENE_MANY_LIGHTS, SCENE_TEXTURED_ANISO,
                            SCENE_MIRROR, SCENE_GLASS};
    const int count = quick ? 3 : (int)(sizeof ids / sizeof ids[0]);
    int status = 0;
    for (int i = 0; i < count && !status; i++) {
        bench_progress("phases: %s", scenes_name(ids[i]));
        status = !run_scene(&gpu, ids[i], size, runs, csv);
    }
    fclose(csv);
    bench_gpu_close(&gpu);
    return status;
}
