/* The GPU path against an Embree peer (bench/lib/embree_peer.h; Embree 3 or 4), its own multipass plan
 * and the CPU reference: the same scenes, camera, lights and BRDF, so the table says where the GPU path
 * stands.
 *
 * Usage: bench_embree [out_dir]   (default bench/out; QUICK=1 for fewer runs)
 * BENCH_CASES (bench/lib/bench_select.h) picks cases by the table's scene column: paper_earth,
 * paper_earth_shadow, glass, many_spheres64, many_spheres1024, each also as name@512 or name@1024.
 * Per case: the CPU reference renders first (the image every other is compared with); the peer builds
 * its BVH (timed on its own, not part of a frame); after one warm-up frame each, four contestants are
 * timed in interleaved rounds, in this order: one peer frame, one GPU frame (BG_PLAN_AUTO), one
 * multipass frame (BG_PLAN_MULTIPASS, on a renderer of its own so that each plan keeps its caches), one
 * CPU reference frame. The drift of a shared machine then falls on all alike, and each ratio is the
 * median of its per-round ratios. Rounds: a case whose GPU warm-up takes over BENCH_SLOW_MS gets
 * BENCH_SLOW_RUNS, over VERY_SLOW_MS one (every contestant); the multipass follows its own rules
 * (MULTIPASS_MAX_OBJECTS, MULTIPASS_SLOW_MS). Writes out_dir/embree.csv (the cases run, only).
 * Built only where Embree is installed (Makefile, bench section). */
#include <stdlib.h>
#include <string.h>

#include "lib/bench_measure.h"
#include "lib/bench_select.h"
#include "lib/embree_internal.h" /* the peer's Embree header (3 or 4), for RTC_VERSION_* */
#include "lib/embree_peer.h"
#include "scenes/scenes.h"

/* A case whose GPU warm-up takes longer than this gets one round: a median of more would multiply the
 * whole benchmark's time for little. */
#define VERY_SLOW_MS 60000.0
/* The multipass draws its intersection and shadow passes per object batch and per ray set, so on
 * llvmpipe many_spheres costs it about 20 s a frame at 64 spheres and minutes at 1024: it is not run on
 * more spheres than MULTIPASS_MAX_OBJECTS, nor on that many at more pixels than MULTIPASS_MAX_SIDE
 * squared (a minute's warm-up and a minute's round at 1024x1024, for a row the 512 one already gives),
 * and a multipass warm-up over MULTIPASS_SLOW_MS gets one round. */
#define MULTIPASS_MAX_OBJECTS 64
#define MULTIPASS_MAX_SIDE 512
#define MULTIPASS_SLOW_MS 10000.0

typedef struct bench_case {
    scene_id id;
    int size;
    int spheres; /* SCENE_MANY_SPHERES only; 0 otherwise */
} bench_case;

static const bench_case cases[] = {
    {SCENE_PAPER_EARTH, 512, 0},        {SCENE_PAPER_EARTH, 1024, 0}, {SCENE_PAPER_EARTH_SHADOW, 512, 0},
    {SCENE_PAPER_EARTH_SHADOW, 1024, 0}, {SCENE_GLASS, 512, 0},         {SCENE_GLASS, 1024, 0},
    {SCENE_MANY_SPHERES, 512, 64},      {SCENE_MANY_SPHERES, 1024, 64}, {SCENE_MANY_SPHERES, 512, 1024},
    {SCENE_MANY_SPHERES, 1024, 1024},
};
#define CASE_COUNT (int)(sizeof cases / sizeof cases[0])

/* The contestants, in round order. */
enum { PEER, GPU, MULTIPASS, CPU, CONTESTANTS };
static const char *const contestant_names[CONTESTANTS] = {"Embree", "GPU", "multipass", "CPU reference"};


/* The two GPU renderers: one per plan. */
typedef struct gpu_pair {
    bg_renderer *automatic, *multipass;
} gpu_pair;

/* One case: its contestants with their state and images, and what the rounds measured. */
typedef struct case_run {
    bench_contestant c[CONTESTANTS];
    bg_image images[CONTESTANTS]; /* images[CPU] is the reference */
    embree_peer_job peer;
    bench_gpu_job gpu, multipass;
    bench_cpu_job cpu;
    double build_ms;
    bench_error error[CONTESTANTS]; /* against the reference; error[CPU] unused */
    char note[128];                 /* what the row should say besides its numbers */
} case_run;

