/* The paper's table: its two scenes at 512x512 and 1024x1024 on the GPU path (its fused plan, its
 * multipass plan and its fused tree plan, each forced, each on a renderer of its own so that each keeps
 * its caches), the CPU reference and, when povray is installed, POV-Ray 3.7 rendering the same scenes as
 * a whole process.
 *
 * Usage: bench_paper [out_dir]   (default bench/out; QUICK=1 for fewer runs)
 * Per case: one warm-up frame each, then interleaved rounds of one fused, one multipass, one tree and one
 * CPU reference frame, so that the drift of a shared machine falls on all alike and each ratio (the median
 * of the per-round ratios) is measured side by side; a contestant whose warm-up took over BENCH_SLOW_MS
 * takes part in the first BENCH_SLOW_RUNS rounds only. POV-Ray runs after the rounds, a warm-up and `runs`
 * timed processes. Writes out_dir/paper.csv. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/bench_measure.h"
#include "lib/pov_export.h"
#include "scenes/scenes.h"

/* The contestants in round order: the three plans, then the CPU reference. */
enum { FUSED, MULTIPASS, TREE, CPU, CONTESTANTS };
#define PLANS CPU
static const char *const contestant_names[CONTESTANTS] = {"fused", "multipass", "fused-tree", "CPU reference"};
static const bg_gpu_plan plans[PLANS] = {BG_PLAN_FUSED, BG_PLAN_MULTIPASS, BG_PLAN_FUSED_TREE};

typedef struct pov_case {
    bool ran;
    bench_times times;
    bench_times startup; /* a 1x1 render of the same file: process start-up and parsing */
    bench_error error; /* POV-Ray's image against the CPU reference: a different shading model */
} pov_case;

/* Times POV-Ray on one scene and size: one warm-up run (file cache), then `runs` timed runs. */
static bool time_pov(scene_id id, const char *dir, int size, int runs, const bg_image *reference, pov_case *out)
{
    char pov[1024], png[1100], message[512];
    memset(out, 0, sizeof *out);
    if (!pov_write_scene(id, dir, pov, sizeof pov, message, sizeof message)) {
        fprintf(stderr, "POV-Ray export: %s\n", message);
        return false;
    }
    snprintf(png, sizeof png, "%s/%s_pov_%d.png", dir, scenes_name(id), size);
    int threads = (int)sysconf(_SC_NPROCESSORS_ONLN);
    char tiny[1100];
    snprintf(tiny, sizeof tiny, "%s/%s_pov_1.png", dir, scenes_name(id));
    double t[64], t1[64], ms = 0.0;
    bool ok = runs <= 64 && pov_render(pov, size, size, threads, png, &ms, message, sizeof message);
    for (int r = 0; r < runs && ok; r++) {
        ok = pov_render(pov, size, size, threads, png, &ms, message, sizeof message) &&
             pov_render(pov, 1, 1, threads, tiny, &t1[r], message, sizeof message);
        t[r] = ms;
    }
    if (!ok) {
        fprintf(stderr, "POV-Ray: %s\n", message);
        return false;
    }
    out->ran = true;
    out->times = bench_times_of(t, runs);
    out->startup = bench_times_of(t1, runs);
    bg_image image;
    if (bench_image_alloc(&image, size, size, BG_PIXEL_RGBA8)) {
        if (bg_png_load(png, &image, message, sizeof message) == BG_OK)
            out->error = bench_error_of(reference, &image);
        bench_image_free(&image);
    }
    return true;
}

/* One case: its contestants with their state and images, and what they measured. */
typedef struct case_run {
    bench_contestant c[CONTESTANTS];
    bg_image images[CONTESTANTS]; /* images[CPU] is the reference */
    bench_gpu_job gpu[PLANS];
    bench_cpu_job cpu;
    bench_error error[PLANS]; /* against the reference */
    pov_case pov;
} case_run;

static bool case_setup(case_run *run, bg_renderer *const renderers[PLANS], bg_scene *scene, int size)
{
    memset(run, 0, sizeof *run);
    bg_render_settings settings = bg_render_settings_init();
    bool ok = true;
    for (int i = 0; i < CONTESTANTS; i++) {
        ok = ok && bench_image_alloc(&run->images[i], size, size, BG_PIXEL_RGBA8);
        run->c[i] = (bench_contestant){.name = contestant_names[i], .image = &run->images[i]};
        if (i < PLANS) {
            run->gpu[i] = (bench_gpu_job){.renderer = renderers[i], .scene = scene, .settings = settings};
            run->gpu[i].settings.gpu_plan = plans[i];
            run->c[i].frame = bench_gpu_frame;
            run->c[i].user = &run->gpu[i];
        }
    }
    run->cpu = (bench_cpu_job){scene, settings};
    run->c[CPU].frame = bench_cpu_frame;
    run->c[CPU].user = &run->cpu;
    return ok;
}

