/* Where a multipass frame's time goes: the renderer's per-phase times (settings.gpu_timing) and pass
 * counts, per scene, as medians over several frames. The multipass is forced: a fused plan draws one
 * pass, all of whose time is its intersection phase.
 *
 * Usage: bench_phases [out_dir]   (default bench/out; QUICK=1 for fewer scenes, runs and pixels)
 * Three renderers on one GL context are timed in interleaved rounds: untimed, timed with GPU timer
 * queries, and timed with the wall clock (a second MACS context hiding the timer extensions, as a
 * driver without them is), so the cost of each way of timing is visible beside the untimed frame.
 * Writes out_dir/phases.csv. */
#include <string.h>

#include "lib/bench_measure.h"
#include "scenes/scenes.h"

/* CSV names of the phases, and the short column heads of the table. */
static const char *const phase_names[BG_PHASE_COUNT_] = {"setup", "rays", "intersect", "shadow",
                                                         "light", "bounce", "resolve_readback"};
static const char *const phase_heads[BG_PHASE_COUNT_] = {"setup", "rays", "isect", "shadow",
                                                         "light", "bounce", "resolve"};

/* The renderers' warnings (a timed call whose timers cannot be right says so) on stderr. */
static void log_warning(bg_log_level level, const char *message, void *user)
{
    (void)user;
    if (level >= BG_LOG_WARNING)
        fprintf(stderr, "%s\n", message);
}

/* The three contestants of a scene: untimed, timed with GPU timers, timed with the wall clock. */
enum { UNTIMED, TIMERS, WALL, WAYS };
static const char *const way_names[WAYS] = {"untimed", "timers", "wall"};

/* One frame of a contestant: its call's wall time, and its stats. */
static bool frame(bg_renderer *r, bg_scene *scene, const bg_render_settings *settings, bg_image *img, double *ms,
                  bg_render_stats *stats)
{
    double t0 = bench_now_ms();
    if (bg_render_gpu(r, scene, settings, img) != BG_OK) {
        fprintf(stderr, "GPU render failed: %s\n", bg_renderer_error_message(r));
        return false;
    }
    *ms = bench_now_ms() - t0;
    bg_renderer_get_stats(r, stats);
    return true;
}

static bool run_scene(bg_renderer *const renderers[WAYS], scene_id id, int size, int runs, FILE *csv)
{
    bg_scene *scene = bench_scene(id, NULL);
    bg_image img;
    if (!scene || !bench_image_alloc(&img, size, size, BG_PIXEL_RGBA8)) {
        bg_scene_destroy(scene);
        return false;
    }
    bg_render_settings settings[WAYS];
    for (int w = 0; w < WAYS; w++) {
        settings[w] = bg_render_settings_init();
        settings[w].gpu_plan = BG_PLAN_MULTIPASS;
        settings[w].gpu_timing = w != UNTIMED;
    }
    double call[WAYS][16], phase[WAYS][BG_PHASE_COUNT_][16];
    bg_render_stats stats[WAYS];
    bool ok = true;
    /* Two warm-up frames each: programs, and the variants llvmpipe compiles on first use. */
    for (int k = 0; k < 2 && ok; k++)
        for (int w = 0; w < WAYS && ok; w++)
            ok = frame(renderers[w], scene, &settings[w], &img, &call[w][0], &stats[w]);
    /* Interleaved rounds: one frame of each contestant per round. */
    for (int r = 0; r < runs && ok; r++)
        for (int w = 0; w < WAYS && ok; w++) {
            ok = frame(renderers[w], scene, &settings[w], &img, &call[w][r], &stats[w]);
            if (ok && w != UNTIMED && !stats[w].timed) {
                fprintf(stderr, "%s: a %s frame was not timed\n", scenes_name(id), way_names[w]);
                ok = false;
            }
            for (int p = 0; p < BG_PHASE_COUNT_ && ok; p++)
                phase[w][p][r] = stats[w].phase_ms[p];
        }
    if (ok && (stats[TIMERS].timing != BG_TIMING_GPU_TIMERS || stats[WALL].timing != BG_TIMING_WALL_CLOCK)) {
        fprintf(stderr, "%s: the timed renderers did not time as asked (timers %d, wall %d)\n", scenes_name(id),
                (int)stats[TIMERS].timing, (int)stats[WALL].timing);
        ok = false;
    }
    if (ok) {
        bench_times t[WAYS];
        for (int w = 0; w < WAYS; w++)
            t[w] = bench_times_of(call[w], runs);
        printf("%-19s | %8.1f %8.1f %8.1f |", scenes_name(id), t[UNTIMED].median, t[TIMERS].median, t[WALL].median);
        for (int w = TIMERS; w < WAYS; w++) {
            for (int p = 0; p < BG_PHASE_COUNT_; p++) {
                bench_times pt = bench_times_of(phase[w][p], runs);
                if (w == TIMERS)
                    printf(" %7.2f", pt.median);
                fprintf(csv, "%s,%d,%s,%s,%.3f,%.3f,%.3f\n", scenes_name(id), size, way_names[w], phase_names[p],
                        pt.median, t[w].median, t[UNTIMED].median);
            }
        }
        const bg_render_stats *st = &stats[TIMERS];
        printf(" | %5d %3d %4d %4d | %4llu %4llu %4llu\n", bench_total_passes(st), st->ray_sets,
               st->passes[BG_PASS_INTERSECT], st->passes[BG_PASS_SHADOW],
               (unsigned long long)stats[UNTIMED].gl_work.syncs, (unsigned long long)stats[TIMERS].gl_work.syncs,
               (unsigned long long)stats[WALL].gl_work.syncs);
        fflush(stdout);
    }
    bench_image_free(&img);
    bg_scene_destroy(scene);
    return ok;
}