static bool case_setup(case_run *run, embree_peer *peer, const gpu_pair *gpu, bg_scene *scene, int size)
{
    memset(run, 0, sizeof *run);
    bg_render_settings settings = bg_render_settings_init();
    run->peer = (embree_peer_job){peer, settings};
    run->gpu.renderer = gpu->automatic;
    run->multipass.renderer = gpu->multipass;
    run->gpu.scene = run->multipass.scene = scene;
    run->gpu.settings = run->multipass.settings = settings;
    run->multipass.settings.gpu_plan = BG_PLAN_MULTIPASS;
    run->cpu = (bench_cpu_job){scene, settings};
    const bench_frame_fn frames[CONTESTANTS] = {embree_peer_frame, bench_gpu_frame, bench_gpu_frame, bench_cpu_frame};
    void *const jobs[CONTESTANTS] = {&run->peer, &run->gpu, &run->multipass, &run->cpu};
    bool ok = true;
    for (int i = 0; i < CONTESTANTS; i++) {
        ok = ok && bench_image_alloc(&run->images[i], size, size, BG_PIXEL_RGBA8);
        run->c[i] = (bench_contestant){.name = contestant_names[i], .frame = frames[i], .user = jobs[i],
                                       .image = &run->images[i]};
    }
    return ok;
}

/* Whether the multipass runs a case at all (MULTIPASS_MAX_OBJECTS, MULTIPASS_MAX_SIDE). */
static bool multipass_runs(const bench_case *c)
{
    return c->spheres <= MULTIPASS_MAX_OBJECTS && (c->spheres == 0 || c->size <= MULTIPASS_MAX_SIDE);
}

/* The multipass's rounds: none on many objects, one after a slow warm-up, else the case's. */
static void choose_multipass_rounds(case_run *run, const bench_case *c, int case_rounds, int runs)
{
    bench_contestant *mp = &run->c[MULTIPASS];
    if (c->spheres > MULTIPASS_MAX_OBJECTS) {
        snprintf(run->note, sizeof run->note, "MP not run: minutes per frame (over %d spheres)",
                 MULTIPASS_MAX_OBJECTS);
        return;
    }
    if (!multipass_runs(c)) {
        snprintf(run->note, sizeof run->note, "MP not run: spheres over %dx%d (its %d row: 1 round)",
                 MULTIPASS_MAX_SIDE, MULTIPASS_MAX_SIDE, MULTIPASS_MAX_SIDE);
        return;
    }
    int own = bench_rounds_after(mp->warm_ms, runs);
    mp->rounds = own < case_rounds ? own : case_rounds;
    if (mp->warm_ms > MULTIPASS_SLOW_MS) {
        mp->rounds = 1;
        snprintf(run->note, sizeof run->note, "MP 1 round: warm-up %.1f s > %.0f s", mp->warm_ms / 1000.0,
                 MULTIPASS_SLOW_MS / 1000.0);
    }
}

/* The reference, the BVH and every warm-up frame (the multipass's first: it decides its own rounds),
 * then the rounds each contestant gets. */
static bool prepare(case_run *run, const bench_case *c, bg_scene *scene, int runs)
{
    char message[512];
    if (!bench_warm_up(&run->c[CPU]))
        return false;
    if (!embree_peer_build(run->peer.peer, scene, message, sizeof message)) {
        fprintf(stderr, "%s\n", message);
        return false;
    }
    run->build_ms = embree_peer_build_ms(run->peer.peer);
    if (multipass_runs(c) && !bench_warm_up(&run->c[MULTIPASS]))
        return false;
    if (!bench_warm_up(&run->c[PEER]) || !bench_warm_up(&run->c[GPU]))
        return false;
    double gpu_ms = run->c[GPU].warm_ms;
    int rounds = gpu_ms > VERY_SLOW_MS ? 1 : bench_rounds_after(gpu_ms, runs);
    run->c[PEER].rounds = run->c[GPU].rounds = run->c[CPU].rounds = rounds;
    choose_multipass_rounds(run, c, rounds, runs);
    return true;
}

static void measure_errors(case_run *run)
{
    for (int i = 0; i < CONTESTANTS; i++)
        if (i != CPU && run->c[i].rounds > 0)
            run->error[i] = bench_error_of(&run->images[CPU], &run->images[i]);
}

/* Appends what the GPU plans did beyond their numbers to the row's note. */
static void note_gpu_oddities(case_run *run)
{
    size_t used = strlen(run->note);
    if (run->gpu.stats.fallback_pixels > 0)
        used += (size_t)snprintf(run->note + used, sizeof run->note - used, "%stree fallback %llu px",
                                 used ? "; " : "", (unsigned long long)run->gpu.stats.fallback_pixels);
    const bench_gpu_job *jobs[2] = {&run->gpu, &run->multipass};
    for (int j = 0; j < 2 && used < sizeof run->note; j++)
        if (jobs[j]->recompiled_frames > 0)
            used += (size_t)snprintf(run->note + used, sizeof run->note - used, "%s%s compiled in %d timed frames",
                                     used ? "; " : "", j ? "MP" : "GPU", jobs[j]->recompiled_frames);
}

