/* The GPU renderer's two plans (bg_gpu_plan): the fused plan, one fragment pass per frame, against
 * the CPU reference on every shared scene within the thresholds the multipass is held to
 * (gpu_thresholds.h); BG_PLAN_AUTO choosing it where it applies and the multipass, with the reason
 * logged, where it does not; a forced multipass rendering what the multipass always rendered; a
 * forced fused plan that cannot run failing clearly; and re-commits that change only values
 * rendering right without compiling a program.
 *
 * The two plans are not bit-identical to each other: they evaluate the same formulas in a
 * different order (one pass sums a pixel's whole ray tree in registers, the multipass adds level by
 * level by blending) and the multipass chooses the nearest hit by depth buffer values while the
 * fused plan compares t itself. Each is held to the CPU reference instead. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/common/encoding.h"
#include "betelgeuse/gpu/driver.h"
#include "gpu_thresholds.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_thresholds.h"

/* The size of test_bg_gpu_scenes, where the thresholds were measured. */
enum { W = 160, H = 120 };

/* ---- helpers ---- */

/* What a renderer logged at BG_LOG_INFO, for the reasons of BG_PLAN_AUTO. */
typedef struct info_log {
    char last[1024];
    int count;
} info_log;

static void capture_info(bg_log_level level, const char *message, void *user)
{
    info_log *log = user;
    if (level != BG_LOG_INFO)
        return;
    snprintf(log->last, sizeof log->last, "%s", message);
    log->count++;
}

static bg_renderer *logging_renderer(info_log *log)
{
    bg_renderer_desc d = {0};
    d.context = util_fx.ctx;
    d.logger.func = capture_info;
    d.logger.user = log;
    bg_renderer *r = NULL;
    char message[512];
    if (bg_renderer_create(&d, &r, message, sizeof message) != BG_OK)
        fail_msg("bg_renderer_create: %s", message);
    return r;
}

static bg_render_settings plan_settings(bg_gpu_plan plan)
{
    bg_render_settings s = bg_render_settings_init();
    s.gpu_plan = plan;
    return s;
}

static bg_render_stats render(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_image *img,
                              const char *label)
{
    util_render_gpu(r, util_fx.ctx, s, set, img, label);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    return stats;
}

/* ---- every shared scene ---- */

