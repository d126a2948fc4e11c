/* Triangle meshes on the GPU (docs/gpu_pipeline.md "Meshes"): every plan's image against the CPU
 * reference on an icosphere, a self-shadowing torus knot, instances of one mesh beside analytic
 * shapes, the bunny, glass, textured and anisotropic meshes; no holes inside the icosphere's
 * silhouette; walks that run out go to the CPU; a camera move compiles nothing. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "scenes/meshes.h"
#include "scenes/ply_mesh.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 96, H = 96 };

/* Bounds (largest channel error, mean channel error, share of pixels off by more than 8), measured
 * on Mesa 22.3 llvmpipe (OSMesa) at 96x96 against the CPU reference: most scenes within 1/255, the
 * bunny 17 and the glass 15 on one pixel each where float and double pick different sides of an
 * edge (mean 0.002 and 0.0045, 1 pixel in 9216 over 8). Bounds leave about twice that, with floors
 * for another CPU's rounding: a shadow lost or a hole costs far more. */
#define CLOSE_MAX 16
#define CLOSE_MEAN 0.02
#define CLOSE_OVER 0.001
#define EDGE_MAX 48
#define EDGE_MEAN 0.03
#define EDGE_OVER 0.003

static bg_scene *new_scene(void)
{
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    const double a[3] = {0.05, 0.05, 0.05};
    assert_int_equal(bg_scene_set_ambient(scene, a), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(3.0, 4.0, 5.0);
    uint32_t id;
    assert_int_equal(bg_scene_add_light(scene, &l, &id), BG_OK);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.3, 0.6, 3.2);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    c.fov_y_degrees = 45.0;
    assert_int_equal(bg_scene_set_camera(scene, &c), BG_OK);
    return scene;
}

static uint32_t material(bg_scene *scene, double r, double g, double b, double mirror)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    m.base.roughness.value = mirror > 0.0 ? 0.0 : 1.0; /* a mirror, or Lambertian */
    uint32_t id = 0;
    assert_int_equal(bg_scene_add_material(scene, &m, &id), BG_OK);
    return id;
}

static uint32_t add_mesh(bg_scene *scene, const mesh *m, uint32_t mat, bg_mat4 transform)
{
    bg_mesh_desc d = bg_mesh_desc_init(mat);
    d.positions = m->positions;
    d.vertex_count = m->vertex_count;
    d.indices = m->indices;
    d.triangle_count = m->triangle_count;
    d.normals = m->normals;
    d.uvs = m->uvs;
    d.transform = transform;
    uint32_t id = 0;
    if (bg_scene_add_mesh(scene, &d, &id) != BG_OK)
        fail_msg("bg_scene_add_mesh: %s", bg_scene_error_message(scene));
    return id;
}

static mesh icosphere(int level, bool normals)
{
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_icosphere_desc d = {level, 0, normals, false};
    char why[256];
    if (mesh_icosphere(&d, &m, why, sizeof why) != BG_OK)
        fail_msg("icosphere: %s", why);
    return m;
}

static mesh terrain(int n, double amplitude, bool normals)
{
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_heightfield_desc d = {n, amplitude, normals, false};
    char why[256];
    if (mesh_heightfield(&d, &m, why, sizeof why) != BG_OK)
        fail_msg("terrain: %s", why);
    return m;
}

static void commit(bg_scene *scene)
{
    if (bg_scene_commit(scene) != BG_OK)
        fail_msg("bg_scene_commit: %s", bg_scene_error_message(scene));
}

static bg_render_settings tree_settings(void)
{
    bg_render_settings s = bg_render_settings_init();
    s.gpu_plan = BG_PLAN_FUSED_TREE;
    s.threads = 2;
    return s;
}

/* Errors of the GPU image against the CPU one. */
typedef struct diff {
    int max;
    double mean, over; /* mean channel error; share of pixels with a channel off by more than 8 */
    int holes;         /* background on the GPU where the CPU pixel and its 8 neighbours are not */
} diff;

static bool is_bg(const unsigned char *p)
{
    return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

static diff compare(const unsigned char *cpu, const unsigned char *gpu, int w, int h)
{
    diff d = {0, 0.0, 0.0, 0};
    long sum = 0, over = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *c = cpu + 4 * (y * w + x), *g = gpu + 4 * (y * w + x);
            int worst = 0;
            for (int k = 0; k < 3; k++) {
                int e = abs((int)c[k] - (int)g[k]);
                sum += e;
                worst = e > worst ? e : worst;
            }
            d.max = worst > d.max ? worst : d.max;
            over += worst > 8;
            bool inside = x > 0 && y > 0 && x + 1 < w && y + 1 < h;
            for (int dy = -1; dy <= 1 && inside; dy++)
                for (int dx = -1; dx <= 1 && inside; dx++)
                    inside = !is_bg(cpu + 4 * ((y + dy) * w + x + dx));
            d.holes += inside && is_bg(g);
        }
    d.mean = (double)sum / (3.0 * w * h);
    d.over = (double)over / (w * h);
    return d;
}

/* The plans every mesh scene is checked on besides the tree plan: each with a renderer of its own,
 * so that the tree plan's renderer keeps its program between a test's frames. */
