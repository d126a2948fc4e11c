/* Triangle-count scaling, in two series.
 *
 * The terrain series: a heightfield terrain of 10^3 to 10^6 triangles (examples/scenes/meshes.h)
 * seen from above at an angle, lit by two point lights with shadows, no bounces. For each point:
 * the time from bg_scene_add_mesh to the end of the first commit (the copy of the arrays and the
 * mesh's tree, which the add builds), the bytes the scene holds afterwards (counted through its
 * allocator), and the frame times of the CPU reference, the GPU renderer (BG_PLAN_AUTO, which takes
 * the tree plan, and the multipass) and, where Embree is
 * installed, the Embree peer (bench/lib/embree_peer.h: Embree's own triangles, the reference's
 * shading), with the peer's BVH build time (its rtcCommitScene calls) and memory.
 *
 * The closed-mesh series: a unit icosphere (an icosahedron subdivided in code, mesh_icosphere) of
 * 5120, 81920 and 1310720 triangles, and the 10^6-triangle terrain beside them, each at 512x512 and
 * 1024x1024, under the same two lights: the GPU renderer (BG_PLAN_AUTO) against the Embree peer. A
 * closed mesh is what a ray walks deepest into: every pixel the sphere covers ends on it, and its
 * shadow rays start on it. The CPU reference draws each image once (the one the others are compared
 * with) and the multipass does not run: on meshes it takes the tree plan's time (the terrain table's
 * MP/GPU column), and the two would triple the series' time. The Stanford bunny at its real
 * resolution (69451 triangles) is not here: the only copy a package serves is the 3674-triangle one
 * in tests/data (docs/benchmarks.md).
 *
 * The CPU reference renders first: its image is the one the others are compared with. After one
 * warm-up frame each, the contestants are timed in interleaved rounds (Embree, GPU, then the
 * multipass and CPU where they take part), every point and size of a series in the same rounds, so
 * that a shared machine's drift falls on all alike and each ratio (between contestants, and between
 * points) is the median of its per-round ratios. The CPU reference and the peer both use every online
 * core.
 *
 * Usage: bench_mesh [out_dir]   (default bench/out; QUICK=1 for 256x256, fewer runs and points)
 * BENCH_CASES (bench/lib/bench_select.h) picks: terrain_series (the whole terrain series), and the
 * closed series' points icosphere5k, icosphere82k, icosphere1.3m, terrain1m, each also as
 * name@512 or name@1024.
 * Writes out_dir/mesh_scaling.csv (the terrain series) and out_dir/mesh_closed.csv (the closed
 * series), each only when its series ran. Built with the peer only where Embree is (BENCH_EMBREE,
 * Makefile). */
#include <stdlib.h>
#include <string.h>

#include "../tests/util_alloc.h"
#include "lib/bench_measure.h"
#include "lib/mesh_scene.h"
#include "lib/bench_select.h"
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

/* The meshes a point shows. */
typedef enum shape_kind { TERRAIN, ICOSPHERE } shape_kind;
typedef struct shape {
    shape_kind kind;
    int param;        /* TERRAIN: the grid side n (2 n^2 triangles); ICOSPHERE: the level (20 * 4^level) */
    const char *name; /* the case's name in BENCH_CASES and the closed series' table */
} shape;

/* The terrain series: grid sides n whose 2 n^2 triangles come closest to 10^3 .. 10^6. */
static const shape terrain_full[] = {{TERRAIN, 22, "terrain1k"},
                                     {TERRAIN, 71, "terrain10k"},
                                     {TERRAIN, 224, "terrain100k"},
                                     {TERRAIN, 707, "terrain1m"}};
static const shape terrain_quick[] = {{TERRAIN, 22, "terrain1k"}, {TERRAIN, 71, "terrain10k"},
                                      {TERRAIN, 224, "terrain100k"}};
/* The closed series: icospheres of levels 4, 6 and 8, and the terrain of 10^6 triangles. */
static const shape closed_shapes[] = {{ICOSPHERE, 4, "icosphere5k"},
                                      {ICOSPHERE, 6, "icosphere82k"},
                                      {ICOSPHERE, 8, "icosphere1.3m"},
                                      {TERRAIN, 707, "terrain1m"}};