static void case_label(const bench_case *c, char *buffer, size_t size)
{
    if (c->spheres > 0)
        snprintf(buffer, size, "%s%d", scenes_name(c->id), c->spheres);
    else
        snprintf(buffer, size, "%s", scenes_name(c->id));
}

/* The table's columns: the header and every row share these widths. */
#define TABLE_FORMAT(x) \
    "%-19s %5" x " %-10s | %-28s | %-28s | %-28s | %-28s | %7s %7s %7s | %7s | %-16s | %-16s | %-16s | %s\n"

/* A ratio for the table, "-" where the rounds shared none. */
static char *ratio_text(double ratio, char *buffer, size_t size)
{
    if (ratio > 0.0)
        snprintf(buffer, size, "%.2f", ratio);
    else
        snprintf(buffer, size, "-");
    return buffer;
}

static void print_row(const bench_case *c, const case_run *run)
{
    char label[64], cell[CONTESTANTS][64], ratio[3][16], build[16], error[3][32];
    case_label(c, label, sizeof label);
    for (int i = 0; i < CONTESTANTS; i++)
        bench_contestant_text(&run->c[i], cell[i], sizeof cell[i]);
    const int shown[3] = {GPU, MULTIPASS, PEER};
    for (int e = 0; e < 3; e++) {
        if (run->c[shown[e]].rounds > 0)
            bench_error_brief(&run->error[shown[e]], error[e], sizeof error[e]);
        else
            snprintf(error[e], sizeof error[e], "-");
    }
    snprintf(build, sizeof build, "%.1f", run->build_ms);
    printf(TABLE_FORMAT("d"), label, c->size, bench_plan_name(run->gpu.stats.plan), cell[PEER], cell[GPU],
           cell[MULTIPASS], cell[CPU], ratio_text(bench_ratio(&run->c[GPU], &run->c[PEER]), ratio[0], 16),
           ratio_text(bench_ratio(&run->c[GPU], &run->c[CPU]), ratio[1], 16),
           ratio_text(bench_ratio(&run->c[MULTIPASS], &run->c[GPU]), ratio[2], 16), build, error[0], error[1],
           error[2], run->note);
    fflush(stdout);
}

#define CSV_HEADER                                                                                          \
    "scene,spheres,size,runs,embree_median_ms,embree_min_ms,embree_max_ms,gpu_median_ms,gpu_min_ms,"        \
    "gpu_max_ms,gpu_over_embree,cpu_ref_ms,bvh_build_ms," BENCH_ERROR_CSV_NAMED("embree_") ","               \
    BENCH_ERROR_CSV_NAMED("gpu_") ",plan,gpu_runs,multipass_runs,cpu_runs,multipass_median_ms,"            \
    "multipass_min_ms,multipass_max_ms,cpu_min_ms,cpu_max_ms,gpu_over_cpu,multipass_over_gpu,"             \
    "multipass_warm_ms,fallback_pixels," BENCH_ERROR_CSV_NAMED("multipass_")

/* The CSV row: the columns the two-way comparison had (cpu_ref_ms is now the reference's median), then
 * the new ones; empty fields where the multipass did not run. */
static void write_row(FILE *csv, const bench_case *c, const case_run *run)
{
    const bench_times *e = &run->c[PEER].times, *g = &run->c[GPU].times, *m = &run->c[MULTIPASS].times,
                      *r = &run->c[CPU].times;
    fprintf(csv, "%s,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.4f,%.1f,%.3f,", scenes_name(c->id), c->spheres, c->size,
            e->runs, e->median, e->min, e->max, g->median, g->min, g->max, bench_ratio(&run->c[GPU], &run->c[PEER]),
            r->median, run->build_ms);
    bench_error_csv(csv, &run->error[PEER]);
    fputc(',', csv);
    bench_error_csv(csv, &run->error[GPU]);
    fprintf(csv, ",%s,%d,%d,%d,", bench_plan_name(run->gpu.stats.plan), g->runs, m->runs, r->runs);
    bool mp = m->runs > 0;
    if (mp)
        fprintf(csv, "%.3f,%.3f,%.3f,", m->median, m->min, m->max);
    else
        fputs(",,,", csv);
    fprintf(csv, "%.3f,%.3f,%.4f,", r->min, r->max, bench_ratio(&run->c[GPU], &run->c[CPU]));
    if (mp)
        fprintf(csv, "%.4f,%.1f,", bench_ratio(&run->c[MULTIPASS], &run->c[GPU]), run->c[MULTIPASS].warm_ms);
    else
        fputs(",,", csv);
    fprintf(csv, "%llu,", (unsigned long long)run->gpu.stats.fallback_pixels);
    if (mp)
        bench_error_csv(csv, &run->error[MULTIPASS]);
    else
        fputs(",,,,", csv);
    fputc('\n', csv);
}

