/* What a frame of the paper's scenes costs the driver: per scene, size and GPU plan, the cached frame
 * into an RGBA8 image (read back) and into an RGBA8 texture (no read-back; the time runs until
 * glFinish returns), its phases by GPU timer (settings.gpu_timing) and its GL work. This is the table
 * the device check prints on a real GPU (docs/device_check.md), where the question is which phase
 * holds a frame's time once the pixel work is cheap.
 *
 * Usage: bench_frame_cost [out_dir]   (default bench/out; QUICK=1 for fewer runs)
 * Per case: two warm-up frames of each contestant, then interleaved rounds of one frame each of
 * image, texture and timed image per plan, each plan on a renderer of its own. Writes
 * out_dir/frame_cost.csv. */
#include <string.h>

#include "lib/bench_measure.h"
#include "scenes/scenes.h"

enum { PLANS = 3, IMAGE = 0, TEXTURE, TIMED, WAYS };
static const bg_gpu_plan plans[PLANS] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
static const char *const plan_names[PLANS] = {"fused", "tree", "multipass"};
static const char *const phase_heads[BG_PHASE_COUNT_] = {"setup", "rays", "isect", "shadow", "light", "bounce",
                                                         "resolve"};

#define MAX_RUNS 16

typedef struct contestant {
    bg_renderer *renderer;
    double ms[WAYS][MAX_RUNS];
    double phase[BG_PHASE_COUNT_][MAX_RUNS];
    bg_render_stats image_stats, timed_stats;
} contestant;

/* One frame of one way; its wall time in *ms. */
static bool frame(bench_gpu *gpu, contestant *c, bg_scene *scene, bg_render_settings settings, int way,
                  bg_image *img, macs_texture *texture, double *ms)
{
    settings.gpu_timing = way == TIMED;
    double t0 = bench_now_ms();
    bg_status st = way == TEXTURE ? bg_render_gpu_to_texture(c->renderer, scene, &settings, texture)
                                  : bg_render_gpu(c->renderer, scene, &settings, img);
    /* Into a texture the call returns before the GPU is done; the frame is done when it is. */
    if (way == TEXTURE)
        macs_context_finish(gpu->context);
    *ms = bench_now_ms() - t0;
    if (st != BG_OK) {
        fprintf(stderr, "GPU render failed: %s\n", bg_renderer_error_message(c->renderer));
        return false;
    }
    if (way == IMAGE)
        bg_renderer_get_stats(c->renderer, &c->image_stats);
    if (way == TIMED)
        bg_renderer_get_stats(c->renderer, &c->timed_stats);
    return true;
}

