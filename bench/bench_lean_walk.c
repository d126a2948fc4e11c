/* One case of the walk, timed in its own process, so that two builds of the library can be compared
 * in interleaved rounds (docs/benchmarks.md, "A leaner walk: what was measured"): a script runs this
 * program of build A, then of build B, then A again, and takes the median of the per-round ratios.
 * Two libraries cannot share one process (the same symbols), hence a process per round.
 *
 * Usage: bench_lean_walk CASE SIZE FRAMES [PLAN]
 *   CASE: spheres64, spheres1024 (SCENE_MANY_SPHERES), terrain<n> (an n x n terrain, 2 n^2
 *   triangles, as bench_mesh draws it), ico<level> (the unit icosphere, 20 * 4^level triangles,
 *   a closed mesh, lit by two lights with shadows), bunny (examples/scenes/bunny_scene.h, run from
 *   the source tree's root), or a shared scene's short name (scenes_find: paper_earth, glass, ...).
 *   PLAN: auto (default), fused, tree or multipass.
 * After one untimed frame (compilation), FRAMES frames of SIZE x SIZE (RGBA8) are timed;
 * prints "CASE plan median_ms min_ms checksum", the checksum an FNV-1a hash of the last image's bytes,
 * so that two builds' images can be compared bit for bit.
 *
 * BENCH_MOVE=1 times what camera moves cost instead (docs/benchmarks.md, "Mesh trees in view
 * order"): three blocks of FRAMES rounds, each round a cached frame and a frame after a move of the
 * camera along x, between x = 0.01 and 0 in the first block, 0.4 and 0.5 in the second, 0.4 and -0.4
 * in the third. The mesh cases' cameras stand over the mesh's centre (x = 0): the first two blocks
 * keep the side of the centre the mesh tree is ordered for, the third crosses it at every move (the
 * tree is ordered again and its node texture rewritten). Prints "CASE plan cached_ms small_ms
 * one_side_ms across_ms", the medians. */
#include <stdlib.h>
#include <string.h>

#include "betelgeuse/scene/scene_internal.h"
#include "lib/bench_measure.h"
#include "lib/mesh_scene.h"
#include "scenes/bunny_scene.h"
#include "scenes/meshes.h"
#include "scenes/scenes.h"

/* A mesh in the mesh benchmarks' scene (lib/mesh_scene.c), seen from above at 35 degrees as
 * bench_mesh's terrain (the icosphere from a little further), committed. */
static bg_status build_mesh(bg_scene *scene, const mesh *m, bool sphere)
{
    bg_camera cam = bg_camera_init();
    cam.position = sphere ? bg_vec3_make(0.0, 1.6, 2.8) : bg_vec3_make(0.0, 1.6, 2.3);
    cam.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    cam.fov_y_degrees = 40.0;
    bg_status st = bench_mesh_scene(scene, m, &cam);
    return st == BG_OK ? bg_scene_commit(scene) : st;
}