static const bg_gpu_plan other_plans[] = {BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
#define OTHER_PLANS ((int)(sizeof other_plans / sizeof other_plans[0]))

static const char *plan_name(bg_gpu_plan p)
{
    return p == BG_PLAN_FUSED_TREE ? "tree" : p == BG_PLAN_FUSED ? "fused" : "multipass";
}

/* The worse of two comparisons in every measure. */
static diff worst(diff a, diff b)
{
    diff d = {a.max > b.max ? a.max : b.max, a.mean > b.mean ? a.mean : b.mean, a.over > b.over ? a.over : b.over,
              a.holes > b.holes ? a.holes : b.holes};
    return d;
}

/* The frame of one plan on r against the CPU image; fails on a render error or another plan run. */
static diff plan_vs_cpu(bg_renderer *r, bg_scene *s, bg_gpu_plan plan, const unsigned char *cpu, const char *label,
                        int w, int h, bg_render_stats *stats)
{
    bg_render_settings set = tree_settings();
    set.gpu_plan = plan;
    unsigned char *gpu = malloc(4 * w * h);
    assert_non_null(gpu);
    bg_image img = {w, h, BG_PIXEL_RGBA8, 0, gpu};
    util_render_gpu(r, util_fx.ctx, s, &set, &img, label);
    bg_renderer_get_stats(r, stats);
    assert_int_equal(stats->plan, plan);
    diff d = compare(cpu, gpu, w, h);
    print_message("%s (%s): max %d mean %.4f over8 %.4f holes %d fallback %llu\n", label, plan_name(plan), d.max,
                  d.mean, d.over, d.holes, (unsigned long long)stats->fallback_pixels);
    free(gpu);
    return d;
}

/* The CPU pixels of the last gpu_vs_cpu's frames: the tree plan's, then other_plans'. */
static uint64_t fallback[1 + OTHER_PLANS];

/* Every plan's frame of w x h against the CPU reference: the worst of them; stats get the tree
 * plan's, rendered on r. */
static diff gpu_vs_cpu_at(bg_renderer *r, bg_scene *s, const char *label, int w, int h, bg_render_stats *stats)
{
    bg_render_settings set = tree_settings();
    unsigned char *cpu = util_cpu_reference(s, &set, w, h);
    diff d = plan_vs_cpu(r, s, BG_PLAN_FUSED_TREE, cpu, label, w, h, stats);
    fallback[0] = stats->fallback_pixels;
    for (int k = 0; k < OTHER_PLANS; k++) {
        bg_renderer *other = util_renderer(util_fx.ctx);
        bg_render_stats own;
        d = worst(d, plan_vs_cpu(other, s, other_plans[k], cpu, label, w, h, &own));
        fallback[1 + k] = own.fallback_pixels;
        bg_renderer_destroy(other);
    }
    free(cpu);
    return d;
}

/* The same at the suite's W x H. */
static diff gpu_vs_cpu(bg_renderer *r, bg_scene *s, const char *label, bg_render_stats *stats)
{
    return gpu_vs_cpu_at(r, s, label, W, H, stats);
}

/* A mean bound; under a profile without float32 blending the multipass sums in RGBA16F, and the error
 * model's wider mean holds (gpu_threshold_half_accumulation in gpu_thresholds.h). */
static double mean_bound(double mean)
{
    return util_half_accumulation() && mean < 0.06 ? 0.06 : mean;
}

static void expect_close(diff d, int max, double mean, double over)
{
    mean = mean_bound(mean);
    assert_int_equal(d.holes, 0);
    assert_true(d.max <= max);
    assert_true(d.mean <= mean);
    assert_true(d.over <= over);
}

static void icosphere_matches_cpu(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m = icosphere(4, true);
    add_mesh(s, &m, material(s, 0.8, 0.5, 0.3, 0.0), bg_mat4_identity());
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    diff d = gpu_vs_cpu(r, s, "icosphere 5120 smooth", &st);
    expect_close(d, CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    /* Only the camera moves: the program stays. */
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(-0.4, 0.2, 3.0);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    c.fov_y_degrees = 45.0;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    commit(s);
    d = gpu_vs_cpu(r, s, "icosphere, camera moved", &st);
    assert_int_equal(st.programs_compiled, 0);
    expect_close(d, CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

static void faceted_icosphere_matches_cpu(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m = icosphere(2, false);
    add_mesh(s, &m, material(s, 0.3, 0.7, 0.4, 0.0), bg_mat4_scale(1.2, 0.8, 1.0));
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    expect_close(gpu_vs_cpu(r, s, "icosphere 320 faceted", &st), CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

static void torus_knot_shadows_itself(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_torus_knot_desc kd = {2, 3, 128, 12, true, false};
    char why[256];
    if (mesh_torus_knot(&kd, &m, why, sizeof why) != BG_OK)
        fail_msg("torus knot: %s", why);
    add_mesh(s, &m, material(s, 0.9, 0.9, 0.9, 0.0), bg_mat4_scale(0.8, 0.8, 0.8));
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    expect_close(gpu_vs_cpu(r, s, "torus knot", &st), CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* The multipass's own options on a mesh scene: every skip switched off (generic shaders, passes
 * over dead pixels, one object per pass), and a half-float G-buffer, which BG_PLAN_AUTO renders
 * with the multipass. The knot shadows itself beside a sphere and over a plane. */
static void multipass_options_with_meshes(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_torus_knot_desc kd = {2, 3, 96, 10, true, false};
    char why[256];
    if (mesh_torus_knot(&kd, &m, why, sizeof why) != BG_OK)
        fail_msg("torus knot: %s", why);
    uint32_t grey = material(s, 0.8, 0.8, 0.8, 0.0), id = 0;
    add_mesh(s, &m, grey, bg_mat4_scale(0.7, 0.7, 0.7));
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0.9, 0.5, 0.2), 0.3, material(s, 0.9, 0.9, 0.9, 1.0), &id),
                     BG_OK);
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0.0, -0.8, 0.0), bg_vec3_make(0.0, 1.0, 0.0), grey, &id), BG_OK);
    commit(s);
    bg_render_settings set = tree_settings();
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    set.gpu_plan = BG_PLAN_MULTIPASS;
    set.gpu_disable_skips = BG_SKIP_ALL;
    unsigned char *gpu = malloc(4 * W * H);
    assert_non_null(gpu);
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, gpu};
    util_render_gpu(r, util_fx.ctx, s, &set, &img, "knot, every skip off");
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.plan, BG_PLAN_MULTIPASS);
    diff d = compare(cpu, gpu, W, H);
    print_message("knot, every skip off: max %d mean %.4f over8 %.4f holes %d\n", d.max, d.mean, d.over, d.holes);
    expect_close(d, CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    bg_renderer_destroy(r);

    bg_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.context = util_fx.ctx;
    rd.half_gbuffer = true;
    char message[256];
    assert_int_equal(bg_renderer_create(&rd, &r, message, sizeof message), BG_OK);
    bg_render_settings automatic = tree_settings();
    automatic.gpu_plan = BG_PLAN_AUTO;
    util_render_gpu(r, util_fx.ctx, s, &automatic, &img, "knot, half G-buffer");
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.plan, BG_PLAN_MULTIPASS);
    d = compare(cpu, gpu, W, H);
    print_message("knot, half G-buffer (%d half targets): max %d mean %.4f over8 %.4f holes %d\n",
                  st.gbuffer_half_targets, d.max, d.mean, d.over, d.holes);
    /* Half normals and reflectances round at 2^-11: measured max 2, mean 0.021 (1/255 units). */
    expect_close(d, CLOSE_MAX, 0.05, CLOSE_OVER);
    bg_renderer_destroy(r);
    free(gpu);
    free(cpu);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* The frame of plan on r, w x h, RGBA8; the caller frees it. */