static bool run_case(embree_peer *peer, const gpu_pair *gpu, const bench_case *c, int runs, FILE *csv)
{
    scene_params params;
    memset(&params, 0, sizeof params);
    params.spheres = c->spheres;
    bg_scene *scene = bench_scene(c->id, &params);
    if (!scene)
        return false;
    char name[64], label[96];
    case_label(c, name, sizeof name);
    snprintf(label, sizeof label, "embree: %s %dx%d", name, c->size, c->size);
    bench_progress("%s: reference, BVH, warm-up", label);
    case_run *run = malloc(sizeof *run);
    bool ok = run && case_setup(run, peer, gpu, scene, c->size) && prepare(run, c, scene, runs);
    ok = ok && bench_interleave(run->c, CONTESTANTS, label);
    if (ok) {
        measure_errors(run);
        note_gpu_oddities(run);
        print_row(c, run);
        write_row(csv, c, run);
    } else {
        fprintf(stderr, "embree: %s failed\n", label);
    }
    for (int i = 0; run && i < CONTESTANTS; i++)
        bench_image_free(&run->images[i]);
    free(run);
    bg_scene_destroy(scene);
    return ok;
}

static void print_header(const bench_gpu *gpu, const embree_peer *peer, int runs)
{
    char how[128];
    printf("== GPU path against an Embree %d.%d.%d peer, its multipass plan and the CPU reference (same scenes,\n"
           "camera, lights and BRDF), interleaved rounds\n",
           RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    bench_print_setup(stdout, gpu, runs);
    printf("Embree peer: %s over 8x8 tiles; user geometry with the reference's double intersection and\n"
           "shading. Round order: Embree, GPU (BG_PLAN_AUTO; plan: the one it ran), MP (BG_PLAN_MULTIPASS, its own\n"
           "renderer), CPU reference. Cells: n rounds, ms median [min-max]. Ratios: medians of the per-round\n"
           "ratios (GPU/Emb > 1: the peer is faster). Errors against the CPU reference's image; BVH: the peer's\n"
           "build, not in its frames. MP: 1 round when its warm-up exceeds %.0f s, not run over %d spheres\n"
           "(nor on spheres over %dx%d).\n",
           embree_peer_describe(peer, how, sizeof how), MULTIPASS_SLOW_MS / 1000.0, MULTIPASS_MAX_OBJECTS,
           MULTIPASS_MAX_SIDE, MULTIPASS_MAX_SIDE);
    bench_select_print(stdout);
    printf(TABLE_FORMAT("s"), "scene", "size", "plan", "Embree: n ms [min-max]", "GPU: n ms [min-max]",
           "MP: n ms [min-max]", "CPU ref: n ms [min-max]", "GPU/Emb", "GPU/CPU", "MP/GPU", "BVH ms", "GPU error",
           "MP error", "Embree error", "note");
}

/* Which cases BENCH_CASES picks, in selected[]; false (with the program's names on stderr) when it
 * names a case that is not here. Asked before anything opens, so that a typo costs nothing. */
static bool select_cases(bool selected[CASE_COUNT])
{
    char known[512] = "", label[64], last[64] = "";
    size_t used = 0;
    for (int i = 0; i < CASE_COUNT; i++) {
        case_label(&cases[i], label, sizeof label);
        selected[i] = bench_selected(label, cases[i].size);
        /* A scene's sizes are neighbours in cases[]: its name once. */
        if (strcmp(label, last) != 0 && used < sizeof known)
            used += (size_t)snprintf(known + used, sizeof known - used, "%s%s", used ? ", " : "", label);
        snprintf(last, sizeof last, "%s", label);
    }
    return bench_select_check("bench_embree", known);
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const int runs = bench_quick() ? 3 : 7;
    bool selected[CASE_COUNT];
    if (!select_cases(selected))
        return 2;
    char message[512];
    embree_peer *peer = embree_peer_create(NULL, message, sizeof message);
    if (!peer) {
        fprintf(stderr, "%s\n", message);
        return 1;
    }
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu)) {
        embree_peer_destroy(peer);
        return 1;
    }
    bg_renderer_desc desc;
    memset(&desc, 0, sizeof desc);
    gpu_pair pair = {gpu.renderer, bench_gpu_renderer(&gpu, desc)};
    FILE *csv = pair.multipass ? bench_csv_open(dir, "embree.csv", CSV_HEADER) : NULL;
    int status = !csv;
    if (csv) {
        print_header(&gpu, peer, runs);
        for (int i = 0; i < CASE_COUNT && !status; i++)
            if (selected[i])
                status = !run_case(peer, &pair, &cases[i], runs, csv);
        fclose(csv);
    }
    bg_renderer_destroy(pair.multipass);
    bench_gpu_close(&gpu);
    embree_peer_destroy(peer);
    return status;
}
