/* Triangle-count scaling: a heightfield terrain of 10^3 to 10^6 triangles (examples/scenes/meshes.h)
 * seen from above at an angle, lit by two point lights with shadows, no bounces. For each point:
 * the time from bg_scene_add_mesh to the end of the first commit (the copy of the arrays and the
 * mesh's tree, which the add builds), the bytes the scene holds afterwards (counted through its
 * allocator), and the frame times of the CPU reference, the GPU renderer (BG_PLAN_AUTO, which takes
 * the tree plan, and the multipass) and, where Embree is
 * installed, the Embree peer (bench/lib/embree_peer.h: Embree's own triangles, the reference's
 * shading), with the peer's BVH build time (its rtcCommitScene calls) and memory.
 *
 * The CPU reference renders first: its image is the one the others are compared with. After one
 * warm-up frame each, the contestants are timed in interleaved rounds (Embree, GPU, CPU), so that a
 * shared machine's drift falls on all alike and each ratio is the median of its per-round ratios.
 * The CPU reference and the peer both use every online core.
 *
 * Usage: bench_mesh [out_dir]   (default bench/out; QUICK=1 for 256x256, fewer runs and points)
 * Writes out_dir/mesh_scaling.csv. Built with the peer only where Embree is (BENCH_EMBREE, Makefile). */
#include <stdlib.h>
#include <string.h>

#include "../tests/util_alloc.h"
#include "lib/bench_measure.h"
#include "scenes/meshes.h"
#ifdef BENCH_EMBREE
#include "lib/embree_peer.h"
#else
typedef struct embree_peer embree_peer; /* never made without Embree */
#endif

/* Builds timed per point, ours and the peer's: the median is reported. The peer's first build in a
 * process also starts Embree's threads and a build on a shared machine can be slowed by a neighbour,
 * so one build alone says little. */
#define BUILD_RUNS 3

/* Grid sides n whose 2 n^2 triangles come closest to 10^3 .. 10^6. */
static const int full_n[] = {22, 71, 224, 707};
static const int quick_n[] = {22, 71, 224};
#define MAX_POINTS 4

/* The targets the summary checks (docs/benchmarks.md, "Triangle meshes"). */
#define TARGET_SCALING 2.5      /* time(10^6 triangles) / time(10^4) at most */
#define TARGET_GPU_OVER_EMBREE 0.7
#define TARGET_BUILD_MS 1500.0  /* a BVH over 10^6 triangles */

/* The contestants, in round order. */
enum { PEER, GPU, MULTIPASS, CPU, CONTESTANTS };
static const char *const contestant_names[CONTESTANTS] = {"Embree", "GPU", "multipass", "CPU reference"};

/* ---- a point's scene ---- */

/* The terrain under a camera looking down at 35 degrees, a white diffuse material, two lights. */
static bg_status build(bg_scene *scene, const mesh *terrain)
{
    uint32_t mat = 0, obj = 0, light = 0;
    bg_material m = bg_material_init();
    bg_status st = bg_scene_add_material(scene, &m, &mat);
    bg_mesh_desc d = bg_mesh_desc_init(mat);
    d.positions = terrain->positions;
    d.vertex_count = terrain->vertex_count;
    d.indices = terrain->indices;
    d.triangle_count = terrain->triangle_count;
    if (st == BG_OK)
        st = bg_scene_add_mesh(scene, &d, &obj);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(1.5, 2.0, 1.0);
    l.intensity = 0.7;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &l, &light);
    l.position = bg_vec3_make(-2.0, 1.5, 0.5);
    l.intensity = 0.5;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &l, &light);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0.0, 1.6, 2.3);
    cam.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    cam.fov_y_degrees = 40.0;
    if (st == BG_OK)
        st = bg_scene_set_camera(scene, &cam);
    return st;
}

