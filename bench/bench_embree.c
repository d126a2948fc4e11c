/* The GPU path against an Embree 3 peer (bench/lib/embree_peer.h): the same scenes, camera, lights and
 * BRDF, traced by the CPU kernel people pick today, so the table says where the GPU path stands.
 *
 * Usage: bench_embree [out_dir]   (default bench/out; QUICK=1 for fewer runs)
 * Per case: the CPU reference renders once (the image both are compared with, and its time as a
 * hint); the peer builds its BVH (timed on its own, not part of a frame); after one warm-up frame each,
 * the peer and the GPU path are timed in interleaved rounds (round i: one peer frame, one GPU frame), so
 * the drift of a shared machine falls on both alike. Cases whose GPU warm-up takes over BENCH_SLOW_MS
 * get BENCH_SLOW_RUNS rounds, over VERY_SLOW_MS one. Writes out_dir/embree.csv.
 * Built only where Embree is installed (Makefile, bench section). */
#include <embree3/rtcore.h>
#include <stdlib.h>
#include <string.h>

#include "lib/bench_measure.h"
#include "lib/embree_peer.h"
#include "scenes/scenes.h"

#define MAX_RUNS 16
/* A case whose GPU warm-up takes longer than this (many_spheres_1024 on llvmpipe: minutes per frame)
 * gets one round: a median of more would multiply the whole benchmark's time for little. */
#define VERY_SLOW_MS 60000.0

typedef struct bench_case {
    scene_id id;
    int size;
    int spheres; /* SCENE_MANY_SPHERES only; 0 otherwise */
} bench_case;

static const bench_case cases[] = {
    {SCENE_PAPER_EARTH, 512, 0},        {SCENE_PAPER_EARTH, 1024, 0}, {SCENE_PAPER_EARTH_SHADOW, 512, 0},
    {SCENE_PAPER_EARTH_SHADOW, 1024, 0}, {SCENE_GLASS, 512, 0},         {SCENE_GLASS, 1024, 0},
    {SCENE_MANY_SPHERES, 512, 64},      {SCENE_MANY_SPHERES, 512, 1024},
};
#define CASE_COUNT (int)(sizeof cases / sizeof cases[0])

/* What one case measured. */
typedef struct case_result {
    bench_times embree, gpu;
    double cpu_ms, build_ms;
    bench_error embree_error, gpu_error;
} case_result;

/* The renders of one case, the reference first; false (with the reason on stderr) on any failure. */
typedef struct case_images {
    bg_image reference, peer, gpu;
} case_images;

static bool peer_frame(embree_peer *peer, const bg_render_settings *settings, bg_image *image, double *ms)
{
    char message[512];
    double t0 = bench_now_ms();
    bool ok = embree_peer_render(peer, settings, image, message, sizeof message);
    *ms = bench_now_ms() - t0;
    if (!ok)
        fprintf(stderr, "%s\n", message);
    return ok;
}

static bool gpu_frame(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings, bg_image *image,
                      double *ms)
{
    double t0 = bench_now_ms();
    bool ok = bg_render_gpu(renderer, scene, settings, image) == BG_OK;
    *ms = bench_now_ms() - t0;
    if (!ok)
        fprintf(stderr, "GPU render failed: %s\n", bg_renderer_error_message(renderer));
    return ok;
}

/* The reference image and the BVH, then the warm-up frames; returns the number of rounds to time. */
static int prepare(embree_peer *peer, bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                   case_images *im, int runs, case_result *res)
{
    char message[512];
    double t0 = bench_now_ms(), peer_ms, gpu_ms;
    if (bg_render_cpu(scene, settings, &im->reference) != BG_OK) {
        fprintf(stderr, "CPU render failed: %s\n", bg_scene_error_message(scene));
        return 0;
    }
    res->cpu_ms = bench_now_ms() - t0;
    if (!embree_peer_build(peer, scene, message, sizeof message)) {
        fprintf(stderr, "%s\n", message);
        return 0;
    }
    res->build_ms = embree_peer_build_ms(peer);
    if (!peer_frame(peer, settings, &im->peer, &peer_ms) || !gpu_frame(renderer, scene, settings, &im->gpu, &gpu_ms))
        return 0;
    res->embree_error = bench_error_of(&im->reference, &im->peer);
    res->gpu_error = bench_error_of(&im->reference, &im->gpu);
    if (gpu_ms > VERY_SLOW_MS)
        return 1;
    return gpu_ms > BENCH_SLOW_MS && runs > BENCH_SLOW_RUNS ? BENCH_SLOW_RUNS : runs;
}

/* Interleaved rounds: one peer frame, then one GPU frame. */
static bool time_rounds(embree_peer *peer, bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                        case_images *im, int runs, const char *label, case_result *res)
{
    double te[MAX_RUNS], tg[MAX_RUNS];
    for (int r = 0; r < runs; r++) {
        bench_progress("embree: %s, round %d of %d", label, r + 1, runs);
        if (!peer_frame(peer, settings, &im->peer, &te[r]) || !gpu_frame(renderer, scene, settings, &im->gpu, &tg[r]))
            return false;
    }
    res->embree = bench_times_of(te, runs);
    res->gpu = bench_times_of(tg, runs);
    return true;
}

