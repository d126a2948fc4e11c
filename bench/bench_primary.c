/* Primary visibility: the fused tree plan's camera rays walked (BG_PRIMARY_WALK) against rasterised
 * (BG_PRIMARY_RASTER), in interleaved rounds on one renderer each, and which one BG_PRIMARY_AUTO
 * takes. Scenes: many_spheres with 64 and 1024 spheres, and a closed mesh (an icosphere) of 5120,
 * 81920 and 1310720 triangles filling most of the view; at 512x512 and 1024x1024.
 *
 * Usage: bench_primary [out_dir]   (BENCH_CASES picks cases: many_spheres64 many_spheres1024
 * icosphere5k icosphere82k icosphere1.3m, each at 512 and 1024; QUICK=1: 512 only, 3 rounds;
 * PHASES=1 prints each frame's phases). Writes out_dir/primary.csv. The ratio raster / walk below 1
 * is the stage's saving; AUTO's choice is printed beside it. */
#include <stdlib.h>
#include <string.h>

#include "lib/bench_select.h"
#include "lib/bench_util.h"
#include "scenes/meshes.h"
#include "scenes/scenes.h"

#define ROUNDS 5
#define QUICK_ROUNDS 3

typedef struct bench_case {
    const char *name;
    int spheres;   /* many_spheres with this many, or 0 */
    int ico_level; /* else an icosphere of 20 * 4^level triangles */
} bench_case;

static const bench_case cases[] = {
    {"many_spheres64", 64, 0}, {"many_spheres1024", 1024, 0}, {"icosphere5k", 0, 4}, {"icosphere82k", 0, 6},
    {"icosphere1.3m", 0, 8},
};
#define CASES (int)(sizeof cases / sizeof cases[0])

/* An icosphere of radius 1 seen from 3.2 away, one light and a dim ambient. */
static bg_scene *icosphere_scene(int level)
{
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_icosphere_desc d = {level, 0, true, false};
    char why[256];
    if (mesh_icosphere(&d, &m, why, sizeof why) != BG_OK) {
        fprintf(stderr, "icosphere: %s\n", why);
        return NULL;
    }
    bg_scene *s = NULL;
    if (bg_scene_create(NULL, &s) != BG_OK)
        return NULL;
    bg_material mat = bg_material_init();
    mat.base.reflectance.r = 0.8;
    mat.base.reflectance.g = 0.7;
    mat.base.reflectance.b = 0.3;
    uint32_t id, mid;
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(3.0, 4.0, 5.0);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.3, 0.6, 3.2);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    bg_mesh_desc md = bg_mesh_desc_init(0);
    bool ok = bg_scene_add_material(s, &mat, &mid) == BG_OK && bg_scene_add_light(s, &l, &id) == BG_OK &&
              bg_scene_set_camera(s, &c) == BG_OK;
    md.material = mid;
    md.positions = m.positions;
    md.vertex_count = m.vertex_count;
    md.indices = m.indices;
    md.triangle_count = m.triangle_count;
    md.normals = m.normals;
    ok = ok && bg_scene_add_mesh(s, &md, &id) == BG_OK && bg_scene_commit(s) == BG_OK;
    mesh_free(&m);
    if (!ok) {
        fprintf(stderr, "icosphere scene: %s\n", bg_scene_error_message(s));
        bg_scene_destroy(s);
        return NULL;
    }
    return s;
}

static bg_scene *scene_of(const bench_case *c)
{
    if (!c->spheres)
        return icosphere_scene(c->ico_level);
    scene_params p = {0};
    p.spheres = c->spheres;
    return bench_scene(SCENE_MANY_SPHERES, &p);
}