static bool run_case(bench_gpu *gpu, contestant *cs, scene_id id, int size, int runs, FILE *csv)
{
    bg_scene *scene = bench_scene(id, NULL);
    bg_image img;
    macs_texture *texture = NULL;
    macs_texture_desc td = {0};
    td.width = td.height = size;
    td.format = MACS_FORMAT_RGBA8;
    if (!scene || !bench_image_alloc(&img, size, size, BG_PIXEL_RGBA8)) {
        bg_scene_destroy(scene);
        return false;
    }
    bool ok = macs_texture_create(gpu->context, &td, &texture) == MACS_OK;
    if (!ok)
        fprintf(stderr, "texture: %s\n", macs_context_error_message(gpu->context));
    bg_render_settings settings[PLANS];
    for (int p = 0; p < PLANS; p++) {
        settings[p] = bg_render_settings_init();
        settings[p].gpu_plan = plans[p];
    }
    double scratch;
    for (int k = 0; k < 2 && ok; k++)
        for (int p = 0; p < PLANS && ok; p++)
            for (int w = 0; w < WAYS && ok; w++)
                ok = frame(gpu, &cs[p], scene, settings[p], w, &img, texture, &scratch);
    for (int r = 0; r < runs && ok; r++)
        for (int p = 0; p < PLANS && ok; p++)
            for (int w = 0; w < WAYS && ok; w++) {
                ok = frame(gpu, &cs[p], scene, settings[p], w, &img, texture, &cs[p].ms[w][r]);
                for (int ph = 0; ph < BG_PHASE_COUNT_ && ok && w == TIMED; ph++)
                    cs[p].phase[ph][r] = cs[p].timed_stats.timed ? cs[p].timed_stats.phase_ms[ph] : -1.0;
            }
    for (int p = 0; p < PLANS && ok; p++) {
        contestant *c = &cs[p];
        bench_times t[WAYS];
        for (int w = 0; w < WAYS; w++)
            t[w] = bench_times_of(c->ms[w], runs);
        const char *how = c->timed_stats.timing == BG_TIMING_GPU_TIMERS   ? "timers"
                          : c->timed_stats.timing == BG_TIMING_WALL_CLOCK ? "wall"
                                                                          : "none";
        printf("%-19s %5d %-9s | %8.2f %8.2f %8.2f | %-6s", scenes_name(id), size, plan_names[p], t[IMAGE].median,
               t[TEXTURE].median, t[TIMED].median, how);
        fprintf(csv, "%s,%d,%s,%.3f,%.3f,%.3f,%s", scenes_name(id), size, plan_names[p], t[IMAGE].median,
                t[TEXTURE].median, t[TIMED].median, how);
        for (int ph = 0; ph < BG_PHASE_COUNT_; ph++) {
            bench_times pt = bench_times_of(c->phase[ph], runs);
            printf(" %7.3f", pt.median);
            fprintf(csv, ",%.4f", pt.median);
        }
        char work[160];
        bench_work_text(&c->image_stats.gl_work, size, size, work, sizeof work);
        printf(" | %s\n", work);
        fprintf(csv, ",%llu,%llu,%llu\n", (unsigned long long)c->image_stats.gl_work.draws,
                (unsigned long long)c->image_stats.gl_work.readback_bytes,
                (unsigned long long)c->image_stats.gl_work.syncs);
    }
    fflush(stdout);
    macs_texture_destroy(texture);
    bench_image_free(&img);
    bg_scene_destroy(scene);
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const bool quick = bench_quick();
    const int runs = quick ? 3 : 9;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    contestant cs[PLANS];
    memset(cs, 0, sizeof cs);
    bool ok = true;
    for (int p = 0; p < PLANS && ok; p++)
        ok = (cs[p].renderer = bench_gpu_renderer(&gpu, (bg_renderer_desc){0})) != NULL;
    FILE *csv = ok ? bench_csv_open(dir, "frame_cost.csv",
                                    "scene,size,plan,image_ms,texture_ms,timed_image_ms,timing,setup_ms,rays_ms,"
                                    "intersect_ms,shadow_ms,light_ms,bounce_ms,resolve_ms,draws,readback_bytes,syncs")
                   : NULL;
    int status = 1;
    if (csv) {
        printf("== What a cached frame costs: medians in ms of %d interleaved rounds\n", runs);
        bench_print_setup(stdout, &gpu, runs);
        printf("   image: bg_render_gpu into RGBA8 (read back); texture: bg_render_gpu_to_texture into RGBA8 until\n"
               "   glFinish; timed: an image frame with gpu_timing, whose phases (GPU time, ms) follow; work: of the\n"
               "   image frame\n");
        printf("%-19s %5s %-9s | %8s %8s %8s | %-6s", "scene", "size", "plan", "image", "texture", "timed", "timing");
        for (int ph = 0; ph < BG_PHASE_COUNT_; ph++)
            printf(" %7s", phase_heads[ph]);
        printf(" | work\n");
        const scene_id ids[] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW};
        const int sizes[] = {512, 1024};
        status = 0;
        for (int s = 0; s < 2 && !status; s++)
            for (int i = 0; i < 2 && !status; i++) {
                bench_progress("frame cost: %s at %d", scenes_name(ids[i]), sizes[s]);
                status = !run_case(&gpu, cs, ids[i], sizes[s], runs, csv);
            }
        fclose(csv);
    }
    for (int p = 0; p < PLANS; p++)
        bg_renderer_destroy(cs[p].renderer);
    bench_gpu_close(&gpu);
    return status;
}