/* The case's committed scene, or NULL with a message on stderr. */
static bg_scene *case_scene(const char *name)
{
    if (strcmp(name, "spheres64") == 0 || strcmp(name, "spheres1024") == 0) {
        scene_params p = {0};
        p.spheres = atoi(name + strlen("spheres"));
        return bench_scene(SCENE_MANY_SPHERES, &p);
    }
    scene_id id;
    if (scenes_find(name, &id))
        return bench_scene((int)id, NULL);
    if (strcmp(name, "bunny") == 0) {
        bg_scene *scene = NULL;
        if (bg_scene_create(NULL, &scene) == BG_OK && bunny_scene_build(scene, "bench_lean_walk") == BG_OK)
            return scene;
        bg_scene_destroy(scene);
        return NULL;
    }
    bool terrain = strncmp(name, "terrain", 7) == 0, ico = strncmp(name, "ico", 3) == 0;
    if (!terrain && !ico) {
        fprintf(stderr, "bench_lean_walk: unknown case %s\n", name);
        return NULL;
    }
    mesh m = {0};
    char why[256] = "";
    bg_status st;
    if (terrain) {
        mesh_heightfield_desc hd = {0};
        hd.n = atoi(name + 7);
        st = mesh_heightfield(&hd, &m, why, sizeof why);
    } else {
        mesh_icosphere_desc id = {0};
        id.level = atoi(name + 3);
        st = mesh_icosphere(&id, &m, why, sizeof why);
    }
    bg_scene *scene = NULL;
    if (st == BG_OK)
        st = bg_scene_create(NULL, &scene);
    if (st == BG_OK)
        st = build_mesh(scene, &m, ico);
    mesh_free(&m);
    if (st != BG_OK) {
        fprintf(stderr, "bench_lean_walk: %s: %s\n", name, scene ? bg_scene_error_message(scene) : why);
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

static unsigned long long fnv1a(const unsigned char *p, size_t n)
{
    unsigned long long h = 1469598103934665603ull;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* The camera as built, read back from the committed state (the API has setters only). */
static bg_camera built_camera(const bg_scene *scene)
{
    return bgi_scene_committed(scene)->camera.camera;
}

/* BENCH_MOVE=1: three blocks of FRAMES rounds, each round a cached frame and then a frame after the
 * camera moved along x: to 0.01 and back to 0 (small), between 0.4 and 0.5 (one side), between 0.4
 * and -0.4 (across the centre). */
enum { MOVES = 3 };

static int time_moves(bench_gpu *gpu, bg_scene *scene, const bg_render_settings *settings, bg_image *image,
                      const char *name, int frames)
{
    static const double at[MOVES][2] = {{0.01, 0.0}, {0.4, 0.5}, {0.4, -0.4}};
    bg_camera built = built_camera(scene);
    double cached[MOVES * 64], moved[MOVES][64];
    bg_status st = bg_render_gpu(gpu->renderer, scene, settings, image);
    for (int k = 0; k < MOVES; k++)
        for (int f = 0; f < frames && st == BG_OK; f++) {
            double t0 = bench_now_ms();
            st = bg_render_gpu(gpu->renderer, scene, settings, image);
            cached[k * frames + f] = bench_now_ms() - t0;
            bg_camera c = built;
            c.position.x += at[k][f % 2];
            c.look_at.x += at[k][f % 2];
            if (st == BG_OK)
                st = bg_scene_set_camera(scene, &c);
            if (st == BG_OK)
                st = bg_scene_commit(scene);
            t0 = bench_now_ms();
            if (st == BG_OK)
                st = bg_render_gpu(gpu->renderer, scene, settings, image);
            moved[k][f] = bench_now_ms() - t0;
        }
    if (st != BG_OK) {
        fprintf(stderr, "bench_lean_walk: %s: %s %s\n", name, bg_renderer_error_message(gpu->renderer),
                bg_scene_error_message(scene));
        return 1;
    }
    bg_render_stats stats;
    bg_renderer_get_stats(gpu->renderer, &stats);
    printf("%s %s %.2f %.2f %.2f %.2f\n", name, bench_plan_name(stats.plan),
           bench_times_of(cached, MOVES * frames).median, bench_times_of(moved[0], frames).median,
           bench_times_of(moved[1], frames).median, bench_times_of(moved[2], frames).median);
    return 0;
}

int main(int argc, char **argv)
{
    static const char *const plans[] = {"auto", "fused", "multipass", "tree"}; /* bg_gpu_plan's order */
    int plan = argc == 5 ? -1 : 0;
    for (int p = 0; argc == 5 && p < 4; p++)
        if (strcmp(argv[4], plans[p]) == 0)
            plan = p;
    if ((argc != 4 && argc != 5) || plan < 0) {
        fprintf(stderr, "usage: bench_lean_walk CASE SIZE FRAMES [auto|fused|tree|multipass]\n");
        return 2;
    }
    int size = atoi(argv[2]), frames = atoi(argv[3]);
    if (size < 1 || size > 4096 || frames < 1 || frames > 64) {
        fprintf(stderr, "bench_lean_walk: SIZE 1..4096, FRAMES 1..64\n");
        return 2;
    }
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    bg_scene *scene = case_scene(argv[1]);
    bg_image image;
    if (!scene || !bench_image_alloc(&image, size, size, BG_PIXEL_RGBA8)) {
        bg_scene_destroy(scene);
        bench_gpu_close(&gpu);
        return 1;
    }
    bg_render_settings settings = bg_render_settings_init();
    settings.gpu_plan = (bg_gpu_plan)plan;
    const char *move = getenv("BENCH_MOVE");
    if (move && strcmp(move, "1") == 0) {
        int code = time_moves(&gpu, scene, &settings, &image, argv[1], frames);
        bench_image_free(&image);
        bg_scene_destroy(scene);
        bench_gpu_close(&gpu);
        return code;
    }
    bg_render_stats stats;
    memset(&stats, 0, sizeof stats);
    double times[64];
    bg_status st = bg_render_gpu(gpu.renderer, scene, &settings, &image);
    for (int f = 0; f < frames && st == BG_OK; f++) {
        double t0 = bench_now_ms();
        st = bg_render_gpu(gpu.renderer, scene, &settings, &image);
        times[f] = bench_now_ms() - t0;
    }
    int code = 0;
    if (st != BG_OK) {
        fprintf(stderr, "bench_lean_walk: %s: %s\n", argv[1], bg_renderer_error_message(gpu.renderer));
        code = 1;
    } else {
        bg_renderer_get_stats(gpu.renderer, &stats);
        bench_times t = bench_times_of(times, frames);
        printf("%s %s %.2f %.2f %016llx\n", argv[1], bench_plan_name(stats.plan), t.median, t.min,
               fnv1a((const unsigned char *)image.pixels, (size_t)size * (size_t)size * 4));
    }
    bench_image_free(&image);
    bg_scene_destroy(scene);
    bench_gpu_close(&gpu);
    return code;
}