/* One frame's wall time, or a negative number on failure (printed). */
static double frame_ms(bg_renderer *r, bg_scene *s, bg_primary_visibility primary, bg_image *img, bool *raster)
{
    bg_render_settings set = bg_render_settings_init();
    set.gpu_plan = BG_PLAN_FUSED_TREE;
    set.primary = primary;
    set.gpu_timing = getenv("PHASES") != NULL;
    double t0 = bench_now_ms();
    if (bg_render_gpu(r, s, &set, img) != BG_OK) {
        fprintf(stderr, "render: %s\n", bg_renderer_error_message(r));
        return -1.0;
    }
    double ms = bench_now_ms() - t0;
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    *raster = st.primary_raster;
    if (set.gpu_timing)
        fprintf(stderr, "  %s: setup %.1f intersect %.1f resolve %.1f total %.1f\n", primary == BG_PRIMARY_WALK ? "walk" : "raster",
                st.phase_ms[BG_PHASE_SETUP], st.phase_ms[BG_PHASE_INTERSECT], st.phase_ms[BG_PHASE_RESOLVE], st.total_ms);
    return ms;
}

int main(int argc, char **argv)
{
    const char *out = bench_out_dir(argc, argv);
    bench_gpu gpu;
    if (!bench_gpu_open(&gpu))
        return 1;
    FILE *csv = bench_csv_open(out, "primary.csv", "case,size,walk_ms,raster_ms,ratio,auto_rasterises");
    if (!csv) {
        bench_gpu_close(&gpu);
        return 1;
    }
    int rounds = bench_quick() ? QUICK_ROUNDS : ROUNDS;
    static const int sizes[] = {512, 1024};
    int size_count = bench_quick() ? 1 : 2;
    bench_select_print(stdout);
    printf("GL: %s\n%-16s %5s %10s %10s %7s %5s\n", gpu.renderer_name, "case", "size", "walk ms", "raster ms", "ratio",
           "auto");
    int status = 0;
    for (int c = 0; c < CASES && !status; c++) {
        bool any = false;
        for (int z = 0; z < size_count; z++)
            any = bench_selected(cases[c].name, sizes[z]) || any;
        if (!any)
            continue;
        bg_scene *s = scene_of(&cases[c]);
        if (!s) {
            status = 1;
            break;
        }
        for (int z = 0; z < size_count && !status; z++) {
            int n = sizes[z];
            if (!bench_selected(cases[c].name, n))
                continue;
            bg_image img;
            bg_renderer *walk_r = bench_gpu_renderer(&gpu, (bg_renderer_desc){0});
            bg_renderer *raster_r = bench_gpu_renderer(&gpu, (bg_renderer_desc){0});
            if (!walk_r || !raster_r || !bench_image_alloc(&img, n, n, BG_PIXEL_RGBA8)) {
                bg_renderer_destroy(walk_r);
                bg_renderer_destroy(raster_r);
                status = 1;
                break;
            }
            double walk[ROUNDS], raster[ROUNDS];
            bool used = false, auto_raster = false;
            /* A first frame each compiles the programs and uploads the scene. */
            if (frame_ms(walk_r, s, BG_PRIMARY_WALK, &img, &used) < 0 ||
                frame_ms(raster_r, s, BG_PRIMARY_RASTER, &img, &used) < 0)
                status = 1;
            for (int k = 0; k < rounds && !status; k++) {
                walk[k] = frame_ms(walk_r, s, BG_PRIMARY_WALK, &img, &used);
                raster[k] = frame_ms(raster_r, s, BG_PRIMARY_RASTER, &img, &used);
                status = walk[k] < 0 || raster[k] < 0;
            }
            if (!status && frame_ms(raster_r, s, BG_PRIMARY_AUTO, &img, &auto_raster) < 0)
                status = 1;
            if (!status) {
                bench_times w = bench_times_of(walk, rounds), ra = bench_times_of(raster, rounds);
                printf("%-16s %5d %10.1f %10.1f %7.3f %5s\n", cases[c].name, n, w.median, ra.median,
                       ra.median / w.median, auto_raster ? "R" : "W");
                fprintf(csv, "%s,%d,%.3f,%.3f,%.4f,%d\n", cases[c].name, n, w.median, ra.median, ra.median / w.median,
                        auto_raster ? 1 : 0);
                fflush(stdout);
            }
            bench_image_free(&img);
            bg_renderer_destroy(walk_r);
            bg_renderer_destroy(raster_r);
        }
        bg_scene_destroy(s);
    }
    fclose(csv);
    bench_gpu_close(&gpu);
    if (!bench_select_check("bench_primary", "many_spheres64 many_spheres1024 icosphere5k icosphere82k icosphere1.3m"))
        return 2;
    return status;
}