static const int closed_full_sides[] = {512, 1024};
static const int closed_quick_sides[] = {256};
#define MAX_POINTS 4
#define MAX_SIDES 2
#define COUNT_OF(a) (int)(sizeof(a) / sizeof((a)[0]))

/* The targets the summaries check (docs/benchmarks.md, "Triangle meshes"; issue 39 for the closed
 * series). */
#define TARGET_SCALING 2.5      /* time(10^6 triangles) / time(10^4) at most; closed: 1.3M / 5k */
#define TARGET_GPU_OVER_EMBREE 0.7
#define TARGET_BUILD_MS 1500.0  /* a BVH over 10^6 triangles */

/* The contestants, in round order. */
enum { PEER, GPU, MULTIPASS, CPU, CONTESTANTS };
static const char *const contestant_names[CONTESTANTS] = {"Embree", "GPU", "multipass", "CPU reference"};

/* ---- a point's scene ---- */

/* The camera of a shape: the terrain seen from above at 35 degrees; the unit icosphere from 3 units
 * away, a little above, so that it fills most of the frame and its rim is in view. */
static bg_camera camera_of(shape_kind kind)
{
    bg_camera cam = bg_camera_init();
    cam.position = kind == TERRAIN ? bg_vec3_make(0.0, 1.6, 2.3) : bg_vec3_make(0.0, 1.0, 2.8);
    cam.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    cam.fov_y_degrees = 40.0;
    return cam;
}

/* The mesh in the benchmarks' scene (lib/mesh_scene.c) with the shape's camera. */
static bg_status build(bg_scene *scene, const mesh *m, shape_kind kind)
{
    bg_camera cam = camera_of(kind);
    return bench_mesh_scene(scene, m, &cam);
}

/* One image size of a point: its renderers (one per plan and size, so that each keeps its caches),
 * its contestants (in the series' list), their images and what they measured. */
typedef struct view {
    int side;
    bool selected;
    bg_renderer *renderer, *multipass; /* BG_PLAN_AUTO (the tree plan) and BG_PLAN_MULTIPASS */
    bench_contestant *c;               /* CONTESTANTS of them, in the series' list */
    bg_image images[CONTESTANTS];      /* images[CPU] is the reference */
    bench_gpu_job gpu, paper;
    bench_cpu_job cpu;
#ifdef BENCH_EMBREE
    embree_peer_job peer_frame;
#endif
    bench_error error[CONTESTANTS]; /* error[CPU] unused */
    char note[200];                 /* why a contestant did not run */
} view;

/* One mesh: its scene and peer (shared by its sizes), their builds, and its views. */
typedef struct point {
    shape shape;
    uint32_t triangles;
    double build_ms;    /* add (validation, copies, the mesh's tree) and the first commit: median */
    util_alloc_counter bytes; /* of the scene rendered (the last one built) */
    double peer_build_ms, peer_commit_ms; /* medians */
    size_t peer_bytes;  /* held by Embree after its build */
    bg_scene *scene;
    embree_peer *peer;
    int view_count;
    view views[MAX_SIDES];
} point;

/* A series: its points, and one list of every contestant of every view of every point: the rounds
 * run over all of them, so that a ratio between two points (the scaling targets) is measured side by
 * side too. */
typedef struct series {
    const char *label;     /* for progress lines */
    bool multipass;        /* the multipass takes part */
    bool reference_rounds; /* the CPU reference is timed in the rounds (else it draws its image once) */
    int count;
    point pts[MAX_POINTS];
    bench_contestant list[MAX_POINTS * MAX_SIDES * CONTESTANTS];
} series;

static void note(view *v, const char *format, const char *text)
{
    size_t used = strlen(v->note);
    snprintf(v->note + used, sizeof v->note - used, format, used ? "; " : "", text);
}

