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

char *bench_error_brief(const bench_error *e, char *buffer, size_t size)
{
    if (e->psnr_db >= IMAGE_METRICS_PSNR_IDENTICAL)
        snprintf(buffer, size, "identical");
    else
        snprintf(buffer, size, "%5.1f dB max %3.0f", e->psnr_db, e->max_abs);
    return buffer;
}

char *bench_work_text(const macs_work *w, int width, int height, char *buffer, size_t size)
{
    double pixels = (double)width * (double)height;
    snprintf(buffer, size, "d %llu p %llu f %llu u %llu up %llu rb %.1f B/px s %llu c %llu",
             (unsigned long long)w->draws, (unsigned long long)w->program_binds,
             (unsigned long long)w->framebuffer_binds, (unsigned long long)w->uniform_calls,
             (unsigned long long)w->upload_bytes, pixels > 0.0 ? (double)w->readback_bytes / pixels : 0.0,
             (unsigned long long)w->syncs, (unsigned long long)w->programs_compiled);
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

bool bench_warm_up(bench_contestant *c)
{
    double t0 = bench_now_ms();
    bool ok = c->frame(c->user, c->image);
    c->warm_ms = bench_now_ms() - t0;
    if (!ok)
        fprintf(stderr, "%s: warm-up failed\n", c->name);
    return ok;
}

int bench_rounds_after(double warm_ms, int runs)
{
    return warm_ms > BENCH_SLOW_MS && runs > BENCH_SLOW_RUNS ? BENCH_SLOW_RUNS : runs;
}

static int most_rounds(const bench_contestant *list, int count)
{
    int most = 0;
    for (int i = 0; i < count; i++)
        if (list[i].rounds > most)
            most = list[i].rounds;
    return most;
}

bool bench_interleave(bench_contestant *list, int count, const char *label)
{
    const int rounds = most_rounds(list, count);
    if (rounds > BENCH_MAX_ROUNDS) {
        fprintf(stderr, "%s: %d rounds asked, at most %d\n", label, rounds, BENCH_MAX_ROUNDS);
        return false;
    }
    for (int r = 0; r < rounds; r++) {
        bench_progress("%s, round %d of %d", label, r + 1, rounds);
        for (int i = 0; i < count; i++) {
            bench_contestant *c = &list[i];
            if (r >= c->rounds)
                continue;
            double t0 = bench_now_ms();
            if (!c->frame(c->user, c->image)) {
                fprintf(stderr, "%s: %s failed in round %d\n", label, c->name, r + 1);
                return false;
            }
            c->ms[r] = bench_now_ms() - t0;
        }
    }
    for (int i = 0; i < count; i++) {
        double sorted[BENCH_MAX_ROUNDS];
        memcpy(sorted, list[i].ms, sizeof sorted);
        list[i].times = bench_times_of(sorted, list[i].rounds);
    }
    return true;
}

double bench_ratio(const bench_contestant *a, const bench_contestant *b)
{
    double ratios[BENCH_MAX_ROUNDS];
    int n = a->rounds < b->rounds ? a->rounds : b->rounds;
    for (int r = 0; r < n; r++)
        ratios[r] = a->ms[r] / b->ms[r];
    return n > 0 ? bench_times_of(ratios, n).median : 0.0;
}

char *bench_contestant_text(const bench_contestant *c, char *buffer, size_t size)
{
    if (c->rounds > 0)
        snprintf(buffer, size, "%2d %8.1f [%.1f-%.1f]", c->rounds, c->times.median, c->times.min, c->times.max);
    else
        snprintf(buffer, size, " -");
    return buffer;
}

bool bench_gpu_frame(void *job, bg_image *image)
{
    bench_gpu_job *g = job;
    if (!gpu_once(g->renderer, g->scene, &g->settings, image))
        return false;
    bg_renderer_get_stats(g->renderer, &g->stats);
    if (g->frames++ > 0 && g->stats.programs_compiled > 0)
        g->recompiled_frames++;
    return true;
}

bool bench_cpu_frame(void *job, bg_image *image)
{
    bench_cpu_job *c = job;
    return cpu_once(c->scene, &c->settings, image);
}

const char *bench_plan_name(bg_gpu_plan plan)
{
    switch (plan) {
    case BG_PLAN_FUSED: return "fused";
    case BG_PLAN_FUSED_TREE: return "fused-tree";
    case BG_PLAN_MULTIPASS: return "multipass";
    default: return "?";
    }
}