static void case_label(const bench_case *c, char *buffer, size_t size)
{
    if (c->spheres > 0)
        snprintf(buffer, size, "%s_%d", scenes_name(c->id), c->spheres);
    else
        snprintf(buffer, size, "%s", scenes_name(c->id));
}

static void print_row(FILE *csv, const bench_case *c, const case_result *res)
{
    char label[64], et[128], gt[128];
    case_label(c, label, sizeof label);
    printf("%-19s %5d %2d | %8.1f [%7.1f-%7.1f] | %8.1f [%7.1f-%7.1f] | %7.2f | %8.1f | %6.1f | %-47s | %s\n",
           label, c->size, res->embree.runs, res->embree.median, res->embree.min, res->embree.max, res->gpu.median,
           res->gpu.min, res->gpu.max, res->gpu.median / res->embree.median, res->cpu_ms, res->build_ms,
           bench_error_text(&res->embree_error, et, sizeof et), bench_error_text(&res->gpu_error, gt, sizeof gt));
    fflush(stdout);
    fprintf(csv, "%s,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.4f,%.1f,%.3f,", scenes_name(c->id), c->spheres, c->size,
            res->embree.runs, res->embree.median, res->embree.min, res->embree.max, res->gpu.median, res->gpu.min,
            res->gpu.max, res->gpu.median / res->embree.median, res->cpu_ms, res->build_ms);
    bench_error_csv(csv, &res->embree_error);
    fputc(',', csv);
    bench_error_csv(csv, &res->gpu_error);
    fputc('\n', csv);
}

static void free_images(case_images *im)
{
    bench_image_free(&im->reference);
    bench_image_free(&im->peer);
    bench_image_free(&im->gpu);
}

static bool run_case(embree_peer *peer, bench_gpu *gpu, const bench_case *c, int runs, FILE *csv)
{
    scene_params params;
    memset(&params, 0, sizeof params);
    params.spheres = c->spheres;
    bg_scene *scene = bench_scene(c->id, &params);
    if (!scene)
        return false;
    case_images im;
    memset(&im, 0, sizeof im);
    bool ok = bench_image_alloc(&im.reference, c->size, c->size, BG_PIXEL_RGBA8) &&
              bench_image_alloc(&im.peer, c->size, c->size, BG_PIXEL_RGBA8) &&
              bench_image_alloc(&im.gpu, c->size, c->size, BG_PIXEL_RGBA8);
    char label[64];
    case_label(c, label, sizeof label);
    bench_progress("embree: %s %dx%d: reference, BVH, warm-up", label, c->size, c->size);
    bg_render_settings settings = bg_render_settings_init();
    case_result res;
    memset(&res, 0, sizeof res);
    int rounds = ok ? prepare(peer, gpu->renderer, scene, &settings, &im, runs, &res) : 0;
    ok = rounds > 0 && time_rounds(peer, gpu->renderer, scene, &settings, &im, rounds, label, &res);
    if (ok)
        print_row(csv, c, &res);
    else
        fprintf(stderr, "embree: %s %dx%d failed\n", label, c->size, c->size);
    free_images(&im);
    bg_scene_destroy(scene);
    return ok;
}

static void print_header(const bench_gpu *gpu, const embree_peer *peer, int runs)
{
    char how[128];
    printf("== GPU path against an Embree %d.%d.%d peer (same scenes, camera, lights and BRDF), interleaved rounds\n",
           RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    bench_print_setup(stdout, gpu, runs);
    printf("Embree peer: %s over 8x8 tiles; user geometry with the reference's double\n"
           "intersection and shading. n: interleaved rounds. GPU/Emb > 1: the peer is faster. CPU ref: one frame\n"
           "of the CPU reference (the image both are compared with); BVH: the peer's build, not in its frames.\n",
           embree_peer_describe(peer, how, sizeof how));
    printf("%-19s %5s %2s | %-26s | %-26s | %7s | %8s | %6s | %-47s | %s\n", "scene", "size", "n",
           "Embree ms median [min-max]", "GPU ms median [min-max]", "GPU/Emb", "CPU ref", "BVH ms",
           "Embree error vs CPU", "GPU error vs CPU");
}

int main(int argc, char **argv)
{
    const char *dir = bench_out_dir(argc, argv);
    const int runs = bench_quick() ? 3 : 7;
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
    FILE *csv = bench_csv_open(dir, "embree.csv",
                               "scene,spheres,size,runs,embree_median_ms,embree_min_ms,embree_max_ms,gpu_median_ms,"
                               "gpu_min_ms,gpu_max_ms,gpu_over_embree,cpu_ref_ms,bvh_build_ms,"
                               "embree_psnr_db,embree_max_abs,embree_mean_abs,embree_over_share,embree_interior_max,"
                               "gpu_psnr_db,gpu_max_abs,gpu_mean_abs,gpu_over_share,gpu_interior_max");
    int status = !csv;
    if (csv) {
        print_header(&gpu, peer, runs);
        for (int i = 0; i < CASE_COUNT && !status; i++)
            status = !run_case(peer, &gpu, &cases[i], runs, csv);
        fclose(csv);
    }
    bench_gpu_close(&gpu);
    embree_peer_destroy(peer);
    return status;
}