/* A new scene of the mesh, counted through util_alloc; the time from add to commit in *ms. */
static bg_scene *scene_of(const mesh *m, shape_kind kind, util_alloc_counter *bytes, double *ms)
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
        st = build(scene, m, kind);
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    *ms = bench_now_ms() - t0;
    if (st != BG_OK) {
        fprintf(stderr, "bench_mesh: %u triangles: %s\n", m->triangle_count,
                scene ? bg_scene_error_message(scene) : "no scene");
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

/* The shape's mesh, made in code. */
static bool make_mesh(const shape *sh, mesh *out)
{
    char why[256] = "";
    bg_status st;
    if (sh->kind == TERRAIN) {
        mesh_heightfield_desc hd = {0};
        hd.n = sh->param;
        st = mesh_heightfield(&hd, out, why, sizeof why);
    } else {
        mesh_icosphere_desc id = {0};
        id.level = sh->param;
        st = mesh_icosphere(&id, out, why, sizeof why);
    }
    if (st != BG_OK)
        fprintf(stderr, "bench_mesh: %s: %s\n", sh->name, why);
    return st == BG_OK;
}

/* The point's scene, built BUILD_RUNS times (the last one is kept). */
static bool build_scene(point *p)
{
    mesh m = {0};
    if (!make_mesh(&p->shape, &m))
        return false;
    p->triangles = m.triangle_count;
    double build_ms[BUILD_RUNS];
    for (int r = 0; r < BUILD_RUNS; r++) {
        bg_scene_destroy(p->scene); /* counted by p->bytes before scene_of resets it */
        p->scene = scene_of(&m, p->shape.kind, &p->bytes, &build_ms[r]);
        if (!p->scene)
            break;
    }
    mesh_free(&m); /* the scene holds its own copy */
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

/* A view's renderers, jobs and images, its reference frame and its other warm-up frames. */
static bool prepare_view(const series *s, point *p, view *v, bench_gpu *gpu)
{
    bench_progress("mesh: %s (%u triangles) %dx%d: reference, warm-up", p->shape.name, p->triangles, v->side,
                   v->side);
    bg_render_settings set = bg_render_settings_init();
    set.max_depth = 0;
    if (gpu) {
        bg_renderer_desc rd = {0};
        v->renderer = bench_gpu_renderer(gpu, rd);
        if (s->multipass)
            v->multipass = bench_gpu_renderer(gpu, rd);
    }
    v->gpu.renderer = v->renderer;
    v->gpu.scene = p->scene;
    v->gpu.settings = set;
    v->paper = v->gpu;
    v->paper.renderer = v->multipass;
    v->paper.settings.gpu_plan = BG_PLAN_MULTIPASS;
    v->cpu = (bench_cpu_job){p->scene, set};
    bench_frame_fn frames[CONTESTANTS] = {NULL, bench_gpu_frame, bench_gpu_frame, bench_cpu_frame};
    void *jobs[CONTESTANTS] = {NULL, &v->gpu, &v->paper, &v->cpu};
#ifdef BENCH_EMBREE
    v->peer_frame = (embree_peer_job){p->peer, set};
    frames[PEER] = embree_peer_frame;
    jobs[PEER] = &v->peer_frame;
#endif
    for (int i = 0; i < CONTESTANTS; i++) {
        if (!bench_image_alloc(&v->images[i], v->side, v->side, BG_PIXEL_RGBA8))
            return false;
        v->c[i] = (bench_contestant){.name = contestant_names[i], .frame = frames[i], .user = jobs[i],
                                     .image = &v->images[i]};
    }
    if (!bench_warm_up(&v->c[CPU]))
        return false;
    /* rounds > 0: takes part (the count is set once every point is ready) */
    v->c[CPU].rounds = s->reference_rounds ? 1 : 0;
#ifdef BENCH_EMBREE
    if (!bench_warm_up(&v->c[PEER]))
        return false;
    v->c[PEER].rounds = 1;
#else
    note(v, "%sEmbree not built (%s)", "libembree-dev not installed");
#endif
    if (v->renderer && bench_warm_up(&v->c[GPU]))
        v->c[GPU].rounds = 1;
    else
        note(v, "%sGPU not run: %s", v->renderer ? bg_renderer_error_message(v->renderer) : "no GPU context");
    if (!s->multipass)
        return true;
    if (v->multipass && bench_warm_up(&v->c[MULTIPASS]))
        v->c[MULTIPASS].rounds = 1;
    else
        note(v, "%smultipass not run: %s", v->multipass ? bg_renderer_error_message(v->multipass) : "no GPU context");
    return true;
}

/* A point's scene, the peer's BVH and its selected views; the longest warm-up of a contestant in the
 * rounds in *slowest. */
static bool prepare(const series *s, point *p, bench_gpu *gpu, double *slowest)
{
    if (!build_scene(p))
        return false;
    bench_progress("mesh: %s: %u triangles: BVH", p->shape.name, p->triangles);
#ifdef BENCH_EMBREE
    if (!build_peer(p))
        return false;
#endif
    for (int j = 0; j < p->view_count; j++) {
        view *v = &p->views[j];
        if (!v->selected)
            continue;
        if (!prepare_view(s, p, v, gpu))
            return false;
        for (int i = 0; i < CONTESTANTS; i++)
            if (v->c[i].rounds > 0 && v->c[i].warm_ms > *slowest)
                *slowest = v->c[i].warm_ms;
    }
    return true;
}

static void release(point *p)
{
    for (int j = 0; j < p->view_count; j++) {
        view *v = &p->views[j];
        for (int i = 0; i < CONTESTANTS; i++)
            bench_image_free(&v->images[i]);
        bg_renderer_destroy(v->renderer);
        bg_renderer_destroy(v->multipass);
    }
#ifdef BENCH_EMBREE
    embree_peer_destroy(p->peer);
#endif
    bg_scene_destroy(p->scene);
}

/* Every point of s (filled by the caller: shapes, views and their selection) prepared, then the
 * rounds over all of them (as many for every contestant: those the slowest warm-up gives), then the
 * errors. False when a point could not be prepared or a frame failed; s->count says how many points
 * are to be released. */
static bool run_series(series *s, bench_gpu *gpu, int runs)
{
    double slowest = 0.0;
    int used = 0;
    for (int i = 0; i < s->count; i++)
        for (int j = 0; j < s->pts[i].view_count; j++, used += CONTESTANTS)
            s->pts[i].views[j].c = &s->list[used];
    for (int i = 0; i < s->count; i++)
        if (!prepare(s, &s->pts[i], gpu, &slowest))
            return false;
    int rounds = bench_rounds_after(slowest, runs);
    for (int i = 0; i < used; i++)
        if (s->list[i].rounds > 0)
            s->list[i].rounds = rounds;
    if (!bench_interleave(s->list, used, s->label))
        return false;
    for (int k = 0; k < s->count; k++)
        for (int j = 0; j < s->pts[k].view_count; j++) {
            view *v = &s->pts[k].views[j];
            for (int i = 0; i < CONTESTANTS; i++)
                if (i != CPU && v->c[i].rounds > 0)
                    v->error[i] = bench_error_of(&v->images[CPU], &v->images[i]);
        }
    return true;
}

/* ---- output ---- */

static char *ratio_text(double ratio, char *buffer, size_t size)
{
    if (ratio > 0.0)
        snprintf(buffer, size, "%.2f", ratio);
    else
        snprintf(buffer, size, "-");
    return buffer;
}

static char *error_text(const view *v, int i, char *buffer, size_t size)
{
    if (v->c[i].rounds > 0)
        return bench_error_brief(&v->error[i], buffer, size);
    snprintf(buffer, size, "-");
    return buffer;
}

static void print_setup(const bench_gpu *gpu, const embree_peer *peer, int runs)
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
    bench_select_print(stdout);
}

/* -- the terrain series -- */

#define TABLE_FORMAT(x) "%10" x " %9s %8s %9s %8s | %-24s | %-24s | %-24s | %-24s | %7s %7s %7s %7s | %-16s | %-16s | %-16s %s\n"

static void print_header(int side)
{
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
    const view *v = &p->views[0];
    char cell[CONTESTANTS][64], ratio[4][16], err[3][32], ebuild[16], ebytes[16], build[16], mb[16];
    for (int i = 0; i < CONTESTANTS; i++)
        bench_contestant_text(&v->c[i], cell[i], sizeof cell[i]);
    snprintf(build, sizeof build, "%.1f", p->build_ms);
    snprintf(mb, sizeof mb, "%.1f", p->bytes.live_bytes / 1048576.0);
    bool peer = v->c[PEER].rounds > 0;
    snprintf(ebuild, sizeof ebuild, peer ? "%.1f" : "-", p->peer_commit_ms);
    snprintf(ebytes, sizeof ebytes, peer ? "%.1f" : "-", p->peer_bytes / 1048576.0);
    printf(TABLE_FORMAT("u"), p->triangles, build, mb, ebuild, ebytes, cell[PEER], cell[GPU], cell[MULTIPASS],
           cell[CPU], ratio_text(bench_ratio(&v->c[GPU], &v->c[CPU]), ratio[0], 16),
           ratio_text(bench_ratio(&v->c[GPU], &v->c[PEER]), ratio[1], 16),
           ratio_text(bench_ratio(&v->c[PEER], &v->c[CPU]), ratio[2], 16),
           ratio_text(bench_ratio(&v->c[MULTIPASS], &v->c[GPU]), ratio[3], 16), error_text(v, GPU, err[0], 32),
           error_text(v, MULTIPASS, err[2], 32), error_text(v, PEER, err[1], 32), v->note);
    fflush(stdout);
}

#define CSV_HEADER                                                                                          \
    "triangles,build_ms,scene_bytes,cpu_median_ms,cpu_min_ms,cpu_max_ms,gpu_median_ms,rounds,gpu_min_ms,"   \
    "gpu_max_ms,embree_median_ms,embree_min_ms,embree_max_ms,embree_build_ms,embree_commit_ms,"             \
    "embree_bytes,gpu_over_cpu,gpu_over_embree,embree_over_cpu," BENCH_ERROR_CSV_NAMED("gpu_") ","          \
    BENCH_ERROR_CSV_NAMED("embree_") ",multipass_median_ms,multipass_min_ms,multipass_max_ms,"              \
    "multipass_over_gpu," BENCH_ERROR_CSV_NAMED("multipass_")

/* An error's CSV fields, empty where its contestant did not run. */
static void error_csv(FILE *csv, const view *v, int i)
{
    if (v->c[i].rounds > 0)
        bench_error_csv(csv, &v->error[i]);
    else
        fputs(",,,,", csv);
}

/* A contestant that did not run has -1 times and empty error fields. */
static void write_row(FILE *csv, const point *p)
{
    const view *v = &p->views[0];
    const bench_times *c = &v->c[CPU].times, *g = &v->c[GPU].times, *e = &v->c[PEER].times;
    bool gpu = v->c[GPU].rounds > 0, peer = v->c[PEER].rounds > 0;
    fprintf(csv, "%u,%.3f,%zu,%.3f,%.3f,%.3f,%.3f,%d,", p->triangles, p->build_ms, p->bytes.live_bytes, c->median, c->min,
            c->max, gpu ? g->median : -1.0, v->c[CPU].rounds);
    fprintf(csv, "%.3f,%.3f,%.3f,%.3f,%.3f,", gpu ? g->min : -1.0, gpu ? g->max : -1.0, peer ? e->median : -1.0,
            peer ? e->min : -1.0, peer ? e->max : -1.0);
    fprintf(csv, "%.3f,%.3f,%zu,%.4f,%.4f,%.4f,", peer ? p->peer_build_ms : -1.0, peer ? p->peer_commit_ms : -1.0,
            p->peer_bytes, bench_ratio(&v->c[GPU], &v->c[CPU]), bench_ratio(&v->c[GPU], &v->c[PEER]),
            bench_ratio(&v->c[PEER], &v->c[CPU]));
    error_csv(csv, v, GPU);
    fputc(',', csv);
    error_csv(csv, v, PEER);
    const bench_times *m = &v->c[MULTIPASS].times;
    bool multi = v->c[MULTIPASS].rounds > 0;
    fprintf(csv, ",%.3f,%.3f,%.3f,%.4f,", multi ? m->median : -1.0, multi ? m->min : -1.0, multi ? m->max : -1.0,
            bench_ratio(&v->c[MULTIPASS], &v->c[GPU]));
    error_csv(csv, v, MULTIPASS);
    fputc('\n', csv);
}

/* The targets, measured: the scaling of each contestant from the second point to the last (the
 * median of the per-round ratios), the GPU against the peer at the last, the BVH builds of the last. */
static void print_summary(const point *pts, int done)
{
    const point *last = &pts[done - 1], *second = &pts[1];
    const view *l = &last->views[0], *s = &second->views[0];
    printf("\ntime(%u triangles) / time(%u triangles), target <= %.1f:", last->triangles, second->triangles,
           TARGET_SCALING);
    for (int i = 0; i < CONTESTANTS; i++)
        if (l->c[i].rounds > 0 && s->c[i].rounds > 0)
            printf(" %s %.2f%s", contestant_names[i], bench_ratio(&l->c[i], &s->c[i]), i + 1 < CONTESTANTS ? "," : "");
    printf("\n");
    double ratio = bench_ratio(&l->c[GPU], &l->c[PEER]);
    char err[2][96];
    if (ratio > 0.0)
        printf("GPU / Embree at %u triangles: %.2f (target <= %.1f: %s), at errors GPU %s, Embree %s\n",
               last->triangles, ratio, TARGET_GPU_OVER_EMBREE, ratio <= TARGET_GPU_OVER_EMBREE ? "met" : "not met",
               bench_error_text(&l->error[GPU], err[0], sizeof err[0]),
               bench_error_text(&l->error[PEER], err[1], sizeof err[1]));
    printf("BVH build of %u triangles, target < %.1f s: ours %.2f s (%s)", last->triangles, TARGET_BUILD_MS / 1000.0,
           last->build_ms / 1000.0, last->build_ms < TARGET_BUILD_MS ? "met" : "not met");
    if (l->c[PEER].rounds > 0)
        printf(", Embree %.2f s (rtcCommitScene; %.2f s with the vertex copy)", last->peer_commit_ms / 1000.0,
               last->peer_build_ms / 1000.0);
    printf("\n");
}

/* The terrain series, when BENCH_CASES picks it: 0 done (or not picked), 1 failed. */
static int terrain_series(bench_gpu *gpu, const char *out_dir, bool quick)
{
    if (!bench_selected("terrain_series", 0))
        return 0;
    const int side = quick ? 256 : 1024, runs = quick ? 3 : 5;
    const shape *shapes = quick ? terrain_quick : terrain_full;
    int count = quick ? COUNT_OF(terrain_quick) : COUNT_OF(terrain_full);
    series *s = calloc(1, sizeof *s);
    FILE *csv = s ? bench_csv_open(out_dir, "mesh_scaling.csv", CSV_HEADER) : NULL;
    bool ok = csv != NULL;
    if (ok) {
        *s = (series){.label = "mesh: every terrain point", .multipass = true, .reference_rounds = true,
                      .count = count};
        for (int i = 0; i < count; i++)
            s->pts[i] = (point){.shape = shapes[i], .view_count = 1, .views = {{.side = side, .selected = true}}};
        ok = run_series(s, gpu, runs);
    }
    if (ok) {
        printf("\n");
        print_setup(gpu, s->pts[0].peer, runs);
        print_header(side);
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
    return ok ? 0 : 1;
}

/* -- the closed-mesh series -- */

#define CLOSED_FORMAT(x) "%-14s %9" x " %5" x " %9s %8s %8s | %-24s | %-24s | %7s | %9s | %-10s | %-16s | %-16s %s\n"

static void print_closed_header(void)
{
    printf("\nClosed meshes (unit icospheres, a subdivided icosahedron) and the 10^6-triangle terrain, 2 point\n"
           "lights with shadows, no bounces: the Embree peer against the GPU renderer (BG_PLAN_AUTO), every\n"
           "point and size in the same interleaved rounds (a round: one frame of each). The CPU reference\n"
           "draws each image once, untimed but for the CPU once column: the image the errors are against.\n"
           "Build ms: ours, median of %d (add + commit, one thread); Emb bld: Embree's rtcCommitScene calls.\n"
           "Cells: n rounds, ms median [min-max]; GPU/Emb: median of per-round ratios.\n",
           BUILD_RUNS);
    printf(CLOSED_FORMAT("s"), "mesh", "triangles", "size", "build ms", "Emb bld", "scene MB", "Embree: n ms [min-max]",
           "GPU: n ms [min-max]", "GPU/Emb", "CPU once", "plan", "GPU error", "Embree error", "");
}

static void print_closed_row(const point *p, const view *v)
{
    char cell[2][64], ratio[16], err[2][32], ebuild[16], build[16], mb[16], cpu[16];
    bench_contestant_text(&v->c[PEER], cell[0], sizeof cell[0]);
    bench_contestant_text(&v->c[GPU], cell[1], sizeof cell[1]);
    snprintf(build, sizeof build, "%.1f", p->build_ms);
    snprintf(mb, sizeof mb, "%.1f", p->bytes.live_bytes / 1048576.0);
    snprintf(ebuild, sizeof ebuild, v->c[PEER].rounds > 0 ? "%.1f" : "-", p->peer_commit_ms);
    snprintf(cpu, sizeof cpu, "%.0f", v->c[CPU].warm_ms);
    printf(CLOSED_FORMAT("u"), p->shape.name, p->triangles, (unsigned)v->side, build, ebuild, mb, cell[0], cell[1],
           ratio_text(bench_ratio(&v->c[GPU], &v->c[PEER]), ratio, sizeof ratio), cpu,
           v->c[GPU].rounds > 0 ? bench_plan_name(v->gpu.stats.plan) : "-", error_text(v, GPU, err[0], 32),
           error_text(v, PEER, err[1], 32), v->note);
    fflush(stdout);
}

#define CLOSED_CSV_HEADER                                                                                   \
    "mesh,triangles,size,rounds,embree_median_ms,embree_min_ms,embree_max_ms,gpu_median_ms,gpu_min_ms,"     \
    "gpu_max_ms,gpu_over_embree,cpu_once_ms,build_ms,scene_bytes,embree_commit_ms,embree_bytes,plan,"        \
    BENCH_ERROR_CSV_NAMED("gpu_") "," BENCH_ERROR_CSV_NAMED("embree_")

/* A contestant that did not run has -1 times and empty error fields. */
static void write_closed_row(FILE *csv, const point *p, const view *v)
{
    const bench_times *g = &v->c[GPU].times, *e = &v->c[PEER].times;
    bool gpu = v->c[GPU].rounds > 0, peer = v->c[PEER].rounds > 0;
    fprintf(csv, "%s,%u,%d,%d,", p->shape.name, p->triangles, v->side, gpu ? v->c[GPU].rounds : v->c[PEER].rounds);
    fprintf(csv, "%.3f,%.3f,%.3f,", peer ? e->median : -1.0, peer ? e->min : -1.0, peer ? e->max : -1.0);
    fprintf(csv, "%.3f,%.3f,%.3f,%.4f,", gpu ? g->median : -1.0, gpu ? g->min : -1.0, gpu ? g->max : -1.0,
            bench_ratio(&v->c[GPU], &v->c[PEER]));
    fprintf(csv, "%.1f,%.3f,%zu,%.3f,%zu,%s,", v->c[CPU].warm_ms, p->build_ms, p->bytes.live_bytes,
            peer ? p->peer_commit_ms : -1.0, p->peer_bytes, gpu ? bench_plan_name(v->gpu.stats.plan) : "");
    error_csv(csv, v, GPU);
    fputc(',', csv);
    error_csv(csv, v, PEER);
    fputc('\n', csv);
}

/* The view of points[k] at a size, or NULL where it did not run. */
static const view *view_at(const series *s, shape_kind kind, int param, int side)
{
    for (int k = 0; k < s->count; k++)
        for (int j = 0; j < s->pts[k].view_count; j++)
            if (s->pts[k].shape.kind == kind && s->pts[k].shape.param == param && s->pts[k].views[j].side == side &&
                s->pts[k].views[j].selected)
                return &s->pts[k].views[j];
    return NULL;
}

/* The closed series' targets (issue 39): the largest icosphere against the smallest, per size and
 * contestant (per-round ratios: the two are in the same rounds), and the GPU against the peer on the
 * terrain. */
static void print_closed_summary(const series *s, const int *sides, int side_count)
{
    const shape *small = &closed_shapes[0], *large = &closed_shapes[2], *terrain = &closed_shapes[3];
    for (int j = 0; j < side_count; j++) {
        const view *a = view_at(s, large->kind, large->param, sides[j]);
        const view *b = view_at(s, small->kind, small->param, sides[j]);
        if (a && b)
            printf("%dx%d: time(%s) / time(%s), target <= %.1f: Embree %.2f, GPU %.2f\n", sides[j], sides[j],
                   large->name, small->name, TARGET_SCALING, bench_ratio(&a->c[PEER], &b->c[PEER]),
                   bench_ratio(&a->c[GPU], &b->c[GPU]));
        const view *t = view_at(s, terrain->kind, terrain->param, sides[j]);
        if (t && bench_ratio(&t->c[GPU], &t->c[PEER]) > 0.0)
            printf("%dx%d: GPU / Embree on %s: %.2f (target <= 1.0)\n", sides[j], sides[j], terrain->name,
                   bench_ratio(&t->c[GPU], &t->c[PEER]));
    }
}

/* The closed series' points and views that BENCH_CASES picks (every one when it names none). */
static void select_closed(series *s, const int *sides, int side_count)
{
    s->count = 0;
    for (int i = 0; i < COUNT_OF(closed_shapes); i++) {
        point *p = &s->pts[s->count];
        *p = (point){.shape = closed_shapes[i], .view_count = side_count};
        bool any = false;
        for (int j = 0; j < side_count; j++) {
            p->views[j].side = sides[j];
            p->views[j].selected = bench_selected(closed_shapes[i].name, sides[j]);
            any = any || p->views[j].selected;
        }
        if (any)
            s->count++;
    }
}

/* The closed series, for the points BENCH_CASES picks: 0 done (or none picked), 1 failed. */
static int closed_series(bench_gpu *gpu, const char *out_dir, bool quick)
{
    const int *sides = quick ? closed_quick_sides : closed_full_sides;
    const int side_count = quick ? COUNT_OF(closed_quick_sides) : COUNT_OF(closed_full_sides);
    const int runs = quick ? 3 : 5;
    series *s = calloc(1, sizeof *s);
    if (!s)
        return 1;
    *s = (series){.label = "mesh: every closed-series point"};
    select_closed(s, sides, side_count);
    if (s->count == 0) {
        free(s);
        return 0;
    }
    FILE *csv = bench_csv_open(out_dir, "mesh_closed.csv", CLOSED_CSV_HEADER);
    bool ok = csv && run_series(s, gpu, runs);
    if (ok) {
        printf("\n");
        print_setup(gpu, s->pts[0].peer, runs);
        print_closed_header();
        for (int i = 0; i < s->count; i++)
            for (int j = 0; j < s->pts[i].view_count; j++)
                if (s->pts[i].views[j].selected) {
                    print_closed_row(&s->pts[i], &s->pts[i].views[j]);
                    write_closed_row(csv, &s->pts[i], &s->pts[i].views[j]);
                }
        print_closed_summary(s, sides, side_count);
    }
    if (csv)
        fclose(csv);
    for (int i = 0; i < s->count; i++)
        release(&s->pts[i]);
    free(s);
    return ok ? 0 : 1;
}

/* Every name BENCH_CASES may hold, asked once before any work so that a typo costs nothing: false
 * (with the names on stderr) when it holds another. */
static bool check_selection(void)
{
    char known[256];
    size_t used = (size_t)snprintf(known, sizeof known, "terrain_series");
    (void)bench_selected("terrain_series", 0);
    for (int i = 0; i < COUNT_OF(closed_shapes); i++) {
        for (int j = 0; j < COUNT_OF(closed_full_sides); j++)
            (void)bench_selected(closed_shapes[i].name, closed_full_sides[j]);
        (void)bench_selected(closed_shapes[i].name, closed_quick_sides[0]);
        if (used < sizeof known)
            used += (size_t)snprintf(known + used, sizeof known - used, ", %s", closed_shapes[i].name);
    }
    return bench_select_check("bench_mesh", known);
}

int main(int argc, char **argv)
{
    const char *out_dir = bench_out_dir(argc, argv);
    if (!out_dir)
        return 2;
    if (!check_selection())
        return 2;
    bool quick = bench_quick();
    bench_gpu gpu;
    bool have_gpu = bench_gpu_open(&gpu);
    int status = terrain_series(have_gpu ? &gpu : NULL, out_dir, quick);
    if (status == 0)
        status = closed_series(have_gpu ? &gpu : NULL, out_dir, quick);
    if (have_gpu)
        bench_gpu_close(&gpu);
    return status;
}