static unsigned char *frame_of(bg_renderer *r, bg_scene *s, bg_gpu_plan plan, int w, int h, const char *label)
{
    bg_render_settings set = tree_settings();
    set.gpu_plan = plan;
    unsigned char *px = malloc(4 * (size_t)w * (size_t)h);
    assert_non_null(px);
    bg_image img = {w, h, BG_PIXEL_RGBA8, 0, px};
    util_render_gpu(r, util_fx.ctx, s, &set, &img, label);
    return px;
}

/* The mesh trees go up ordered for the camera's octant around the mesh (shared/meshes.c). Small
 * moves across a centre plane keep the order and upload no node texture; a camera move to the far
 * side rewrites the node texture in place with the other order, and only it. The frame after it
 * equals, byte for byte, a fresh renderer's frame of the same commit (which uploads that order at
 * once), on the tree plan and on the multipass, whose passes keep their bindings and compile
 * nothing; and it stays within the suite's bounds of the CPU. Two instances share one order. */
static void mesh_order_follows_the_camera(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m = icosphere(4, false);
    uint32_t mat = material(s, 0.8, 0.5, 0.3, 0.2);
    uint32_t first = add_mesh(s, &m, mat, bg_mat4_mul(bg_mat4_translate(-0.5, 0.0, 0.0), bg_mat4_scale(0.6, 0.6, 0.6)));
    bg_mat4 t = bg_mat4_mul(bg_mat4_translate(0.6, 0.1, -0.3), bg_mat4_scale(0.5, 0.5, 0.5));
    uint32_t id;
    assert_int_equal(bg_scene_add_mesh_instance(s, first, &t, material(s, 0.2, 0.4, 0.9, 0.0), true, &id), BG_OK);
    commit(s);
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
    /* RGBA32F texels of the tree (5n - 2) and of the triangles (6 each) */
    const uint64_t node_bytes = (5 * (uint64_t)m.triangle_count - 2) * 16;
    const uint64_t triangle_bytes = 6 * (uint64_t)m.triangle_count * 16;
    for (int k = 0; k < 2; k++) {
        bg_camera c = bg_camera_init();
        c.position = bg_vec3_make(0.3, 0.6, 3.2);
        c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
        c.fov_y_degrees = 45.0;
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        commit(s);
        bg_renderer *r = util_renderer(util_fx.ctx);
        free(frame_of(r, s, plans[k], W, H, "mesh order, front"));
        /* Across the first mesh's centre plane x = -0.5 (0.05 in its object space, within an eighth
         * of its extent of 2): the order and the node texture stay. */
        c.position = bg_vec3_make(-0.47, 0.6, 3.2);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        commit(s);
        free(frame_of(r, s, plans[k], W, H, "mesh order, over the centre"));
        c.position = bg_vec3_make(-0.53, 0.6, 3.2);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        commit(s);
        free(frame_of(r, s, plans[k], W, H, "mesh order, just across the centre"));
        bg_render_stats st;
        bg_renderer_get_stats(r, &st);
        if (st.gl_work.upload_bytes >= node_bytes)
            fail_msg("%s: %llu bytes uploaded after a move within the margin", plan_name(plans[k]),
                     (unsigned long long)st.gl_work.upload_bytes);
        c.position = bg_vec3_make(-0.4, -0.5, -3.1);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        commit(s);
        unsigned char *moved = frame_of(r, s, plans[k], W, H, "mesh order, camera behind");
        bg_renderer_get_stats(r, &st);
        assert_int_equal(st.programs_compiled, 0);
        /* The node texture again, rows padded to at most 4096 texels, and not the triangles. */
        if (st.gl_work.upload_bytes < node_bytes || st.gl_work.upload_bytes >= node_bytes + 4096 * 16 + triangle_bytes)
            fail_msg("%s: %llu bytes uploaded after the order changed, not the node texture's %llu alone",
                     plan_name(plans[k]), (unsigned long long)st.gl_work.upload_bytes, (unsigned long long)node_bytes);
        bg_renderer *fresh = util_renderer(util_fx.ctx);
        unsigned char *once = frame_of(fresh, s, plans[k], W, H, "mesh order, fresh renderer");
        if (memcmp(moved, once, 4 * (size_t)W * H) != 0)
            fail_msg("%s: the frame after the reorder differs from a fresh renderer's", plan_name(plans[k]));
        bg_render_settings set = tree_settings();
        unsigned char *cpu = util_cpu_reference(s, &set, W, H);
        diff d = compare(cpu, moved, W, H);
        print_message("mesh order (%s): max %d mean %.4f over8 %.4f\n", plan_name(plans[k]), d.max, d.mean, d.over);
        expect_close(d, CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
        free(cpu);
        free(once);
        free(moved);
        bg_renderer_destroy(fresh);
        bg_renderer_destroy(r);
    }
    mesh_free(&m);
    bg_scene_destroy(s);
}

static void instances_and_spheres_match_cpu(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m = icosphere(3, true);
    uint32_t mat = material(s, 0.8, 0.8, 0.2, 0.0);
    uint32_t first = add_mesh(s, &m, mat, bg_mat4_mul(bg_mat4_translate(-0.7, 0.0, 0.0), bg_mat4_scale(0.4, 0.4, 0.4)));
    uint32_t id;
    bg_mat4 t = bg_mat4_mul(bg_mat4_translate(0.7, 0.0, 0.0), bg_mat4_scale(0.4, 0.4, 0.4));
    assert_int_equal(bg_scene_add_mesh_instance(s, first, &t, material(s, 0.2, 0.4, 0.9, 0.3), true, &id), BG_OK);
    t = bg_mat4_mul(bg_mat4_translate(0.0, 0.6, -0.5), bg_mat4_scale(0.3, 0.3, 0.3));
    assert_int_equal(bg_scene_add_mesh_instance(s, first, &t, mat, true, &id), BG_OK);
    bg_object_desc sp = bg_object_desc_init(BG_SHAPE_SPHERE, material(s, 0.9, 0.2, 0.2, 0.0));
    sp.transform = bg_mat4_mul(bg_mat4_translate(0.0, -0.1, 0.3), bg_mat4_scale(0.25, 0.25, 0.25));
    assert_int_equal(bg_scene_add_object(s, &sp, &id), BG_OK);
    bg_object_desc pl = bg_object_desc_init(BG_SHAPE_PLANE, material(s, 0.6, 0.6, 0.6, 0.0));
    pl.transform = bg_mat4_translate(0.0, -0.45, 0.0);
    assert_int_equal(bg_scene_add_object(s, &pl, &id), BG_OK);
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    expect_close(gpu_vs_cpu(r, s, "instances, sphere, plane, mirror", &st), CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* Stacked thin annular fins (24 of them, 0.02 thick and 0.1 apart, like an engine's cooling fins),
 * built 100 times too large and shown through three instances scaled by 1/100, each fin shadowing
 * the next under a high light. A leaving ray's float offset lifts the shadow ray's start off the
 * surface towards the fin above it, moving every shadow edge the same way: with 256 float ulps of
 * the point this gave 11 isolated pixels darker on the GPU than on the CPU at 320x240 and none
 * lighter (2CylinderEngine.glb's "speckles"); with 16 ulps (docs/shading.md 2.10), none. */
static void fins(mesh *m)
{
    enum { FINS = 24, SEG = 48 };
    const double r1 = 50.0, r2 = 100.0, thick = 2.0, gap = 10.0;
    char why[128];
    assert_int_equal(mesh_alloc(m, FINS * SEG * 4, FINS * SEG * 8, false, false, "fins", why, sizeof why), BG_OK);
    uint32_t t = 0;
    for (int k = 0; k < FINS; k++)
        for (int i = 0; i < SEG; i++) {
            double a = 2.0 * 3.14159265358979323846 * i / SEG;
            const double rad[4] = {r1, r2, r1, r2}, y[4] = {k * gap, k * gap, k * gap + thick, k * gap + thick};
            for (int c = 0; c < 4; c++) {
                float *p = &m->positions[3 * ((k * SEG + i) * 4 + c)];
                p[0] = (float)(rad[c] * cos(a));
                p[1] = (float)y[c];
                p[2] = (float)(rad[c] * sin(a));
            }
            uint32_t A = (uint32_t)((k * SEG + i) * 4), B = (uint32_t)((k * SEG + (i + 1) % SEG) * 4);
            /* bottom, top, outer rim, inner rim; counter-clockwise from outside */
            const uint32_t tri[8][3] = {{A, A + 1, B + 1}, {A, B + 1, B},         {A + 2, B + 3, A + 3},
                                        {A + 2, B + 2, B + 3}, {A + 1, A + 3, B + 3}, {A + 1, B + 3, B + 1},
                                        {A, B + 2, A + 2},     {A, B, B + 2}};
            for (int j = 0; j < 8; j++, t++)
                memcpy(&m->indices[3 * t], tri[j], sizeof tri[j]);
        }
}

static void thin_instanced_fins_keep_their_shadow_edges(void **state)
{
    (void)state;
    enum { FW = 320, FH = 240 };
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    const double a[3] = {0.15, 0.15, 0.15};
    assert_int_equal(bg_scene_set_ambient(s, a), BG_OK);
    bg_light l = bg_light_init();
    uint32_t id;
    l.position = bg_vec3_make(2, 8, 5);
    l.intensity = 0.9;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    l.position = bg_vec3_make(-5, 3, -2);
    l.intensity = 0.4;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(3.5, 2.8, 4.5);
    c.look_at = bg_vec3_make(0.0, 1.0, 0.0);
    c.fov_y_degrees = 40.0;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    bg_material metal = bg_material_init();
    metal.base.reflectance = (bg_color_param){0.7, 0.7, 0.72, 0};
    metal.base.roughness.value = 0.5;
    uint32_t mat;
    assert_int_equal(bg_scene_add_material(s, &metal, &mat), BG_OK);
    mesh m = {0};
    fins(&m);
    const double place[3][4] = {{-1.2, 0, 0, 0}, {1.2, 0, 0, 30}, {0, 0, -1.5, 75}};
    uint32_t first = 0;
    for (int k = 0; k < 3; k++) {
        bg_mat4 t = bg_mat4_mul(bg_mat4_translate(place[k][0], place[k][1], place[k][2]),
                                bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 0, 0.3), place[k][3]),
                                            bg_mat4_scale(0.01, 0.01, 0.01)));
        if (k == 0)
            first = add_mesh(s, &m, mat, t);
        else
            assert_int_equal(bg_scene_add_mesh_instance(s, first, &t, mat, true, &id), BG_OK);
    }
    bg_object_desc pl = bg_object_desc_init(BG_SHAPE_PLANE, material(s, 0.5, 0.5, 0.5, 0.0));
    pl.transform = bg_mat4_translate(0.0, -0.2, 0.0);
    assert_int_equal(bg_scene_add_object(s, &pl, &id), BG_OK);
    commit(s);
    bg_render_settings set = tree_settings();
    unsigned char *cpu = util_cpu_reference(s, &set, FW, FH);
    unsigned char *gpu = malloc(4 * FW * FH);
    assert_non_null(gpu);
    bg_image img = {FW, FH, BG_PIXEL_RGBA8, 0, gpu};
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &img, "thin fins");
    int darker = 0, lighter = 0;
    for (int i = 0; i < FW * FH; i++) {
        int d = 0;
        for (int k = 0; k < 3; k++)
            d += (int)gpu[4 * i + k] - (int)cpu[4 * i + k];
        darker += d < -3 * 24;
        lighter += d > 3 * 24;
    }
    print_message("thin fins %dx%d: %d pixels darker on the GPU, %d lighter (by more than 24 a channel)\n", FW, FH,
                  darker, lighter);
    /* Float and double may still split a shadow edge differently at a pixel or two, either way. */
    assert_true(darker <= 2);
    assert_true(lighter <= 2);
    free(gpu);
    free(cpu);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* Pixels seen through a very narrow camera aimed at a terrain vertex (where six triangles meet, the
 * hit points are as near to the neighbours as they get, within a few float ulps), lit by a sun that
 * no part of the terrain hides there: the GPU image matches the CPU's, no pixel shadowed by a
 * neighbour triangle, at every scale and far from the origin (the float offset, docs/shading.md 2.10). */
static void leaving_rays_miss_the_neighbours(void **state)
{
    (void)state;
    enum { N = 24 };
    mesh m = terrain(64, 0.05, true); /* smooth: a pixel off is a shadow, not the other facet */
    const double scales[3] = {1.0, 1e-3, 1e4};
    const double shifts[2] = {0.0, 1e3};
    bg_renderer *r = util_renderer(util_fx.ctx);
    int total = 0, pixels = 0;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < 2; j++) {
            double sc = scales[k], shift = shifts[j] * sc;
            bg_scene *s = NULL;
            assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
            const double none[3] = {0, 0, 0};
            assert_int_equal(bg_scene_set_ambient(s, none), BG_OK);
            bg_light l = bg_light_init();
            l.type = BG_LIGHT_DIRECTIONAL;
            l.direction = bg_vec3_make(0.2, -1.0, 0.1); /* towards the ground: the sun at (-0.2, 1, -0.1) */
            uint32_t id;
            assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
            add_mesh(s, &m, material(s, 0.9, 0.9, 0.9, 0.0),
                     bg_mat4_mul(bg_mat4_translate(shift, -0.5 * shift, 0.25 * shift), bg_mat4_scale(sc, sc, sc)));
            commit(s);
            int bad = 0;
            for (uint32_t v = 0; v < m.vertex_count; v += 397) {
                uint32_t row = v / 65, column = v % 65; /* (n + 1)^2 vertices, row by row */
                if (row == 0 || column == 0 || row == 64 || column == 64)
                    continue; /* the open boundary: a silhouette, not a neighbour */
                const float *p = &m.positions[3 * v];
                double at[3] = {p[0] * sc + shift, p[1] * sc - 0.5 * shift, p[2] * sc + 0.25 * shift};
                bg_camera c = bg_camera_init();
                c.position = bg_vec3_make(at[0] + 0.3 * sc, at[1] + sc, at[2] + 0.2 * sc);
                c.look_at = bg_vec3_make(at[0], at[1], at[2]);
                c.fov_y_degrees = 2e-4; /* about 40 float ulps of the point across the image */
                assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
                commit(s);
                bg_render_settings set = tree_settings();
                unsigned char *cpu = util_cpu_reference(s, &set, N, N);
                unsigned char gpu[4 * N * N];
                bg_image img = {N, N, BG_PIXEL_RGBA8, 0, gpu};
                util_render_gpu(r, util_fx.ctx, s, &set, &img, "terrain vertex");
                for (int i = 0; i < N * N; i++) {
                    int e = 0;
                    for (int c3 = 0; c3 < 3; c3++)
                        e = abs((int)cpu[4 * i + c3] - (int)gpu[4 * i + c3]) > e ? abs((int)cpu[4 * i + c3] - (int)gpu[4 * i + c3]) : e;
                    bad += e > 8;
                }
                pixels += N * N;
                free(cpu);
            }
            print_message("terrain vertices at scale %g, shift %g: %d pixels off\n", sc, shift, bad);
            total += bad;
            bg_scene_destroy(s);
        }
    print_message("terrain vertices: %d of %d pixels off\n", total, pixels);
    assert_int_equal(total, 0);
    bg_renderer_destroy(r);
    mesh_free(&m);
}

static void bunny_matches_cpu(void **state)
{
    (void)state;
    mesh m;
    memset(&m, 0, sizeof m);
    char why[256];
    if (ply_mesh_read("tests/data/bunny.ply", &m, why, sizeof why) != BG_OK)
        fail_msg("%s", why);
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < m.vertex_count; v++)
        for (int i = 0; i < 3; i++) {
            lo[i] = fminf(lo[i], m.positions[3 * v + i]);
            hi[i] = fmaxf(hi[i], m.positions[3 * v + i]);
        }
    double c[3], size = 0;
    for (int i = 0; i < 3; i++) {
        c[i] = 0.5 * (lo[i] + hi[i]);
        size = fmax(size, hi[i] - lo[i]);
    }
    bg_scene *s = new_scene();
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(c[0] + size, c[1] + 2 * size, c[2] + 3 * size);
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(c[0] + 0.5 * size, c[1] + 0.3 * size, c[2] + 2.2 * size);
    cam.look_at = bg_vec3_make(c[0], c[1], c[2]);
    cam.fov_y_degrees = 40.0;
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    add_mesh(s, &m, material(s, 0.85, 0.8, 0.75, 0.0), bg_mat4_identity());
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    expect_close(gpu_vs_cpu(r, s, "bunny", &st), EDGE_MAX, EDGE_MEAN, EDGE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* A glass icosphere (a mesh) in front of a sphere and a plane: rays enter and leave the mesh. */
static void glass_mesh_matches_cpu(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m = icosphere(3, true);
    bg_material glass = bg_material_init();
    glass.base.reflectance.r = glass.base.reflectance.g = glass.base.reflectance.b = 0.04;
    glass.base.roughness.value = 0.0;
    glass.transparency.value = 0.9;
    glass.ior = 1.5;
    uint32_t gm;
    assert_int_equal(bg_scene_add_material(s, &glass, &gm), BG_OK);
    add_mesh(s, &m, gm, bg_mat4_mul(bg_mat4_translate(0.0, 0.0, 0.8), bg_mat4_scale(0.5, 0.5, 0.5)));
    uint32_t id;
    bg_object_desc sp = bg_object_desc_init(BG_SHAPE_SPHERE, material(s, 0.9, 0.2, 0.2, 0.0));
    sp.transform = bg_mat4_mul(bg_mat4_translate(0.3, 0.0, -0.8), bg_mat4_scale(0.4, 0.4, 0.4));
    assert_int_equal(bg_scene_add_object(s, &sp, &id), BG_OK);
    bg_object_desc pl = bg_object_desc_init(BG_SHAPE_PLANE, material(s, 0.3, 0.6, 0.3, 0.0));
    pl.transform = bg_mat4_translate(0.0, -0.5, 0.0);
    assert_int_equal(bg_scene_add_object(s, &pl, &id), BG_OK);
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    expect_close(gpu_vs_cpu(r, s, "glass icosphere", &st), EDGE_MAX, EDGE_MEAN, EDGE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* A checker texture through the mesh's own UVs, scaled by the object's uv_scale. */
static void textured_mesh_matches_cpu(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_icosphere_desc d = {3, 0, true, true};
    char why[256];
    if (mesh_icosphere(&d, &m, why, sizeof why) != BG_OK)
        fail_msg("icosphere: %s", why);
    enum { T = 8 };
    float texels[T * T * 4];
    for (int i = 0; i < T * T; i++) {
        float v = ((i % T) + (i / T)) % 2 ? 1.0f : 0.2f;
        texels[4 * i] = v;
        texels[4 * i + 1] = 0.5f * v;
        texels[4 * i + 2] = 0.2f;
        texels[4 * i + 3] = 1.0f;
    }
    bg_image img = {T, T, BG_PIXEL_RGBA32F, 0, texels};
    uint32_t tex;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &tex), BG_OK);
    bg_material mat = bg_material_init();
    mat.base.reflectance.r = mat.base.reflectance.g = mat.base.reflectance.b = 1.0;
    mat.base.reflectance.texture = tex;
    uint32_t mid;
    assert_int_equal(bg_scene_add_material(s, &mat, &mid), BG_OK);
    add_mesh(s, &m, mid, bg_mat4_identity());
    commit(s);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    expect_close(gpu_vs_cpu(r, s, "textured icosphere", &st), CLOSE_MAX, CLOSE_MEAN, CLOSE_OVER);
    bg_renderer_destroy(r);
    mesh_free(&m);
    bg_scene_destroy(s);
}

/* An anisotropic material on a knot with UVs: the tangent follows the UVs' u direction (along the
 * knot); without UVs it falls back as on the CPU. */
static void anisotropic_mesh_matches_cpu(void **state)
{
    (void)state;
    unsigned char *images[2] = {NULL, NULL};
    for (int uvs = 0; uvs < 2; uvs++) {
        bg_scene *s = new_scene();
        mesh m;
        memset(&m, 0, sizeof m);
        mesh_torus_knot_desc kd = {2, 3, 128, 12, true, uvs == 1};
        char why[256];
        if (mesh_torus_knot(&kd, &m, why, sizeof why) != BG_OK)
            fail_msg("torus knot: %s", why);
        bg_material mat = bg_material_init();
        mat.base.reflectance.r = 0.9;
        mat.base.reflectance.g = 0.7;
        mat.base.reflectance.b = 0.3;
        mat.base.roughness.value = 0.6;
        mat.base.isotropy.value = 0.1;
        uint32_t mid;
        assert_int_equal(bg_scene_add_material(s, &mat, &mid), BG_OK);
        add_mesh(s, &m, mid, bg_mat4_scale(0.8, 0.8, 0.8));
        commit(s);
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_stats st;
        expect_close(gpu_vs_cpu(r, s, uvs ? "anisotropic knot, uvs" : "anisotropic knot, no uvs", &st), CLOSE_MAX,
                     CLOSE_MEAN, CLOSE_OVER);
        /* The tangent matters: the two variants' images differ. */
        bg_render_settings set = tree_settings();
        images[uvs] = util_cpu_reference(s, &set, W, H);
        bg_renderer_destroy(r);
        mesh_free(&m);
        bg_scene_destroy(s);
    }
    int differ = 0;
    for (int i = 0; i < 4 * W * H; i++)
        differ += abs((int)images[0][i] - (int)images[1][i]) > 8;
    print_message("anisotropic knot: %d channels differ between the tangents\n", differ);
    assert_true(differ > 100);
    free(images[0]);
    free(images[1]);
}

/* A terrain of 845,000 triangles: 8.45 million texels of mesh data, past the 2^23 that llvmpipe
 * reads right from one texture (gpu/shared/meshes.c gives nodes and triangles a texture each). In one
 * texture its nearest rows went missing (measured: 251 of 16,384 pixels off by up to 240). */
static void mesh_past_one_texture_matches_cpu(void **state)
{
    (void)state;
    bg_scene *s = new_scene();
    mesh m = terrain(650, 0.25, false);
    add_mesh(s, &m, material(s, 0.6, 0.7, 0.5, 0.0), bg_mat4_identity());
    mesh_free(&m);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.0, 1.6, 2.2);
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    commit(s);
    /* The tree plan and the multipass (the unrolled plan's fetch is the tree plan's): one pixel in
     * 9,216 is off by 106 in both alike, a ridge below the pixel's size whose shadow float and double
     * decide apart; the share and the mean are what would show missing rows. */
    bg_render_settings set = tree_settings();
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    static const bg_gpu_plan plans[2] = {BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
    for (int k = 0; k < 2; k++) {
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_stats st;
        diff d = plan_vs_cpu(r, s, plans[k], cpu, "terrain 845,000", W, H, &st);
        assert_int_equal(d.holes, 0);
        assert_true(d.mean <= mean_bound(CLOSE_MEAN));
        assert_true(d.over <= CLOSE_OVER);
        bg_renderer_destroy(r);
    }
    free(cpu);
    bg_scene_destroy(s);
}

/* The triangle stack (tests/util_gpu.c): the pixels near the axis walk every node and run out of
 * steps, and must come from the CPU reference in every plan; the whole image still matches it. At
 * 48x48: every pixel that runs out walks the whole step budget on the GPU and then 40000 triangles
 * on the CPU, so the suite's 96x96 would take four times as long for nothing more to see. */
static void mesh_walks_that_run_out_go_to_the_cpu(void **state)
{
    (void)state;
    bg_scene *s = util_triangle_stack_scene();
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_stats st;
    enum { SW = 48, SH = 48 };
    diff d = gpu_vs_cpu_at(r, s, "triangle stack", SW, SH, &st);
    for (int k = 0; k <= OTHER_PLANS; k++)
        if (fallback[k] == 0 || fallback[k] >= (uint64_t)SW * SH)
            fail_msg("triangle stack, %s: %llu CPU pixels; some (not all) should be",
                     plan_name(k ? other_plans[k - 1] : BG_PLAN_FUSED_TREE), (unsigned long long)fallback[k]);
    expect_close(d, 8, 0.1, 0.001);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* A terrain of 2 n^2 triangles and its copy or its instance beside it, committed. */
static bg_scene *two_terrains(int n, bool instance)
{
    bg_scene *s = new_scene();
    mesh m = terrain(n, 0.25, false);
    uint32_t mat = material(s, 0.6, 0.7, 0.5, 0.0);
    bg_mat4 left = bg_mat4_translate(-1.0, 0.0, 0.0), right = bg_mat4_translate(1.0, 0.0, 0.0);
    uint32_t first = add_mesh(s, &m, mat, left), second = 0;
    if (instance)
        assert_int_equal(bg_scene_add_mesh_instance(s, first, &right, mat, true, &second), BG_OK);
    else
        add_mesh(s, &m, mat, right);
    mesh_free(&m);
    commit(s);
    return s;
}

/* With GL_MAX_TEXTURE_SIZE capped at 64 a mesh texture holds 64 rows of 64 texels, 4096: a terrain
 * of 648 triangles (3888 texels of attributes, 3238 of tree) fits, and so does an instance of it,
 * which shares them; two copies (7776 and 6476) do not. Every plan then refuses the frame with a
 * message that names the plan (or that none can), the texels and the cap, leaves the caller's image
 * as it was, and renders the next frame. */
static void meshes_beyond_the_texture_cap(void **state)
{
    (void)state;
    macs_limits caps = {0};
    caps.max_texture_size = 64;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *fits = two_terrains(18, true), *over = two_terrains(18, false);
    static const bg_gpu_plan plans[] = {BG_PLAN_AUTO, BG_PLAN_FUSED_TREE, BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
    unsigned char px[48 * 36 * 4];
    bg_image img = {48, 36, BG_PIXEL_RGBA8, 0, px};
    for (size_t k = 0; k < sizeof plans / sizeof plans[0]; k++) {
        bg_render_settings set = bg_render_settings_init();
        set.gpu_plan = plans[k];
        memset(px, 0x5a, sizeof px);
        /* The refusal is the test: the library's own call, which no limit profile turns into a skip. */
        bg_status st = (bg_render_gpu)(r, over, &set, &img);
        const char *msg = bg_renderer_error_message(r);
        const char *plan = plans[k] == BG_PLAN_FUSED_TREE ? "BG_PLAN_FUSED_TREE"
                           : plans[k] == BG_PLAN_FUSED    ? "BG_PLAN_FUSED"
                                                          : "no plan";
        if (st != BG_ERR_LIMIT || !strstr(msg, plan) || !strstr(msg, "the 4096 of a mesh texture") ||
            (!strstr(msg, "nodes of their trees need 6476") && !strstr(msg, "triangles need 7776")))
            fail_msg("plan %d, two copies: status %s, message \"%s\"", (int)plans[k], bg_status_string(st), msg);
        for (size_t i = 0; i < sizeof px; i++)
            if (px[i] != 0x5a)
                fail_msg("plan %d: a refused frame wrote byte %zu of the image", (int)plans[k], i);
        bg_renderer_clear_error(r);
        util_render_gpu(r, ctx, fits, &set, &img, "a terrain and its instance after the refusal");
        size_t unchanged = 0;
        for (size_t i = 0; i < sizeof px; i++)
            unchanged += px[i] == 0x5a;
        assert_true(unchanged < sizeof px / 2);
    }
    bg_scene_destroy(over);
    bg_scene_destroy(fits);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(leaving_rays_miss_the_neighbours),
        cmocka_unit_test(faceted_icosphere_matches_cpu),
        cmocka_unit_test(icosphere_matches_cpu),
        cmocka_unit_test(mesh_order_follows_the_camera),
        cmocka_unit_test(torus_knot_shadows_itself),
        cmocka_unit_test(instances_and_spheres_match_cpu),
        cmocka_unit_test(thin_instanced_fins_keep_their_shadow_edges),
        cmocka_unit_test(multipass_options_with_meshes),
        cmocka_unit_test(bunny_matches_cpu),
        cmocka_unit_test(glass_mesh_matches_cpu),
        cmocka_unit_test(textured_mesh_matches_cpu),
        cmocka_unit_test(anisotropic_mesh_matches_cpu),
        cmocka_unit_test(mesh_walks_that_run_out_go_to_the_cpu),
        cmocka_unit_test(mesh_past_one_texture_matches_cpu),
        cmocka_unit_test(meshes_beyond_the_texture_cap),
    };
    return cmocka_run_group_tests_name("bg_gpu_mesh", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
