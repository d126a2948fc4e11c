/* Test helpers for the GPU renderer suites (util_gpu.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define UTIL_GPU_LIBRARY_CALLS /* this file calls the library's bg_render_gpu*, not the macros */
#include "gpu_thresholds.h"
#include "scenes/image_metrics.h"
#include "util_gl.h"
#include "util_gpu.h"

static void skip_refused(bg_renderer *r, bg_status st, const char *label);

bg_scene *util_many_spheres(int n)
{
    scene_params p = {0};
    p.spheres = n;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(scenes_build_ex(SCENE_MANY_SPHERES, &p, s), BG_OK);
    return s;
}

unsigned char *util_cpu_reference(bg_scene *s, const bg_render_settings *set, int width, int height)
{
    unsigned char *cpu = malloc((size_t)width * height * 4);
    assert_non_null(cpu);
    bg_image ci = {width, height, BG_PIXEL_RGBA8, 0, cpu};
    assert_int_equal(bg_render_cpu(s, set, &ci), BG_OK);
    return cpu;
}

unsigned char *util_gpu_plan_image(bg_scene *s, const bg_render_settings *set, bg_gpu_plan plan, int width,
                                   int height, const char *label)
{
    bg_render_settings own = *set;
    own.gpu_plan = plan;
    unsigned char *px = malloc((size_t)width * height * 4);
    assert_non_null(px);
    bg_image img = {width, height, BG_PIXEL_RGBA8, 0, px};
    bg_renderer *r = util_renderer(util_fx.ctx);
    util_render_gpu(r, util_fx.ctx, s, &own, &img, label);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.plan, plan);
    bg_renderer_destroy(r);
    return px;
}

void util_expect_near(const unsigned char *cpu, const bg_image *gpu, scene_id id, const char *label)
{
    util_expect_near_row(cpu, gpu, gpu_threshold_of(id), label);
}

void util_expect_near_row(const unsigned char *cpu, const bg_image *gpu, const gpu_threshold *row, const char *label)
{
    bg_image ci = {gpu->width, gpu->height, BG_PIXEL_RGBA8, 0, (void *)cpu};
    image_metrics m;
    assert_true(image_metrics_compare(&ci, gpu, GPU_SILHOUETTE_THRESHOLD, &m));
    char line[512], why[256];
    print_message("%-28s %s\n", label, image_metrics_format(&m, line, sizeof line));
    if (!gpu_threshold_check(row, &m, why, sizeof why))
        fail_msg("%s: %s", label, why);
}

void util_expect_within(bg_scene *s, const bg_render_settings *set, const bg_image *gpu, scene_id id,
                        const char *label)
{
    unsigned char *cpu = util_cpu_reference(s, set, gpu->width, gpu->height);
    util_expect_near(cpu, gpu, id, label);
    free(cpu);
}

bg_renderer *util_renderer(macs_context *ctx)
{
    bg_renderer_desc d = {0};
    d.context = ctx;
    bg_renderer *r = NULL;
    char message[256];
    bg_status st = bg_renderer_create(&d, &r, message, sizeof message);
    util_skip_if_profile_refuses(st, message, "bg_renderer_create");
    if (st != BG_OK)
        fail_msg("bg_renderer_create: %s: %s", bg_status_string(st), message);
    assert_non_null(r);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    assert_string_equal(bg_renderer_error_message(r), "");
    return r;
}

void util_gpu_open(util_gpu *g, const macs_limits *caps)
{
    g->headless = util_headless();
    g->ctx = util_context(g->headless, caps);
    g->renderer = util_renderer(g->ctx);
}

void util_gpu_close(util_gpu *g)
{
    bg_renderer_destroy(g->renderer);
    macs_context_destroy(g->ctx);
    macs_headless_destroy(g->headless);
    g->renderer = NULL;
    g->ctx = NULL;
    g->headless = NULL;
}

bg_scene *util_scene(scene_id id)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_status st = scenes_build(id, s);
    if (st != BG_OK)
        fail_msg("%s: %s", scenes_name(id), bg_scene_error_message(s));
    return s;
}

void util_render_gpu(bg_renderer *r, macs_context *ctx, bg_scene *s, const bg_render_settings *set, bg_image *img,
                     const char *label)
{
    bg_status st = bg_render_gpu(r, s, set, img);
    skip_refused(r, st, label);
    if (st != BG_OK)
        fail_msg("%s: bg_render_gpu: %s: %s (MACS: %s)", label, bg_status_string(st), bg_renderer_error_message(r),
                 macs_context_error_message(ctx));
}

void util_skip_if_profile_refuses(bg_status st, const char *message, const char *label)
{
    /* Only a limit refusal, and only under a profile: anywhere else BG_ERR_LIMIT stays a failure. */
    if (st != BG_ERR_LIMIT || !util_profile())
        return;
    /* The renderer keeps its first error, which may be older than this refusal: said as such. */
    print_message("skipped: %s: the renderer refuses profile %s's limits (BG_ERR_LIMIT); its first recorded "
                  "error: %s\n", label, util_profile(), message);
    skip();
}

/* A skipped test must leave nothing behind for the next: the refusal stays recorded (first error
 * wins) in the renderer and in the MACS context, which the suite's fixture shares across tests. */
