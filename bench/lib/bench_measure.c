/* Timed renders and their error: see bench_measure.h. */
#include "bench_measure.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static bool gpu_once(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings, bg_image *image)
{
    if (bg_render_gpu(renderer, scene, settings, image) == BG_OK)
        return true;
    fprintf(stderr, "GPU render failed: %s\n", bg_renderer_error_message(renderer));
    return false;
}

static bool cpu_once(bg_scene *scene, const bg_render_settings *settings, bg_image *image)
{
    bg_status st = bg_render_cpu(scene, settings, image);
    if (st == BG_OK)
        return true;
    fprintf(stderr, "CPU render failed: %s\n", bg_status_string(st));
    return false;
}

/* The shared timing loop of both renderers; renderer NULL means the CPU reference. */
static bool time_renders(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                         bg_image *image, int runs, bench_times *out)
{
    double *t = malloc(sizeof *t * (size_t)(runs > 0 ? runs : 1));
    if (!t) {
        fprintf(stderr, "out of memory\n");
        return false;
    }
    double t0 = bench_now_ms();
    bool ok = renderer ? gpu_once(renderer, scene, settings, image) : cpu_once(scene, settings, image);
    if (bench_now_ms() - t0 > BENCH_SLOW_MS && runs > BENCH_SLOW_RUNS)
        runs = BENCH_SLOW_RUNS;
    for (int r = 0; r < runs && ok; r++) {
        t0 = bench_now_ms();
        ok = renderer ? gpu_once(renderer, scene, settings, image) : cpu_once(scene, settings, image);
        t[r] = bench_now_ms() - t0;
    }
    if (ok)
        *out = bench_times_of(t, runs);
    free(t);
    return ok;
}

bool bench_time_gpu(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings, bg_image *image,
                    int runs, bench_times *out)
{
    return renderer && time_renders(renderer, scene, settings, image, runs, out);
}

bool bench_time_cpu(bg_scene *scene, const bg_render_settings *settings, bg_image *image, int runs,
                    bench_times *out)
{
    return time_renders(NULL, scene, settings, image, runs, out);
}

bench_error bench_error_of(const bg_image *reference, const bg_image *test)
{
    bench_error e;
    memset(&e, 0, sizeof e);
    image_metrics m;
    if (!image_metrics_compare(reference, test, BENCH_SILHOUETTE, &m)) {
        e.psnr_db = 0.0;
        e.max_abs = e.mean_abs = e.interior_max = 255.0;
        e.over_share = 1.0;
        return e;
    }
    e.psnr_db = m.all.psnr_db;
    for (int c = 0; c < 3; c++) {
        if (m.all.max_abs[c] > e.max_abs)
            e.max_abs = m.all.max_abs[c];
        if (m.interior.max_abs[c] > e.interior_max)
            e.interior_max = m.interior.max_abs[c];
        e.mean_abs += m.all.mean_abs[c] / 3.0;
    }
    e.over_share = m.all.over_share;
    return e;
}

void bench_error_csv(FILE *f, const bench_error *e)
{
    fprintf(f, "%.2f,%.0f,%.5f,%.6f,%.0f", e->psnr_db, e->max_abs, e->mean_abs, e->over_share, e->interior_max);
}

char *bench_error_text(const bench_error *e, char *buffer, size_t size)
{
    if (e->psnr_db >= IMAGE_METRICS_PSNR_IDENTICAL)
        snprintf(buffer, size, "identical");
    else
        snprintf(buffer, size, "PSNR %5.1f dB, max %3.0f, mean %.4f, over %.3f%%", e->psnr_db, e->max_abs,
                 e->mean_abs, 100.0 * e->over_share);
    return buffer;
}

int bench_total_passes(const bg_render_stats *stats)
{
    int passes = 0;
    for (int k = 0; k < BG_PASS_KIND_COUNT_; k++)
        passes += stats->passes[k];
    return passes;
}

/* The CPU model from /proc/cpuinfo, or "?" where there is none. */
static void cpu_model(char *buffer, size_t size)
{
    snprintf(buffer, size, "?");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) == 0 && colon) {
            colon += 2;
            colon[strcspn(colon, "\n")] = '\0';
            snprintf(buffer, size, "%s", colon);
            break;
        }
    }
    fclose(f);
}

void bench_print_setup(FILE *f, const bench_gpu *gpu, int runs)
{
    char cpu[256];
    cpu_model(cpu, sizeof cpu);
    const char *lp = getenv("LP_NUM_THREADS");
    fprintf(f, "machine: %s, %ld online cores\n", cpu, sysconf(_SC_NPROCESSORS_ONLN));
    fprintf(f, "GL: %s; LP_NUM_THREADS=%s; CPU reference threads = online cores; %d timed runs after a warm-up\n",
            gpu ? gpu->renderer_name : "-", lp ? lp : "(unset)", runs);
}