/* One point: its scene and renderers, its contestants (in the series' list), what was measured. */
typedef struct point {
    int n;
    uint32_t triangles;
    double build_ms;    /* add (validation, copies, the mesh's tree) and the first commit: median */
    util_alloc_counter bytes; /* of the scene rendered (the last one built) */
    double peer_build_ms, peer_commit_ms; /* medians */
    size_t peer_bytes;  /* held by Embree after its build */
    bg_scene *scene;
    bg_renderer *renderer, *multipass; /* BG_PLAN_AUTO (the tree plan) and BG_PLAN_MULTIPASS */
    embree_peer *peer;
    bench_contestant *c; /* CONTESTANTS of them, in the series' list */
    bg_image images[CONTESTANTS]; /* images[CPU] is the reference */
    bench_gpu_job gpu, paper;
    bench_cpu_job cpu;
#ifdef BENCH_EMBREE
    embree_peer_job peer_frame;
#endif
    bench_error error[CONTESTANTS]; /* error[CPU] unused */
    char note[200];                 /* why a contestant did not run */
} point;

/* Every point, and one list of every contestant of every point: the rounds run over all of them,
 * so that a ratio between two points (the scaling targets) is measured side by side too. */
typedef struct series {
    int count;
    point pts[MAX_POINTS];
    bench_contestant list[MAX_POINTS * CONTESTANTS];
} series;

static void note(point *p, const char *format, const char *text)
{
    size_t used = strlen(p->note);
    snprintf(p->note + used, sizeof p->note - used, format, used ? "; " : "", text);
}

