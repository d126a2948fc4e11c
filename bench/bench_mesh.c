/* Triangle-count scaling: a heightfield terrain of 10^3 to 10^6 triangles (examples/scenes/meshes.h)
 * seen from above at an angle, lit by two point lights with shadows, no bounces. For each point:
 * the time from bg_scene_add_mesh to the end of the first commit (the copy of the arrays and the
 * mesh's tree, which the add builds), the bytes the scene holds afterwards (counted through its
 * allocator), the CPU reference's frame time, and what the GPU renderer does with it.
 *
 * Usage: bench_mesh [out_dir]   (default bench/out; QUICK=1 for 256x256, fewer runs and points)
 * Writes out_dir/mesh_scaling.csv. */
#include <stdlib.h>
#include <string.h>

#include "lib/bench_measure.h"
#include "scenes/meshes.h"

/* Grid sides n whose 2 n^2 triangles come closest to 10^3 .. 10^6. */
static const int full_n[] = {22, 71, 224, 707};
static const int quick_n[] = {22, 71, 224};

/* ---- bytes the scene holds: a size header before every block ---- */

typedef struct byte_counter {
    size_t live, peak;
} byte_counter;

/* Blocks keep their size in a header as wide as the strictest alignment malloc gives. */
typedef union block_header {
    size_t size;
    long double align_ld;
    void *align_p;
    long long align_ll;
} block_header;

static void *counted_alloc(size_t size, void *user)
{
    byte_counter *c = user;
    block_header *h = malloc(sizeof *h + size);
    if (!h)
        return NULL;
    h->size = size;
    c->live += size;
    if (c->live > c->peak)
        c->peak = c->live;
    return h + 1;
}

static void counted_free(void *p, void *user)
{
    byte_counter *c = user;
    if (!p)
        return;
    block_header *h = (block_header *)p - 1;
    c->live -= h->size;
    free(h);
}

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

typedef struct point {
    int n;
    uint32_t triangles;
    double build_ms;       /* add (validation, copies, the mesh's tree) and the first commit */
    size_t scene_bytes;    /* held by the scene after that commit */
    bench_times cpu;
    bool gpu_ran;
    bench_times gpu;
    char gpu_note[160];
} point;

static bool run_point(bench_gpu *gpu, int n, int side, int runs, point *p)
{
    memset(p, 0, sizeof *p);
    p->n = n;
    char why[256] = "";
    mesh terrain = {0};
    mesh_heightfield_desc hd = {0};
    hd.n = n;
    if (mesh_heightfield(&hd, &terrain, why, sizeof why) != BG_OK) {
        fprintf(stderr, "bench_mesh: terrain n = %d: %s\n", n, why);
        return false;
    }
    p->triangles = terrain.triangle_count;

    byte_counter bytes = {0, 0};
    bg_scene_desc sd = {0};
    sd.allocator.alloc = counted_alloc;
    sd.allocator.free = counted_free;
    sd.allocator.user = &bytes;
    bg_scene *scene = NULL;
    bg_status st = bg_scene_create(&sd, &scene);
    double t0 = bench_now_ms();
    if (st == BG_OK)
        st = build(scene, &terrain);
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    p->build_ms = bench_now_ms() - t0;
    mesh_free(&terrain); /* the scene holds its own copy */
    p->scene_bytes = bytes.live;
    if (st != BG_OK) {
        fprintf(stderr, "bench_mesh: terrain n = %d: %s\n", n, scene ? bg_scene_error_message(scene) : "no scene");
        bg_scene_destroy(scene);
        return false;
    }

    bg_image img;
    bool ok = bench_image_alloc(&img, side, side, BG_PIXEL_RGBA8);
    bg_render_settings set = bg_render_settings_init();
    set.max_depth = 0;
    ok = ok && bench_time_cpu(scene, &set, &img, runs, &p->cpu);
    if (ok && gpu) {
        bg_renderer_desc rd = {0};
        bg_renderer *r = bench_gpu_renderer(gpu, rd);
        if (r && bg_render_gpu(r, scene, &set, &img) == BG_OK) {
            p->gpu_ran = bench_time_gpu(r, scene, &set, &img, runs, &p->gpu);
        } else if (r) {
            /* Said, not hidden: the table shows what the GPU renderer answers for meshes. */
            snprintf(p->gpu_note, sizeof p->gpu_note, "%s", bg_renderer_error_message(r));
        }
        bg_renderer_destroy(r);
    }
    bench_image_free(&img);
    bg_scene_destroy(scene);
    return ok;
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
    bench_print_setup(stdout, have_gpu ? &gpu : NULL, runs);
    printf("\nTerrain meshes, %dx%d, 2 point lights with shadows, no bounces: the CPU reference and the GPU "
           "renderer (BG_PLAN_AUTO), medians [min-max]\n", side, side);
    printf("%10s %12s %10s %20s %s\n", "triangles", "build ms", "scene MB", "CPU ms", "GPU");

    char path[1024];
    snprintf(path, sizeof path, "%s/mesh_scaling.csv", out_dir);
    FILE *csv = fopen(path, "w");
    if (!csv) {
        fprintf(stderr, "bench_mesh: cannot write %s\n", path);
        if (have_gpu)
            bench_gpu_close(&gpu);
        return 1;
    }
    fprintf(csv, "triangles,build_ms,scene_bytes,cpu_median_ms,cpu_min_ms,cpu_max_ms,gpu_median_ms\n");
    point pts[4];
    int done = 0;
    for (int i = 0; i < count; i++) {
        bench_progress("terrain n = %d", ns[i]);
        if (!run_point(have_gpu ? &gpu : NULL, ns[i], side, runs, &pts[i]))
            break;
        point *p = &pts[i];
        char gpu_text[200];
        if (p->gpu_ran)
            snprintf(gpu_text, sizeof gpu_text, "%.1f [%.0f-%.0f] ms, %.2fx the CPU's", p->gpu.median, p->gpu.min,
                     p->gpu.max, p->gpu.median / p->cpu.median);
        else
            snprintf(gpu_text, sizeof gpu_text, "not run: %s", p->gpu_note[0] ? p->gpu_note : "no GPU context");
        printf("%10u %12.1f %10.1f %9.1f [%.0f-%.0f]   %s\n", p->triangles, p->build_ms, p->scene_bytes / 1048576.0,
               p->cpu.median, p->cpu.min, p->cpu.max, gpu_text);
        fprintf(csv, "%u,%.3f,%zu,%.3f,%.3f,%.3f,%.3f\n", p->triangles, p->build_ms, p->scene_bytes,
                p->cpu.median, p->cpu.min, p->cpu.max, p->gpu_ran ? p->gpu.median : -1.0);
        done++;
    }
    fclose(csv);
    if (done >= 2) {
        const point *last = &pts[done - 1], *second = &pts[1];
        printf("\ntime(%u triangles) / time(%u triangles): CPU %.2f", last->triangles, second->triangles,
               last->cpu.median / second->cpu.median);
        if (last->gpu_ran && second->gpu_ran)
            printf(", GPU %.2f", last->gpu.median / second->gpu.median);
        printf("\n");
    }
    if (have_gpu)
        bench_gpu_close(&gpu);
    return done == count ? 0 : 1;
}