/* Warm-ups, interleaved rounds, then each plan's error against the reference. */
static bool time_case(case_run *run, const char *label, int runs)
{
    for (int i = 0; i < CONTESTANTS; i++) {
        if (!bench_warm_up(&run->c[i]))
            return false;
        run->c[i].rounds = bench_rounds_after(run->c[i].warm_ms, runs);
    }
    if (!bench_interleave(run->c, CONTESTANTS, label))
        return false;
    for (int p = 0; p < PLANS; p++)
        run->error[p] = bench_error_of(&run->images[CPU], &run->images[p]);
    return true;
}

/* The table's columns: the header and every row share these widths. */
#define TABLE_FORMAT(x) "%-19s %5" x " | %-24s | %-24s | %-24s | %-24s | %-22s | %7s %7s %7s %7s | %-47s | %-16s | %s\n"

static void print_header(const bench_gpu *gpu, bool pov, int runs)
{
    printf("== Paper scenes: GPU path (three plans), CPU reference%s\n", pov ? ", POV-Ray 3.7 (whole process)" : "");
    bench_print_setup(stdout, gpu, runs);
    if (!pov)
        printf("povray not installed: the POV-Ray columns are empty\n");
    printf("GPU: the fused plan; MP: the multipass plan; tree: the fused tree plan (each forced, each its own\n"
           "renderer). Rounds: GPU, MP, tree, CPU; cells: n rounds, ms median [min-max]; ratios against the fused\n"
           "plan, medians of the per-round ratios (POV/GPU: of the medians, POV-Ray timed after the rounds).\n"
           "Under each row, each plan's GL work per frame (bg_render_stats.gl_work): d draws, p program binds,\n"
           "f framebuffer binds, u uniform calls, up bytes uploaded, rb bytes read back a pixel, s syncs, c programs\n"
           "compiled\n");
    printf(TABLE_FORMAT("s"), "scene", "size", "GPU: n ms [min-max]", "MP: n ms [min-max]", "tree: n ms [min-max]",
           "CPU: n ms [min-max]", "POV ms median [min-max]", "MP/GPU", "CPU/GPU", "POV/GPU", "tree/GPU",
           "GPU error vs CPU", "tree error", "note");
}

static void print_row(scene_id id, int size, const case_run *run)
{
    char cell[CONTESTANTS][64], pov_text[64] = "-", pov_ratio[16] = "-", ratio[3][16], error[128], tree[32],
        note[64] = "";
    for (int i = 0; i < CONTESTANTS; i++)
        bench_contestant_text(&run->c[i], cell[i], sizeof cell[i]);
    if (run->pov.ran) {
        snprintf(pov_text, sizeof pov_text, "%7.1f [%.1f-%.1f]", run->pov.times.median, run->pov.times.min,
                 run->pov.times.max);
        snprintf(pov_ratio, sizeof pov_ratio, "%.2f", run->pov.times.median / run->c[FUSED].times.median);
    }
    const int over[3] = {MULTIPASS, CPU, TREE};
    for (int r = 0; r < 3; r++)
        snprintf(ratio[r], sizeof ratio[r], "%.2f", bench_ratio(&run->c[over[r]], &run->c[FUSED]));
    if (run->gpu[TREE].stats.fallback_pixels > 0)
        snprintf(note, sizeof note, "tree fallback %llu px", (unsigned long long)run->gpu[TREE].stats.fallback_pixels);
    printf(TABLE_FORMAT("d"), scenes_name(id), size, cell[FUSED], cell[MULTIPASS], cell[TREE], cell[CPU], pov_text,
           ratio[0], ratio[1], pov_ratio, ratio[2], bench_error_text(&run->error[FUSED], error, sizeof error),
           bench_error_brief(&run->error[TREE], tree, sizeof tree), note);
    /* The GL work of each plan's last timed frame, beside its time (the cached frame: no uploads). */
    for (int p = 0; p < PLANS; p++) {
        char work[160];
        printf("  GL work per frame, %-10s %s\n", contestant_names[p],
               bench_work_text(&run->gpu[p].stats.gl_work, size, size, work, sizeof work));
    }
    fflush(stdout);
}

#define CSV_HEADER                                                                                                 \
    "scene,size,gpu_median_ms,gpu_min_ms,gpu_max_ms,multipass_median_ms,multipass_min_ms,multipass_max_ms,"       \
    "cpu_median_ms,cpu_min_ms,cpu_max_ms,pov_median_ms,pov_min_ms,pov_max_ms,cpu_over_gpu,pov_over_gpu,"          \
    "multipass_over_gpu," BENCH_ERROR_CSV_HEADER ",pov_startup_median_ms,pov_psnr_db,pov_mean_abs,tree_median_ms," \
    "tree_min_ms,tree_max_ms,tree_over_gpu,tree_fallback_pixels,gpu_runs,multipass_runs,tree_runs,cpu_runs,"      \
    BENCH_ERROR_CSV_NAMED("multipass_") "," BENCH_ERROR_CSV_NAMED("tree_")