/* A new scene of the terrain, counted through util_alloc; the time from add to commit in *ms. */
static bg_scene *scene_of(const mesh *terrain, util_alloc_counter *bytes, double *ms)
{
    *bytes = (util_alloc_counter)UTIL_ALLOC_COUNTER;
    bg_scene_desc sd = {0};
    sd.allocator.alloc = util_counted_alloc;
    sd.allocator.realloc = util_counted_realloc;
    sd.allocator.free = util_counted_free;
    sd.allocator.user = bytes;
    bg_scene *scene = NULL;
    bg_status st = bg_scene_create(&sd, &scene);
    double t0 = bench_now_ms();
    if (st == BG_OK)
        st = build(scene, terrain);
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    *ms = bench_now_ms() - t0;
    if (st != BG_OK) {
        fprintf(stderr, "bench_mesh: %u triangles: %s\n", terrain->triangle_count,
                scene ? bg_scene_error_message(scene) : "no scene");
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

/* The terrain's scene, built BUILD_RUNS times (the last one is kept). */
static bool build_scene(point *p)
{
    char why[256] = "";
    mesh terrain = {0};
    mesh_heightfield_desc hd = {0};
    hd.n = p->n;
    if (mesh_heightfield(&hd, &terrain, why, sizeof why) != BG_OK) {
        fprintf(stderr, "bench_mesh: terrain n = %d: %s\n", p->n, why);
        return false;
    }
    p->triangles = terrain.triangle_count;
    double build_ms[BUILD_RUNS];
    for (int r = 0; r < BUILD_RUNS; r++) {
        bg_scene_destroy(p->scene); /* counted by p->bytes before scene_of resets it */
        p->scene = scene_of(&terrain, &p->bytes, &build_ms[r]);
        if (!p->scene)
            break;
    }
    mesh_free(&terrain); /* the scene holds its own copy */
    if (p->scene)
        p->build_ms = bench_times_of(build_ms, BUILD_RUNS).median;
    return p->scene != NULL;
}

#ifdef BENCH_EMBREE
/* The point's own peer (each point keeps its BVH through the rounds), built BUILD_RUNS times. */
static bool build_peer(point *p)
{
    char message[512];
    p->peer = embree_peer_create(NULL, message, sizeof message);
    double build_ms[BUILD_RUNS], commit_ms[BUILD_RUNS];
    for (int r = 0; p->peer && r < BUILD_RUNS; r++) {
        if (!embree_peer_build(p->peer, p->scene, message, sizeof message)) {
            fprintf(stderr, "%s\n", message);
            return false;
        }
        build_ms[r] = embree_peer_build_ms(p->peer);
        commit_ms[r] = embree_peer_commit_ms(p->peer);
    }
    if (!p->peer) {
        fprintf(stderr, "%s\n", message);
        return false;
    }
    p->peer_build_ms = bench_times_of(build_ms, BUILD_RUNS).median;
    p->peer_commit_ms = bench_times_of(commit_ms, BUILD_RUNS).median;
    p->peer_bytes = embree_peer_bytes(p->peer);
    return true;
}
#endif

/* A point's scene, the reference frame, the peer's BVH and every other warm-up frame; the longest
 * warm-up in *slowest. */
static bool prepare(point *p, bench_gpu *gpu, int side, double *slowest)
{
    if (!build_scene(p))
        return false;
    bench_progress("mesh: %u triangles: reference, BVH, warm-up", p->triangles);
    bg_render_settings set = bg_render_settings_init();
    set.max_depth = 0;
    if (gpu) {
        bg_renderer_desc rd = {0};
        p->renderer = bench_gpu_renderer(gpu, rd); /* one per point and plan: each keeps its caches */
        p->multipass = bench_gpu_renderer(gpu, rd);
    }
    p->gpu.renderer = p->renderer;
    p->gpu.scene = p->scene;
    p->gpu.settings = set;
    p->paper = p->gpu;
    p->paper.renderer = p->multipass;
    p->paper.settings.gpu_plan = BG_PLAN_MULTIPASS;
    p->cpu = (bench_cpu_job){p->scene, set};
    bench_frame_fn frames[CONTESTANTS] = {NULL, bench_gpu_frame, bench_gpu_frame, bench_cpu_frame};
    void *jobs[CONTESTANTS] = {NULL, &p->gpu, &p->paper, &p->cpu};
#ifdef BENCH_EMBREE
    if (!build_peer(p))
        return false;
    p->peer_frame = (embree_peer_job){p->peer, set};
    frames[PEER] = embree_peer_frame;
    jobs[PEER] = &p->peer_frame;
#endif
    for (int i = 0; i < CONTESTANTS; i++) {
        if (!bench_image_alloc(&p->images[i], side, side, BG_PIXEL_RGBA8))
            return false;
        p->c[i] = (bench_contestant){.name = contestant_names[i], .frame = frames[i], .user = jobs[i],
                                     .image = &p->images[i]};
    }
    if (!bench_warm_up(&p->c[CPU]))
        return false;
    p->c[CPU].rounds = 1; /* rounds > 0: takes part (the count is set once every point is ready) */
#ifdef BENCH_EMBREE
    if (!bench_warm_up(&p->c[PEER]))
        return false;
    p->c[PEER].rounds = 1;
#else
    note(p, "%sEmbree not built (%s)", "libembree-dev not installed");
#endif
    if (p->renderer && bench_warm_up(&p->c[GPU]))
        p->c[GPU].rounds = 1;
    else
        note(p, "%sGPU not run: %s", p->renderer ? bg_renderer_error_message(p->renderer) : "no GPU context");
    if (p->multipass && bench_warm_up(&p->c[MULTIPASS]))
        p->c[MULTIPASS].rounds = 1;
    else
        note(p, "%smultipass not run: %s", p->multipass ? bg_renderer_error_message(p->multipass) : "no GPU context");
    for (int i = 0; i < CONTESTANTS; i++)
        if (p->c[i].rounds > 0 && p->c[i].warm_ms > *slowest)
            *slowest = p->c[i].warm_ms;
    return true;
}

static void release(point *p)
{
    for (int i = 0; i < CONTESTANTS; i++)
        bench_image_free(&p->images[i]);
#ifdef BENCH_EMBREE
    embree_peer_destroy(p->peer);
#endif
    bg_renderer_destroy(p->renderer);
    bg_renderer_destroy(p->multipass);
    bg_scene_destroy(p->scene);
}

/* Every point prepared, then the rounds over all of them (as many for every contestant: those the
 * slowest warm-up gives), then the errors. False when a point could not be prepared or a frame failed;
 * s->count says how many points are measured. */
static bool run_series(series *s, bench_gpu *gpu, const int *ns, int count, int side, int runs)
{
    double slowest = 0.0;
    s->count = 0;
    for (int i = 0; i < count; i++) {
        point *p = &s->pts[i];
        p->n = ns[i];
        p->c = &s->list[i * CONTESTANTS];
        s->count = i + 1;
        if (!prepare(p, gpu, side, &slowest))
            return false;
    }
    int rounds = bench_rounds_after(slowest, runs);
    for (int i = 0; i < s->count * CONTESTANTS; i++)
        if (s->list[i].rounds > 0)
            s->list[i].rounds = rounds;
    if (!bench_interleave(s->list, s->count * CONTESTANTS, "mesh: every point"))
        return false;
    for (int j = 0; j < s->count; j++)
        for (int i = 0; i < CONTESTANTS; i++)
            if (i != CPU && s->pts[j].c[i].rounds > 0)
                s->pts[j].error[i] = bench_error_of(&s->pts[j].images[CPU], &s->pts[j].images[i]);
    return true;
}

/* ---- output ---- */

#define TABLE_FORMAT(x) "%10" x " %9s %8s %9s %8s | %-24s | %-24s | %-24s | %-24s | %7s %7s %7s %7s | %-16s | %-16s | %-16s %s\n"

static char *ratio_text(double ratio, char *buffer, size_t size)
{
    if (ratio > 0.0)
        snprintf(buffer, size, "%.2f", ratio);
    else
        snprintf(buffer, size, "-");
    return buffer;
}

static char *error_text(const point *p, int i, char *buffer, size_t size)
{
    if (p->c[i].rounds > 0)
        return bench_error_brief(&p->error[i], buffer, size);
    snprintf(buffer, size, "-");
    return buffer;
}

static void print_header(const bench_gpu *gpu, const embree_peer *peer, int side, int runs)
{
    bench_print_setup(stdout, gpu, runs);
#ifdef BENCH_EMBREE
    char how[128];
    if (peer)
        printf("Embree peer: %s (the same count as the CPU reference), over 8x8 tiles; meshes as Embree\n"
               "triangles (robust, build quality medium), the reference's double shading\n",
               embree_peer_describe(peer, how, sizeof how));
#else
    (void)peer;
    printf("Embree peer: not built (libembree-dev not installed)\n");
#endif
    printf("\nTerrain meshes, %dx%d, 2 point lights with shadows, no bounces: the Embree peer, the GPU renderer\n"
           "(BG_PLAN_AUTO: the tree plan; and BG_PLAN_MULTIPASS) and the CPU reference, every point in the same\n"
           "interleaved rounds (a round: one frame\n"
           "of each contestant of each point). Build, median of %d: ours (add + commit,\n"
           "one thread), Embree's (its rtcCommitScene calls, on the peer's threads); MB: held after the build.\n"
           "Cells: n rounds, ms median [min-max]; ratios: medians of per-round ratios; errors against the CPU\n"
           "reference.\n",
           side, side, BUILD_RUNS);
    printf(TABLE_FORMAT("s"), "triangles", "build ms", "scene MB", "Emb bld", "Emb MB", "Embree: n ms [min-max]",
           "GPU: n ms [min-max]", "multipass: n ms", "CPU: n ms [min-max]", "GPU/CPU", "GPU/Emb", "Emb/CPU", "MP/GPU",
           "GPU error", "multipass error", "Embree error", "");
}

static void print_row(const point *p)
{
    char cell[CONTESTANTS][64], ratio[4][16], err[3][32], ebuild[16], ebytes[16], build[16], mb[16];
    for (int i = 0; i < CONTESTANTS; i++)
        bench_contestant_text(&p->c[i], cell[i], sizeof cell[i]);
    snprintf(build, sizeof build, "%.1f", p->build_ms);
    snprintf(mb, sizeof mb, "%.1f", p->bytes.live_bytes / 1048576.0);
    bool peer = p->c[PEER].rounds > 0;
    snprintf(ebuild, sizeof ebuild, peer ? "%.1f" : "-", p->peer_commit_ms);
    snprintf(ebytes, sizeof ebytes, peer ? "%.1f" : "-", p->peer_bytes / 1048576.0);
    printf(TABLE_FORMAT("u"), p->triangles, build, mb, ebuild, ebytes, cell[PEER], cell[GPU], cell[MULTIPASS],
           cell[CPU], ratio_text(bench_ratio(&p->c[GPU], &p->c[CPU]), ratio[0], 16),
           ratio_text(bench_ratio(&p->c[GPU], &p->c[PEER]), ratio[1], 16),
           ratio_text(bench_ratio(&p->c[PEER], &p->c[CPU]), ratio[2], 16),
           ratio_text(bench_ratio(&p->c[MULTIPASS], &p->c[GPU]), ratio[3], 16), error_text(p, GPU, err[0], 32),
           error_text(p, MULTIPASS, err[2], 32), error_text(p, PEER, err[1], 32), p->note);
    fflush(stdout);
}

#define CSV_HEADER                                                                                          \
    "triangles,build_ms,scene_bytes,cpu_median_ms,cpu_min_ms,cpu_max_ms,gpu_median_ms,rounds,gpu_min_ms,"   \
    "gpu_max_ms,embree_median_ms,embree_min_ms,embree_max_ms,embree_build_ms,embree_commit_ms,"             \
    "embree_bytes,gpu_over_cpu,gpu_over_embree,embree_over_cpu," BENCH_ERROR_CSV_NAMED("gpu_") ","          \
    BENCH_ERROR_CSV_NAMED("embree_") ",multipass_median_ms,multipass_min_ms,multipass_max_ms,"              \
    "multipass_over_gpu," BENCH_ERROR_CSV_NAMED("multipass_")

/* A contestant that did not run has -1 times and empty error fields. */
static void write_row(FILE *csv, const point *p)
{
    const bench_times *c = &p->c[CPU].times, *g = &p->c[GPU].times, *e = &p->c[PEER].times;
    bool gpu = p->c[GPU].rounds > 0, peer = p->c[PEER].rounds > 0;
    fprintf(csv, "%u,%.3f,%zu,%.3f,%.3f,%.3f,%.3f,%d,", p->triangles, p->build_ms, p->bytes.live_bytes, c->median, c->min,
            c->max, gpu ? g->median : -1.0, p->c[CPU].rounds);
    fprintf(csv, "%.3f,%.3f,%.3f,%.3f,%.3f,", gpu ? g->min : -1.0, gpu ? g->max : -1.0, peer ? e->median : -1.0,
            peer ? e->min : -1.0, peer ? e->max : -1.0);
    fprintf(csv, "%.3f,%.3f,%zu,%.4f,%.4f,%.4f,", peer ? p->peer_build_ms : -1.0, peer ? p->peer_commit_ms : -1.0,
            p->peer_bytes, bench_ratio(&p->c[GPU], &p->c[CPU]), bench_ratio(&p->c[GPU], &p->c[PEER]),
            bench_ratio(&p->c[PEER], &p->c[CPU]));
    if (gpu)
        bench_error_csv(csv, &p->error[GPU]);
    else
        fputs(",,,,", csv);
    fputc(',', csv);
    if (peer)
        bench_error_csv(csv, &p->error[PEER]);
    else
        fputs(",,,,", csv);
    const bench_times *m = &p->c[MULTIPASS].times;
    bool multi = p->c[MULTIPASS].rounds > 0;
    fprintf(csv, ",%.3f,%.3f,%.3f,%.4f,", multi ? m->median : -1.0, multi ? m->min : -1.0, multi ? m->max : -1.0,
            bench_ratio(&p->c[MULTIPASS], &p->c[GPU]));
    if (multi)
        bench_error_csv(csv, &p->error[MULTIPASS]);
    else
        fputs(",,,,", csv);
    fputc('\n', csv);
}

/* The targets, measured: the scaling of each contestant from the second point to the last (the
 * median of the per-round ratios), the GPU against the peer at the last, the BVH builds of the last. */
static void print_summary(const point *pts, int done)
{
    const point *last = &pts[done - 1], *second = &pts[1];
    printf("\ntime(%u triangles) / time(%u triangles), target <= %.1f:", last->triangles, second->triangles,
           TARGET_SCALING);
    for (int i = 0; i < CONTESTANTS; i++)
        if (last->c[i].rounds > 0 && second->c[i].rounds > 0)
            printf(" %s %.2f%s", contestant_names[i], bench_ratio(&last->c[i], &second->c[i]),
                   i + 1 < CONTESTANTS ? "," : "");
    printf("\n");
    double ratio = bench_ratio(&last->c[GPU], &last->c[PEER]);
    char err[2][96];
    if (ratio > 0.0)
        printf("GPU / Embree at %u triangles: %.2f (target <= %.1f: %s), at errors GPU %s, Embree %s\n",
               last->triangles, ratio, TARGET_GPU_OVER_EMBREE, ratio <= TARGET_GPU_OVER_EMBREE ? "met" : "not met",
               bench_error_text(&last->error[GPU], err[0], sizeof err[0]),
               bench_error_text(&last->error[PEER], err[1], sizeof err[1]));
    printf("BVH build of %u triangles, target < %.1f s: ours %.2f s (%s)", last->triangles, TARGET_BUILD_MS / 1000.0,
           last->build_ms / 1000.0, last->build_ms < TARGET_BUILD_MS ? "met" : "not met");
    if (last->c[PEER].rounds > 0)
        printf(", Embree %.2f s (rtcCommitScene; %.2f s with the vertex copy)", last->peer_commit_ms / 1000.0,
               last->peer_build_ms / 1000.0);
    printf("\n");
}

int main(int argc, char **argv)
{
    const char *out_dir = bench_out_dir(argc, argv);
    if (!out_dir)
        return 2;
    bool quick = bench_quick();
    int side = quick ? 256 : 1024, runs = quick ? 3 : 5;
    const int *ns = quick ? quick_n : full_n;
    int count = quick ? (int)(sizeof quick_n / sizeof quick_n[0]) : (int)(sizeof full_n / sizeof full_n[0]);

    bench_gpu gpu;
    bool have_gpu = bench_gpu_open(&gpu);
    FILE *csv = bench_csv_open(out_dir, "mesh_scaling.csv", CSV_HEADER);
    series *s = calloc(1, sizeof *s);
    bool ok = csv && s && run_series(s, have_gpu ? &gpu : NULL, ns, count, side, runs);
    if (ok) {
        print_header(have_gpu ? &gpu : NULL, s->pts[0].peer, side, runs);
        for (int i = 0; i < s->count; i++) {
            print_row(&s->pts[i]);
            write_row(csv, &s->pts[i]);
        }
        if (s->count >= 2)
            print_summary(s->pts, s->count);
    }
    if (csv)
        fclose(csv);
    for (int i = 0; s && i < s->count; i++)
        release(&s->pts[i]);
    free(s);
    if (have_gpu)
        bench_gpu_close(&gpu);
    return ok ? 0 : 1;
}