static void check_scene(scene_id id)
{
    const char *name = scenes_name(id);
    char label[64];
    bg_scene *s = util_scene(id);
    size_t bytes = (size_t)W * H * 4;
    bg_render_settings set = plan_settings(BG_PLAN_AUTO);
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    unsigned char *fused = malloc(bytes), *other = malloc(bytes);
    float *linear = malloc(bytes * sizeof(float));
    assert_non_null(fused);
    assert_non_null(other);
    assert_non_null(linear);
    bg_image fi = {W, H, BG_PIXEL_RGBA8, 0, fused}, oi = {W, H, BG_PIXEL_RGBA8, 0, other};
    bg_image li = {W, H, BG_PIXEL_RGBA32F, 0, linear};

    /* Forced fused: within the scene's thresholds, one pass. */
    set = plan_settings(BG_PLAN_FUSED);
    bg_render_stats st = render(util_fx.renderer, s, &set, &fi, name);
    assert_int_equal(st.plan, BG_PLAN_FUSED);
    assert_int_equal(st.passes[BG_PASS_INTERSECT], 1);
    assert_int_equal(st.intersect_objects, (int)bgi_scene_committed(s)->object_count);
    snprintf(label, sizeof label, "%s fused", name);
    util_expect_near(cpu, &fi, id, label);

    /* Its float output is finite and what the RGBA8 output encodes. */
    render(util_fx.renderer, s, &set, &li, name);
    size_t bad = image_metrics_count_nonfinite(&li);
    if (bad != 0)
        fail_msg("%s: %zu non-finite values in the fused RGBA32F output", name, bad);
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 0; c < 3; c++) {
            float v = linear[4 * i + c];
            int want = bgi_encode_channel(v, BG_ENCODING_SRGB);
            if (v < 0.0f || abs(want - fused[4 * i + c]) > 1 || linear[4 * i + 3] != 1.0f)
                fail_msg("%s: pixel %zu channel %d: float %g encodes to %d, RGBA8 output %d", name, i, c, (double)v,
                         want, fused[4 * i + c]);
        }

    /* Forced tree variant: the bounded objects walked from textures, within the same thresholds,
     * every pixel finished by the GPU. Not the unrolled image bit for bit (other float operations). */
    set = plan_settings(BG_PLAN_FUSED_TREE);
    st = render(util_fx.renderer, s, &set, &oi, name);
    assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
    assert_int_equal(st.passes[BG_PASS_INTERSECT], 1);
    if (st.fallback_pixels != 0)
        fail_msg("%s: %llu pixels of the tree variant went to the CPU reference", name,
                 (unsigned long long)st.fallback_pixels);
    snprintf(label, sizeof label, "%s fused tree", name);
    util_expect_near(cpu, &oi, id, label);

    /* Automatic: every shared scene is within the fused plans' bounds, and gets the same program
     * as the variant forced: unrolled below 8 objects in the tree, walked from 8 on. */
    bool walked = bgi_scene_committed(s)->tree_count >= 8;
    if (walked)
        memcpy(fused, other, bytes);
    set = plan_settings(BG_PLAN_AUTO);
    st = render(util_fx.renderer, s, &set, &oi, name);
    if (st.plan != (walked ? BG_PLAN_FUSED_TREE : BG_PLAN_FUSED))
        fail_msg("%s: BG_PLAN_AUTO ran plan %d, not the %s fused plan", name, (int)st.plan,
                 walked ? "tree variant of the" : "unrolled");
    /* Equal on any conforming driver: the same program (MACS's cache hands the forced variant's
     * over) on the same uniforms and textures (GL 2.1 appendix A, rule 4). */
    assert_memory_equal(fused, other, bytes);

    free(cpu);
    free(fused);
    free(other);
    free(linear);
    bg_scene_destroy(s);
}

UTIL_EACH_SCENE(UTIL_SCENE_TEST)

/* A forced multipass renders what the multipass always rendered, within the same thresholds: the
 * image BG_PLAN_AUTO gives when a skip is switched off, which sends it to the multipass (switching
 * off batching changes no bit on Mesa, test_bg_gpu_skips). Two scenes, one with every bounce kind, keep the
 * suite short: test_bg_gpu_scenes holds the multipass to the thresholds on every scene. */
static void forced_multipass_is_the_multipass(void **state)
{
    (void)state;
    const scene_id ids[2] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS};
    unsigned char forced[W * H * 4], automatic[W * H * 4];
    bg_image fi = {W, H, BG_PIXEL_RGBA8, 0, forced}, ai = {W, H, BG_PIXEL_RGBA8, 0, automatic};
    for (int k = 0; k < 2; k++) {
        bg_scene *s = util_scene(ids[k]);
        bg_render_settings set = plan_settings(BG_PLAN_MULTIPASS);
        bg_render_stats st = render(util_fx.renderer, s, &set, &fi, scenes_name(ids[k]));
        assert_int_equal(st.plan, BG_PLAN_MULTIPASS);
        assert_true(st.passes[BG_PASS_RAYS] == 1 && st.passes[BG_PASS_RESOLVE] == 1);
        char label[64];
        snprintf(label, sizeof label, "%s multipass", scenes_name(ids[k]));
        util_expect_within(s, &set, &fi, ids[k], label);
        set = plan_settings(BG_PLAN_AUTO);
        set.gpu_disable_skips = BG_SKIP_BATCH;
        assert_int_equal(render(util_fx.renderer, s, &set, &ai, scenes_name(ids[k])).plan, BG_PLAN_MULTIPASS);
        /* Batching off makes one program per object: other programs over the same formulas, so the
         * same bits on Mesa and the error model's bound on any driver. */
        util_expect_near_row(forced, &ai, gpu_threshold_of(ids[k]), label);
        bg_scene_destroy(s);
    }
}

/* The ray tree's shapes: no bounce at all, a single bounce, a partial tree under a coloured
 * background (seen at every level, through the glass too), and the full tree of max_depth 5 with
 * nothing pruned (63 rays a pixel, the stack full). */