static void skip_refused(bg_renderer *r, bg_status st, const char *label)
{
    if (st != BG_ERR_LIMIT || !util_profile())
        return;
    char message[1024];
    snprintf(message, sizeof message, "%s", bg_renderer_error_message(r));
    bg_renderer_clear_error(r);
    if (util_fx.ctx)
        macs_context_clear_error(util_fx.ctx);
    util_skip_if_profile_refuses(st, message, label);
}

bg_status util_profiled_render_gpu(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_image *img)
{
    bg_status st = bg_render_gpu(r, s, set, img);
    skip_refused(r, st, "bg_render_gpu");
    return st;
}

bg_status util_profiled_render_gpu_to_texture(bg_renderer *r, bg_scene *s, const bg_render_settings *set,
                                              macs_texture *target)
{
    bg_status st = bg_render_gpu_to_texture(r, s, set, target);
    skip_refused(r, st, "bg_render_gpu_to_texture");
    return st;
}

bg_status util_profiled_render_gpu_accumulate(bg_renderer *r, bg_scene *s, const bg_render_settings *set,
                                              bg_accumulation *acc, int first, int count)
{
    bg_status st = bg_render_gpu_accumulate(r, s, set, acc, first, count);
    skip_refused(r, st, "bg_render_gpu_accumulate");
    return st;
}

util_gpu util_fx;

int util_gpu_group_setup(void **state)
{
    (void)state;
    util_gpu_open(&util_fx, NULL);
    return 0;
}

int util_gpu_group_teardown(void **state)
{
    (void)state;
    util_gpu_close(&util_fx);
    return 0;
}

bg_render_settings util_multipass_settings(void)
{
    bg_render_settings s = bg_render_settings_init();
    s.gpu_plan = BG_PLAN_MULTIPASS;
    return s;
}

bg_scene *util_triangle_stack_scene(void)
{
    enum { K = 40000 };
    float *pos = malloc(sizeof(float) * 9 * K);
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * K);
    assert_non_null(pos);
    assert_non_null(idx);
    for (int k = 0; k < K; k++) {
        float z = -1e-5f * (float)k;
        const float tri[9] = {1.0f, -0.5f, z, 1.0f, 1.0f, z, -0.5f, 1.0f, z};
        memcpy(pos + 9 * k, tri, sizeof tri);
        for (int c = 0; c < 3; c++)
            idx[3 * k + c] = (uint32_t)(3 * k + c);
    }
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t mat = 0, id = 0;
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){0.7, 0.7, 0.7, 0};
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    bg_mesh_desc d = bg_mesh_desc_init(mat);
    d.positions = pos;
    d.vertex_count = 3 * K;
    d.indices = idx;
    d.triangle_count = K;
    assert_int_equal(bg_scene_add_mesh(s, &d, &id), BG_OK); /* the scene keeps its own copy */
    free(pos);
    free(idx);
    const double ambient[3] = {0.05, 0.05, 0.05};
    assert_int_equal(bg_scene_set_ambient(s, ambient), BG_OK);
    bg_light l = bg_light_init();
    l.position = (bg_vec3){3.0, 4.0, 5.0};
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = (bg_vec3){0.0, 0.0, 3.0};
    cam.look_at = (bg_vec3){0.0, 0.0, 0.0};
    cam.fov_y_degrees = 40.0;
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

bg_scene *util_tube_scene(void)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t mat = 0;
    bg_material m = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    /* Centre (0.4, 0.4) is 0.566 from the axis, beyond the radius 0.5; the box [-0.1, 0.9]^2 holds it. */
    uint32_t id = 0;
    for (int k = 0; k < 40000; k++)
        assert_int_equal(bg_scene_add_sphere(s, (bg_vec3){0.4, 0.4, -5.0 - 1e-4 * k}, 0.5, mat, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = (bg_vec3){2.0, 3.0, 2.0};
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = (bg_vec3){0.0, 0.0, 0.0};
    cam.look_at = (bg_vec3){0.0, 0.0, -1.0};
    cam.up = (bg_vec3){0.0, 1.0, 0.0};
    cam.fov_y_degrees = 8.0;
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

void util_expect_multipass_refuses(bg_scene *s, const bg_render_settings *set, const char *named)
{
    unsigned char px[16 * 12 * 4];
    memset(px, 0x5a, sizeof px);
    bg_image img = {16, 12, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings own = *set;
    own.gpu_plan = BG_PLAN_MULTIPASS;
    bg_renderer *r = util_renderer(util_fx.ctx);
    assert_int_equal(bg_render_gpu(r, s, &own, &img), BG_ERR_LIMIT);
    if (!strstr(bg_renderer_error_message(r), named))
        fail_msg("the multipass's refusal does not name %s: %s", named, bg_renderer_error_message(r));
    for (size_t i = 0; i < sizeof px; i++)
        assert_int_equal(px[i], 0x5a);
    bg_renderer_destroy(r);
}

void util_expect_multipass_refuses_environment(bg_scene *s, const bg_render_settings *set)
{
    util_expect_multipass_refuses(s, set, "environment");
}

bg_render_settings util_plan_settings(bg_gpu_plan plan, int samples)
{
    bg_render_settings s = bg_render_settings_init();
    s.gpu_plan = plan;
    s.samples = samples;
    s.threads = 2;
    return s;
}

void util_expect_render_ok(bg_renderer *r, bg_status st, const char *what)
{
    if (st != BG_OK)
        fail_msg("%s: %s (%s)", what, bg_status_string(st), bg_renderer_error_message(r));
}