/* A MACS context on the session's GL context with both timer extensions hidden, and a renderer on it:
 * the wall-clock fallback, as a driver without timer queries takes it. */
static bool open_wall_clock(bench_gpu *gpu, macs_context **ctx, bg_renderer **r)
{
    macs_context_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.get_proc_address = macs_headless_get_proc_address(gpu->headless);
    cd.get_proc_address_user = macs_headless_proc_user(gpu->headless);
    cd.hidden_extensions = "GL_ARB_timer_query GL_EXT_timer_query";
    char message[512];
    *r = NULL;
    if (macs_context_create(&cd, ctx, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "MACS context: %s\n", message);
        return false;
    }
    bg_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.context = *ctx;
    rd.logger.func = log_warning;
    if (bg_renderer_create(&rd, r, message, sizeof message) != BG_OK) {
        fprintf(stderr, "renderer: %s\n", message);
        macs_context_destroy(*ctx);
        return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const int runs = quick ? 3 : 7, size = quick ? 256 : 512;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    macs_features features;
    macs_context_get_features(gpu.context, &features);
    if (!features.timer_query) {
        fprintf(stderr, "bench_phases: the GL context has neither GL_ARB_timer_query nor GL_EXT_timer_query\n");
        bench_gpu_close(&gpu);
        return 1;
    }
    macs_context *wall_ctx = NULL;
    bg_renderer *wall = NULL;
    bg_renderer_desc logged = {0};
    logged.logger.func = log_warning;
    bg_renderer *timers = bench_gpu_renderer(&gpu, logged);
    FILE *csv = NULL;
    int status = 1;
    if (timers && open_wall_clock(&gpu, &wall_ctx, &wall))
        csv = bench_csv_open(dir, "phases.csv", "scene,size,timing,phase,median_ms,timed_call_ms,untimed_call_ms");
    if (csv) {
        printf("== Where multipass GPU time goes at %dx%d: medians in ms of %d interleaved rounds\n", size, size, runs);
        bench_print_setup(stdout, &gpu, runs);
        printf("   call times: untimed, timed with GPU timers, timed with the wall clock (glFinish around each phase);\n"
               "   phases: GPU timer medians; syncs: of the untimed, timers and wall-clock calls\n");
        printf("%-19s | %8s %8s %8s |", "scene", "untimed", "timers", "wall");
        for (int p = 0; p < BG_PHASE_COUNT_; p++)
            printf(" %7s", phase_heads[p]);
        printf(" | passes sets isect shadow | syncs\n");
        const scene_id ids[] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW, SCENE_MANY_LIGHTS, SCENE_TEXTURED_ANISO,
                                SCENE_MIRROR, SCENE_GLASS};
        const int count = quick ? 3 : (int)(sizeof ids / sizeof ids[0]);
        bg_renderer *const renderers[WAYS] = {gpu.renderer, timers, wall};
        status = 0;
        for (int i = 0; i < count && !status; i++) {
            bench_progress("phases: %s", scenes_name(ids[i]));
            status = !run_scene(renderers, ids[i], size, runs, csv);
        }
        fclose(csv);
    }
    bg_renderer_destroy(wall);
    macs_context_destroy(wall_ctx);
    bg_renderer_destroy(timers);
    bench_gpu_close(&gpu);
    return status;
}