static void depths_and_pruning(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_GLASS);
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    const int depths[4] = {0, 1, 3, 5};
    for (int k = 0; k < 4; k++) {
        bg_render_settings set = plan_settings(BG_PLAN_FUSED);
        set.max_depth = depths[k];
        if (depths[k] == 3) {
            set.background[0] = 0.2;
            set.background[1] = 0.3;
            set.background[2] = 0.5;
        }
        if (depths[k] == 5)
            set.min_weight = 0.0;
        char label[64];
        snprintf(label, sizeof label, "glass depth %d%s", depths[k], depths[k] == 5 ? " unpruned" : "");
        assert_int_equal(render(util_fx.renderer, s, &set, &img, label).plan, BG_PLAN_FUSED);
        util_expect_within(s, &set, &img, SCENE_GLASS, label);
    }
    bg_scene_destroy(s);
}

/* ---- re-commits ---- */

/* Renders the glass scene with the plan after each change, within its thresholds, and returns how
 * many programs the render built. */
static int plan_render_count(bg_renderer *r, bg_scene *s, bg_image *img, bg_gpu_plan plan, const char *label)
{
    bg_render_settings set = plan_settings(plan);
    bg_render_stats st = render(r, s, &set, img, label);
    assert_int_equal(st.plan, plan);
    if (img->format == BG_PIXEL_RGBA8)
        util_expect_within(s, &set, img, SCENE_GLASS, label);
    return st.programs_compiled;
}

/* Camera, material colour, light, transform, image size and format are values: the plan's programs
 * stay. A material crossing into another class (glass made opaque: no refraction anywhere) is
 * structure: a new program. */