/* The CSV row: the columns the table had before the tree plan (the fused plan's error unprefixed), then
 * the new ones; empty POV-Ray fields where it did not run. */
static void write_row(FILE *csv, scene_id id, int size, const case_run *run)
{
    const bench_times *g = &run->c[FUSED].times, *m = &run->c[MULTIPASS].times, *c = &run->c[CPU].times,
                      *t = &run->c[TREE].times, *p = &run->pov.times;
    fprintf(csv, "%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,", scenes_name(id), size, g->median, g->min,
            g->max, m->median, m->min, m->max, c->median, c->min, c->max);
    if (run->pov.ran)
        fprintf(csv, "%.1f,%.1f,%.1f,", p->median, p->min, p->max);
    else
        fputs(",,,", csv);
    fprintf(csv, "%.3f,", bench_ratio(&run->c[CPU], &run->c[FUSED]));
    if (run->pov.ran)
        fprintf(csv, "%.3f", p->median / g->median);
    fprintf(csv, ",%.3f,", bench_ratio(&run->c[MULTIPASS], &run->c[FUSED]));
    bench_error_csv(csv, &run->error[FUSED]);
    if (run->pov.ran)
        fprintf(csv, ",%.1f,%.2f,%.3f,", run->pov.startup.median, run->pov.error.psnr_db, run->pov.error.mean_abs);
    else
        fputs(",,,,", csv);
    fprintf(csv, "%.3f,%.3f,%.3f,%.3f,%llu,%d,%d,%d,%d,", t->median, t->min, t->max,
            bench_ratio(&run->c[TREE], &run->c[FUSED]), (unsigned long long)run->gpu[TREE].stats.fallback_pixels,
            g->runs, m->runs, t->runs, c->runs);
    bench_error_csv(csv, &run->error[MULTIPASS]);
    fputc(',', csv);
    bench_error_csv(csv, &run->error[TREE]);
    fputc('\n', csv);
}

/* POV-Ray's start-up and how close its image is, over the cases it ran. */
typedef struct pov_summary {
    int cases;
    double startup_sum, worst_psnr;
} pov_summary;

static bool run_case(bg_renderer *const renderers[PLANS], bg_scene *scene, scene_id id, int size, int runs,
                     const char *dir, FILE *csv, pov_summary *pov)
{
    char label[96];
    snprintf(label, sizeof label, "paper: %s %dx%d", scenes_name(id), size, size);
    bench_progress("%s: warm-up", label);
    case_run *run = malloc(sizeof *run);
    bool ok = run && case_setup(run, renderers, scene, size) && time_case(run, label, runs);
    if (ok && pov_available())
        ok = time_pov(id, dir, size, runs, &run->images[CPU], &run->pov);
    if (ok) {
        print_row(id, size, run);
        write_row(csv, id, size, run);
        if (run->pov.ran) {
            pov->cases++;
            pov->startup_sum += run->pov.startup.median;
            if (run->pov.error.psnr_db < pov->worst_psnr)
                pov->worst_psnr = run->pov.error.psnr_db;
        }
    } else {
        fprintf(stderr, "%s failed\n", label);
    }
    for (int i = 0; run && i < CONTESTANTS; i++)
        bench_image_free(&run->images[i]);
    free(run);
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const int runs = bench_quick() ? 3 : 7;
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    bg_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    bg_renderer *renderers[PLANS] = {gpu.renderer, bench_gpu_renderer(&gpu, desc), bench_gpu_renderer(&gpu, desc)};
    FILE *csv = renderers[MULTIPASS] && renderers[TREE] ? bench_csv_open(dir, "paper.csv", CSV_HEADER) : NULL;
    int status = !csv;
    pov_summary pov = {0, 0.0, IMAGE_METRICS_PSNR_IDENTICAL};
    if (csv)
        print_header(&gpu, pov_available(), runs);
    const scene_id ids[2] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW};
    const int sizes[2] = {512, 1024};
    for (int s = 0; s < 2 && !status; s++) {
        bg_scene *scene = bench_scene(ids[s], NULL);
        status = !scene;
        for (int z = 0; z < 2 && !status; z++)
            status = !run_case(renderers, scene, ids[s], sizes[z], runs, dir, csv, &pov);
        bg_scene_destroy(scene);
    }
    if (!status && pov.cases > 0)
        printf("POV-Ray times are whole processes; a 1x1 render of the same file (start-up and parsing) took\n"
               "%.0f ms (median over every case). POV-Ray's image against our CPU reference: PSNR %.1f dB at worst, the\n"
               "same geometry, camera, texture and lights with its own shading model (a diffuse fit to Schlick's),\n"
               "so it shows the scenes match, not an accuracy.\n",
               pov.startup_sum / pov.cases, pov.worst_psnr);
    if (csv)
        fclose(csv);
    bg_renderer_destroy(renderers[MULTIPASS]);
    bg_renderer_destroy(renderers[TREE]);
    bench_gpu_close(&gpu);
    return status;
}