static void value_recommits(bg_gpu_plan plan)
{
    /* A context of its own: its program cache starts empty, so the first render compiles. */
    macs_context *ctx = util_context(util_fx.headless, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = util_scene(SCENE_GLASS);
    const bg_scene_state *ss = bgi_scene_committed(s);
    unsigned char px[W * H * 4];
    float fpx[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    assert_true(plan_render_count(r, s, &img, plan, "glass first render") >= 1);

    /* The multipass keeps its uploaded scene textures too (its renderer holds them). */
    assert_true(plan != BG_PLAN_MULTIPASS || (ss->texture_count > 0 && r->multipass->textures && r->multipass->textures[0]));
    const macs_texture *uploaded = plan == BG_PLAN_MULTIPASS ? r->multipass->textures[0] : NULL;
    bg_camera cam = ss->camera.camera;
    cam.position = bg_vec3_make(0.8, 1.9, 5.2);
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(plan_render_count(r, s, &img, plan, "glass camera moved"), 0);
    if (plan == BG_PLAN_MULTIPASS && r->multipass->textures[0] != uploaded)
        fail_msg("the multipass uploaded its scene textures again after a camera move");

    /* The last material is the mirror sphere's (scenes.c adds floor, glass, chrome). */
    uint32_t chrome = ss->material_count;
    bg_material m = ss->materials[chrome - 1];
    m.base.reflectance.r = 0.95;
    m.base.reflectance.g = 0.6;
    m.base.reflectance.b = 0.3;
    assert_int_equal(bg_scene_set_material(s, chrome, &m), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(plan_render_count(r, s, &img, plan, "glass mirror tinted"), 0);

    bg_light l = ss->lights[0];
    l.position = bg_vec3_make(-2, 7, 3);
    l.intensity = 1.1;
    assert_int_equal(bg_scene_set_light(s, 1, &l), BG_OK);
    bg_mat4 t = bg_mat4_mul(bg_mat4_translate(1.0, 0.1, -0.6), bg_mat4_scale(0.9, 0.9, 0.9));
    assert_int_equal(bg_scene_set_transform(s, ss->object_count, &t), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(plan_render_count(r, s, &img, plan, "glass light and sphere moved"), 0);

    bg_image smaller = {W / 2, H / 2, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(plan_render_count(r, s, &smaller, plan, "glass at half size"), 0);
    bg_image as_float = {W, H, BG_PIXEL_RGBA32F, 0, fpx};
    assert_int_equal(plan_render_count(r, s, &as_float, plan, "glass as float"), 0);

    /* The glass sphere's material comes before the mirror's. */
    m = ss->materials[chrome - 2];
    m.transparency.value = 0.0;
    assert_int_equal(bg_scene_set_material(s, chrome - 1, &m), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_true(plan_render_count(r, s, &img, plan, "glass made opaque") >= 1);

    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

static void value_recommits_compile_nothing(void **state)
{
    (void)state;
    value_recommits(BG_PLAN_FUSED);
}

/* The multipass builds its passes anew after any commit, but MACS's program cache still holds the
 * programs of the old ones while it does. */
static void multipass_value_recommits_compile_nothing(void **state)
{
    (void)state;
    value_recommits(BG_PLAN_MULTIPASS);
}

/* ---- choosing ---- */

/* Outside its bounds, or asked for what only the multipass has, BG_PLAN_AUTO renders with the
 * multipass and says why; forced, the fused plan still renders there, within the same thresholds. */
static void auto_falls_back_and_says_why(void **state)
{
    (void)state;
    info_log log = {"", 0};
    bg_renderer *r = logging_renderer(&log);
    enum { SW = 48, SH = 36 };
    unsigned char px[SW * SH * 4];
    bg_image small = {SW, SH, BG_PIXEL_RGBA8, 0, px};

    /* Skips switched off: their switches are the multipass's. */
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_render_settings set = plan_settings(BG_PLAN_AUTO);
    set.gpu_disable_skips = BG_SKIP_SCISSOR;
    assert_int_equal(render(r, s, &set, &small, "skips off").plan, BG_PLAN_MULTIPASS);
    if (log.count != 1 || !strstr(log.last, "gpu_disable_skips"))
        fail_msg("no reason logged for skips off (%d messages, last \"%s\")", log.count, log.last);
    /* A depth scale of its own: dmax is the multipass's. */
    set = plan_settings(BG_PLAN_AUTO);
    set.dmax = 50.0;
    assert_int_equal(render(r, s, &set, &small, "dmax").plan, BG_PLAN_MULTIPASS);
    if (log.count != 2 || !strstr(log.last, "dmax"))
        fail_msg("no reason logged for dmax (%d messages, last \"%s\")", log.count, log.last);
    bg_scene_destroy(s);

    /* A deep glass tree: more rays per pixel than the fused plan was measured with. */
    s = util_scene(SCENE_GLASS);
    set = plan_settings(BG_PLAN_AUTO);
    set.max_depth = 12;
    assert_int_equal(render(r, s, &set, &small, "deep glass").plan, BG_PLAN_MULTIPASS);
    if (log.count != 3 || !strstr(log.last, "rays"))
        fail_msg("no reason logged for the deep tree (%d messages, last \"%s\")", log.count, log.last);
    unsigned char big[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, big};
    set.gpu_plan = BG_PLAN_FUSED;
    assert_int_equal(render(r, s, &set, &img, "deep glass fused").plan, BG_PLAN_FUSED);
    util_expect_within(s, &set, &img, SCENE_GLASS, "glass depth 12 fused");
    bg_scene_destroy(s);

    /* More unbounded objects than it unrolls: planes stay outside the object tree. */
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(scenes_build(SCENE_PAPER_EARTH_SHADOW, s), BG_OK);
    uint32_t id = 0;
    for (int k = 0; k < 40; k++)
        assert_int_equal(bg_scene_add_plane(s, (bg_vec3){0.0, -10.0 - k, 0.0}, (bg_vec3){0.0, 1.0, 0.0}, 1, &id),
                         BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    set = plan_settings(BG_PLAN_AUTO);
    assert_int_equal(render(r, s, &set, &small, "40 planes").plan, BG_PLAN_MULTIPASS);
    /* Under a limit profile the smaller uniform budget may decline the frame first: a reason too. */
    bool uniforms = util_profile() && strstr(log.last, "uniform components");
    if (log.count != 4 || (!strstr(log.last, "objects outside the object tree") && !uniforms))
        fail_msg("no reason logged for 40 planes (%d messages, last \"%s\")", log.count, log.last);
    bg_scene_destroy(s);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    bg_renderer_destroy(r);

    /* A renderer made for a half-float G-buffer (where GL renders to RGBA16F) keeps its G-buffer. */
    bg_renderer_desc d = {0};
    d.context = util_fx.ctx;
    d.half_gbuffer = true;
    assert_int_equal(bg_renderer_create(&d, &r, NULL, 0), BG_OK);
    s = util_scene(SCENE_PAPER_EARTH);
    set = plan_settings(BG_PLAN_AUTO);
    bg_render_stats st = render(r, s, &set, &small, "half G-buffer");
    assert_int_equal(st.plan, st.gbuffer_half_targets > 0 ? BG_PLAN_MULTIPASS : BG_PLAN_FUSED);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

/* A forced fused plan beyond what it can run fails with BG_ERR_LIMIT and says so; the renderer
 * renders the next frame. */
static void forced_fused_beyond_limits_fails(void **state)
{
    (void)state;
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_GLASS);
    unsigned char px[32 * 24 * 4];
    bg_image img = {32, 24, BG_PIXEL_RGBA8, 0, px};
    /* Without min_weight's pruning the full tree of depth 20 needs 2^21 - 1 rays per pixel. */
    bg_render_settings set = plan_settings(BG_PLAN_FUSED);
    set.max_depth = 20;
    set.min_weight = 0.0;
    /* The refusal is the test: the library's own call, which no limit profile turns into a skip. */
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    assert_int_equal(bg_renderer_error(r), BG_ERR_LIMIT);
    const char *msg = bg_renderer_error_message(r);
    if (!strstr(msg, "BG_PLAN_FUSED") || !strstr(msg, "rays"))
        fail_msg("unclear message: \"%s\"", msg);
    bg_renderer_clear_error(r);
    set = plan_settings(BG_PLAN_FUSED);
    assert_int_equal(render(r, s, &set, &img, "after the limit").plan, BG_PLAN_FUSED);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);

    /* Fewer texture units than the scene samples textures. */
    macs_limits caps = {0};
    caps.max_texture_units = 2;
    macs_context *ctx = util_context(util_fx.headless, &caps);
    r = util_renderer(ctx);
    s = util_scene(SCENE_TEXTURED_ANISO);
    assert_int_equal((bg_render_gpu)(r, s, &set, &img), BG_ERR_LIMIT);
    msg = bg_renderer_error_message(r);
    if (!strstr(msg, "texture units"))
        fail_msg("unclear message: \"%s\"", msg);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* GL_NEAREST scene textures (bg_texture_desc.filter): an 8x8 checker on a tilted plane, read as
 * whole texels by both fused variants and the multipass, within the textured scene's thresholds of
 * the CPU reference (texel edges count as silhouettes there). */
static void nearest_textures(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    unsigned char checker[8 * 8 * 4];
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            unsigned char *p = checker + (y * 8 + x) * 4;
            bool light = (x + y) % 2 == 0;
            p[0] = light ? 230 : 40;
            p[1] = light ? 200 : 60;
            p[2] = light ? 90 : 140;
            p[3] = 255;
        }
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, checker};
    bg_texture_desc desc = {BG_WRAP_REPEAT, BG_TEXTURE_SRGB, BG_FILTER_NEAREST};
    uint32_t tex = 0, mat = 0, id = 0;
    assert_int_equal(bg_scene_add_texture(s, &img, &desc, &tex), BG_OK);
    bg_material m = bg_material_init();
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 1.0;
    m.base.reflectance.texture = tex;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    bg_object_desc plane = bg_object_desc_init(BG_SHAPE_PLANE, mat);
    plane.transform = bg_mat4_rotate(bg_vec3_make(1, 0.3, 0), 12.0);
    plane.uv_scale[0] = plane.uv_scale[1] = 0.37;
    assert_int_equal(bg_scene_add_object(s, &plane, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(1.0, 4.0, 2.0);
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0.3, 2.2, 4.1);
    cam.look_at = bg_vec3_make(0.1, 0.0, 0.0);
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    unsigned char px[W * H * 4];
    bg_image out = {W, H, BG_PIXEL_RGBA8, 0, px};
    const bg_gpu_plan plans[3] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
    const char *labels[3] = {"nearest checker fused", "nearest checker tree", "nearest checker multipass"};
    for (int k = 0; k < 3; k++) {
        bg_render_settings set = plan_settings(plans[k]);
        assert_int_equal(render(util_fx.renderer, s, &set, &out, labels[k]).plan, plans[k]);
        util_expect_within(s, &set, &out, SCENE_TEXTURED_ANISO, labels[k]);
    }
    /* Not what linear filtering gives: the texels' edges stay sharp. */
    bg_render_settings set = plan_settings(BG_PLAN_FUSED);
    unsigned char *nearest = util_cpu_reference(s, &set, W, H);
    desc.filter = BG_FILTER_LINEAR;
    assert_int_equal(bg_scene_add_texture(s, &img, &desc, &tex), BG_OK);
    m.base.reflectance.texture = tex;
    assert_int_equal(bg_scene_set_material(s, mat, &m), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    unsigned char *linear = util_cpu_reference(s, &set, W, H);
    size_t differ = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        differ += nearest[i] != linear[i];
    if (differ < 1000)
        fail_msg("nearest and linear checkers differ in only %zu channels", differ);
    free(nearest);
    free(linear);
    bg_scene_destroy(s);
}

/* The plan is a setting like any other: defaults to automatic, unknown values are refused. */
static void plan_setting(void **state)
{
    (void)state;
    bg_render_settings set = bg_render_settings_init();
    assert_int_equal(set.gpu_plan, BG_PLAN_AUTO);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    set.gpu_plan = (bg_gpu_plan)7;
    assert_int_equal(bg_render_gpu(util_fx.renderer, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    if (!strstr(bg_renderer_error_message(util_fx.renderer), "gpu_plan"))
        fail_msg("message does not name the field: \"%s\"", bg_renderer_error_message(util_fx.renderer));
    bg_renderer_clear_error(util_fx.renderer);
    bg_scene_destroy(s);
}

/* ---- a GL that refuses the fused program, and a context capped below it ------------------------ */

/* glShaderSource swaps any fragment source holding the fused trace for one that does not compile,
 * as a GL whose compiler cannot take the long program would fail it. */
typedef void (*shader_source_fn)(unsigned, int, const char *const *, const int *);

static struct {
    macs_get_proc_address_fn real;
    void *real_user;
    shader_source_fn shader_source;
    int refused;
} nofused;

static void nofused_shader_source(unsigned shader, int count, const char *const *strings, const int *lengths)
{
    /* MACS passes NUL-terminated sources (lengths NULL), so strstr stays inside each string. */
    for (int i = 0; i < count && !lengths; i++) {
        if (strings[i] && strstr(strings[i], "bg_fused_nearest")) {
            static const char *const broken = "#version 110\nvoid main() { refused by the test's loader }\n";
            nofused.refused++;
            nofused.shader_source(shader, 1, &broken, NULL);
            return;
        }
    }
    nofused.shader_source(shader, count, strings, lengths);
}

static macs_gl_proc nofused_loader(const char *name, void *user)
{
    (void)user;
    macs_gl_proc p = nofused.real(name, nofused.real_user);
    if (p && strcmp(name, "glShaderSource") == 0) {
        nofused.shader_source = (shader_source_fn)p;
        return (macs_gl_proc)nofused_shader_source;
    }
    return p;
}

/* Renders a scene on ctx with AUTO (expecting the multipass, with a reason logged) and with the
 * multipass forced on the default fixture. With same_programs (ctx has the fixture's limits, so the
 * multipass batches alike) the two images must be the same bits on any conforming driver: programs of
 * the same source strings on the same inputs in the same order (GL 2.1 appendix A, rule 4), compiled
 * in two contexts. Otherwise (a cap that makes smaller batches) they come from other programs over
 * the same formulas, within the error model's bound (util_expect_gpu_twins). */
static void auto_falls_back_to_the_same_image(macs_context *ctx, scene_id id, const char *why, const char *label,
                                              bool same_programs)
{
    info_log log = {"", 0};
    bg_renderer_desc d = {0};
    d.context = ctx;
    d.logger.func = capture_info;
    d.logger.user = &log;
    bg_renderer *r = NULL;
    char message[512];
    if (bg_renderer_create(&d, &r, message, sizeof message) != BG_OK)
        fail_msg("bg_renderer_create: %s", message);
    bg_scene *s = util_scene(id);
    float *a = malloc((size_t)W * H * 16), *b = malloc((size_t)W * H * 16);
    assert_non_null(a);
    assert_non_null(b);
    bg_image ia = {W, H, BG_PIXEL_RGBA32F, 0, a}, ib = {W, H, BG_PIXEL_RGBA32F, 0, b};
    bg_render_settings set = plan_settings(BG_PLAN_AUTO);
    util_render_gpu(r, ctx, s, &set, &ia, label);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.plan, BG_PLAN_MULTIPASS);
    if (log.count < 1 || !strstr(log.last, why))
        fail_msg("%s: no reason naming \"%s\" logged (%d messages, last \"%s\")", label, why, log.count, log.last);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    set = plan_settings(BG_PLAN_MULTIPASS);
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &ib, label);
    if (!same_programs)
        util_expect_gpu_twins(a, b, W, H, gpu_threshold_of(id), label);
    else if (memcmp(a, b, (size_t)W * H * 16) != 0)
        fail_msg("%s: the fallback's image differs from the forced multipass", label);
    free(a);
    free(b);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

static void refused_program_falls_back(void **state)
{
    (void)state;
    memset(&nofused, 0, sizeof nofused);
    nofused.real = macs_headless_get_proc_address(util_fx.headless);
    nofused.real_user = macs_headless_proc_user(util_fx.headless);
    macs_context_desc cd = {0};
    cd.get_proc_address = nofused_loader;
    cd.profile = util_profile(); /* the fixture's limits and float features, so that the programs are the same */
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    auto_falls_back_to_the_same_image(ctx, SCENE_GLASS, "multipass", "refused fused program", true);
    assert_true(nofused.refused >= 1);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

static void uniform_cap_falls_back(void **state)
{
    (void)state;
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(util_fx.headless);
    cd.get_proc_address_user = macs_headless_proc_user(util_fx.headless);
    cd.caps.max_uniform_components = 256; /* GL 2.0 hardware's budget; the multipass's batches fit it */
    cd.profile = util_profile();
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    macs_limits eff;
    macs_context_get_limits(ctx, NULL, &eff);
    /* A profile's own cap combines with the test's, the smaller winning (gl21: 64). */
    int expected = 256;
    if (util_profile()) {
        macs_context_desc pd = {0};
        pd.get_proc_address = cd.get_proc_address;
        pd.get_proc_address_user = cd.get_proc_address_user;
        pd.profile = util_profile();
        macs_context *pctx = NULL;
        assert_int_equal(macs_context_create(&pd, &pctx, NULL, 0), MACS_OK);
        macs_limits peff;
        macs_context_get_limits(pctx, NULL, &peff);
        if (peff.max_uniform_components < expected)
            expected = peff.max_uniform_components;
        macs_context_destroy(pctx);
    }
    assert_int_equal(eff.max_uniform_components, expected);
    assert_int_equal(macs_context_max_uniform_components(ctx), expected);
    auto_falls_back_to_the_same_image(ctx, SCENE_MANY_LIGHTS, "uniform components", "uniform cap", false);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        UTIL_EACH_SCENE(UTIL_SCENE_UNIT_TEST)
        cmocka_unit_test(forced_multipass_is_the_multipass),
        cmocka_unit_test(depths_and_pruning),
        cmocka_unit_test(value_recommits_compile_nothing),
        cmocka_unit_test(multipass_value_recommits_compile_nothing),
        cmocka_unit_test(auto_falls_back_and_says_why),
        cmocka_unit_test(forced_fused_beyond_limits_fails),
        cmocka_unit_test(plan_setting),
        cmocka_unit_test(nearest_textures),
        cmocka_unit_test(refused_program_falls_back),
        cmocka_unit_test(uniform_cap_falls_back),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
