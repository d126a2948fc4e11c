/* The GPU renderer's error paths and edge cases: bad arguments, uncommitted scenes, image sizes
 * beyond the GL limits, bad settings, the sticky first error, empty and unlit scenes, GPU out of
 * memory (injected through a GL loader wrapper), no leak over many renderers on one context, a
 * reason for every failed creation, and each entry point's name at the start of its messages. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_alloc.h"

#include "betelgeuse.h"
#include "gpu_thresholds.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_oom.h"

/* ---- helpers ---- */

static bg_scene *new_scene(void)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    return s;
}

/* An untextured red sphere lit by one light: fits any max_texture_size. */
static bg_scene *small_scene(void)
{
    bg_scene *s = new_scene();
    bg_material m = bg_material_init();
    m.base.reflectance.g = m.base.reflectance.b = 0.1;
    uint32_t mat = 0, id = 0;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1.0, mat, &id), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(2, 3, 4);
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

static void render_ok(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_image *img)
{
    bg_status st = bg_render_gpu(r, s, set, img);
    if (st != BG_OK)
        fail_msg("bg_render_gpu: %s: %s", bg_status_string(st), bg_renderer_error_message(r));
}

/* The centre pixel of an RGBA8 image is not the background: something was drawn. */
static void assert_centre_drawn(const unsigned char *px, int w, int h)
{
    const unsigned char *c = px + ((size_t)(h / 2) * w + w / 2) * 4;
    assert_true(c[0] > 30);
    assert_int_equal(c[3], 255);
}

/* ---- arguments ---- */

static void null_arguments(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer *r = (bg_renderer *)ctx; /* must be reset to NULL on failure */
    bg_renderer_desc d = {0};
    assert_int_equal(bg_renderer_create(NULL, &r, NULL, 0), BG_ERR_INVALID_ARGUMENT);
    assert_null(r);
    r = (bg_renderer *)ctx;
    assert_int_equal(bg_renderer_create(&d, &r, NULL, 0), BG_ERR_INVALID_ARGUMENT); /* no context */
    assert_null(r);
    d.context = ctx;
    assert_int_equal(bg_renderer_create(&d, NULL, NULL, 0), BG_ERR_INVALID_ARGUMENT);
    bg_renderer_destroy(NULL);

    r = util_renderer(ctx);
    bg_scene *s = small_scene();
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init();
    assert_int_equal(bg_render_gpu(NULL, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_render_gpu(r, NULL, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_render_gpu(r, s, &set, NULL), BG_ERR_INVALID_ARGUMENT);
    bg_image nopix = img;
    nopix.pixels = NULL;
    assert_int_equal(bg_render_gpu(r, s, &set, &nopix), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_renderer_error(r), BG_ERR_INVALID_ARGUMENT);
    assert_true(strlen(bg_renderer_error_message(r)) > 0);
    bg_renderer_clear_error(r);
    /* nothing was half done: the same renderer renders */
    render_ok(r, s, &set, &img);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    assert_centre_drawn(px, 8, 8);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

static void uncommitted_scene(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = new_scene();
    bg_material m = bg_material_init();
    uint32_t mat = 0, id = 0;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1.0, mat, &id), BG_OK);
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init();
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_NOT_COMMITTED);
    assert_int_equal(bg_renderer_error(r), BG_ERR_NOT_COMMITTED);
    bg_renderer_clear_error(r);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    render_ok(r, s, &set, &img);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* Sizes below 1 are caller mistakes, named in the message; sizes above GL's limit render in tiles
 * (test_bg_gpu_view checks them bit for bit), and a refused size leaves the renderer ready for a
 * valid one. */
static void image_sizes(void **state)
{
    macs_limits caps = {0};
    caps.max_texture_size = 64;
    macs_context *ctx = util_context(*state, &caps);
    macs_limits eff;
    macs_context_get_limits(ctx, NULL, &eff);
    assert_int_equal(eff.max_texture_size, 64);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = small_scene();
    bg_render_settings set = bg_render_settings_init();
    unsigned char *px = calloc((size_t)65 * 65, 4);
    assert_non_null(px);

    bg_image img = {0, 8, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    img.width = 8;
    img.height = -3;
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    img.height = 8;
    img.stride = 31; /* below a row of 8 RGBA8 pixels */
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    img.stride = 0;
    img.format = (bg_pixel_format)7;
    assert_int_equal(bg_render_gpu(r, s, &set, &img), BG_ERR_INVALID_ARGUMENT);
    bg_renderer_clear_error(r);

    bg_image big = {65, 65, BG_PIXEL_RGBA8, 0, px};
    render_ok(r, s, &set, &big);
    assert_centre_drawn(px, 65, 65);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_int_equal(stats.tiles, 4); /* 33 + 32 per side */
    big.width = 64; /* the other side alone is too big */
    render_ok(r, s, &set, &big);
    bg_renderer_get_stats(r, &stats);
    assert_int_equal(stats.tiles, 2);

    /* the largest allowed size works on the same renderer */
    bg_image fits = {64, 64, BG_PIXEL_RGBA8, 0, px};
    render_ok(r, s, &set, &fits);
    assert_centre_drawn(px, 64, 64);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    free(px);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

static void bad_settings(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = small_scene();
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    const bg_render_settings good = bg_render_settings_init();
    assert_true(good.dmax == 0.0);
    assert_false(good.gpu_timing);
    assert_int_equal(good.gpu_disable_skips, 0);
    bg_render_settings b;
    b = good;
    b.dmax = NAN;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.dmax = -1.0;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.dmax = INFINITY;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.max_depth = 65;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.max_depth = -1;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.min_weight = NAN;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.background[1] = INFINITY;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.background[2] = -0.5;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    b = good;
    b.encoding = (bg_output_encoding)9;
    assert_int_equal(bg_render_gpu(r, s, &b, &img), BG_ERR_INVALID_ARGUMENT);
    /* a caller's dmax that holds the scene is honoured and reported */
    bg_renderer_clear_error(r);
    b = good;
    b.dmax = 100.0;
    render_ok(r, s, &b, &img);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_true(st.dmax[0] == 100.0);
    assert_centre_drawn(px, 8, 8);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* The first error stays, through later failures and successes, until cleared. */
static void first_error_is_sticky(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = small_scene();
    unsigned char px[8 * 8 * 4];
    bg_image img = {8, 8, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init(), bad = set;
    bad.max_depth = 65;
    assert_int_equal(bg_render_gpu(r, s, &bad, &img), BG_ERR_INVALID_ARGUMENT);
    char first[512];
    snprintf(first, sizeof first, "%s", bg_renderer_error_message(r));
    assert_true(strlen(first) > 0);
    bg_scene *empty = new_scene(); /* never committed */
    assert_int_equal(bg_render_gpu(r, empty, &set, &img), BG_ERR_NOT_COMMITTED);
    render_ok(r, s, &set, &img);
    assert_int_equal(bg_renderer_error(r), BG_ERR_INVALID_ARGUMENT);
    assert_string_equal(bg_renderer_error_message(r), first);
    bg_renderer_clear_error(r);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    assert_string_equal(bg_renderer_error_message(r), "");
    assert_int_equal(bg_render_gpu(r, empty, &set, &img), BG_ERR_NOT_COMMITTED);
    assert_int_equal(bg_renderer_error(r), BG_ERR_NOT_COMMITTED);
    bg_scene_destroy(empty);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* ---- degenerate scenes ---- */

static void empty_scene_is_background(void **state)
{
    enum { W = 24, H = 16 };
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = new_scene();
    assert_int_equal(bg_scene_commit(s), BG_OK);
    bg_render_settings set = bg_render_settings_init();
    set.background[0] = 0.25;
    set.background[1] = 0.5;
    set.background[2] = 1.0;
    float f[W * H * 4];
    bg_image fi = {W, H, BG_PIXEL_RGBA32F, 0, f};
    render_ok(r, s, &set, &fi);
    for (int i = 0; i < W * H; i++)
        if (!(f[4 * i] == 0.25f && f[4 * i + 1] == 0.5f && f[4 * i + 2] == 1.0f && f[4 * i + 3] == 1.0f))
            fail_msg("pixel (%d, %d) is (%g, %g, %g, %g), not the background", i % W, i / W, (double)f[4 * i],
                     (double)f[4 * i + 1], (double)f[4 * i + 2], (double)f[4 * i + 3]);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.passes[BG_PASS_INTERSECT], 0);
    assert_int_equal(st.levels, 0);
    /* the RGBA8 output is the CPU's encoding of the same colour */
    unsigned char g8[W * H * 4], c8[W * H * 4];
    bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, g8}, ci = {W, H, BG_PIXEL_RGBA8, 0, c8};
    render_ok(r, s, &set, &gi);
    assert_int_equal(bg_render_cpu(s, &set, &ci), BG_OK);
    for (int i = 0; i < W * H * 4; i++)
        if (abs(g8[i] - c8[i]) > 1)
            fail_msg("RGBA8 value %d: GPU %d, CPU %d", i, g8[i], c8[i]);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* No lights: ambient and emission only, as the CPU renders it, within paper_earth's thresholds
 * (the same textured sphere, plus an emissive box and a plane). */
static void unlit_scene_matches_cpu(void **state)
{
    enum { W = 96, H = 96 };
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = new_scene();
    uint32_t tex = 0, globe = 0, glow = 0, grey = 0, id = 0;
    assert_int_equal(scenes_add_earth_texture(s, &tex), BG_OK);
    bg_material m = bg_material_init();
    m.base.reflectance.texture = tex;
    m.ambient.r = m.ambient.g = m.ambient.b = 1.0;
    m.ambient.texture = tex;
    assert_int_equal(bg_scene_add_material(s, &m, &globe), BG_OK);
    m = bg_material_init();
    m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    m.emission.r = 0.9;
    m.emission.g = 0.5;
    m.emission.b = 0.1;
    assert_int_equal(bg_scene_add_material(s, &m, &glow), BG_OK);
    m = bg_material_init();
    m.ambient.r = 0.3;
    m.ambient.g = 0.35;
    m.ambient.b = 0.4;
    assert_int_equal(bg_scene_add_material(s, &m, &grey), BG_OK);
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_SPHERE, globe);
    d.transform = bg_mat4_rotate(bg_vec3_make(0, 0, 1), 23.4);
    assert_int_equal(bg_scene_add_object(s, &d, &id), BG_OK);
    d = bg_object_desc_init(BG_SHAPE_BOX, glow);
    d.transform = bg_mat4_mul(bg_mat4_translate(1.6, -0.6, 0.5),
                              bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 30), bg_mat4_scale(0.3, 0.3, 0.3)));
    assert_int_equal(bg_scene_add_object(s, &d, &id), BG_OK);
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), grey, &id), BG_OK);
    const double amb[3] = {0.6, 0.6, 0.6};
    assert_int_equal(bg_scene_set_ambient(s, amb), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0, 1, 4.5);
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    unsigned char g[W * H * 4], c[W * H * 4];
    bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, g}, ci = {W, H, BG_PIXEL_RGBA8, 0, c};
    bg_render_settings set = bg_render_settings_init();
    render_ok(r, s, &set, &gi);
    assert_int_equal(bg_render_cpu(s, &set, &ci), BG_OK);
    image_metrics met;
    assert_true(image_metrics_compare(&ci, &gi, GPU_SILHOUETTE_THRESHOLD, &met));
    char line[512], why[256];
    print_message("unlit: %s\n", image_metrics_format(&met, line, sizeof line));
    if (!gpu_threshold_check(gpu_threshold_of(SCENE_PAPER_EARTH), &met, why, sizeof why))
        fail_msg("unlit scene: %s", why);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    assert_int_equal(st.passes[BG_PASS_SHADOW], 0);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* ---- resources ---- */

/* Twenty renderers made, used and destroyed on one context: every block of the renderer's
 * allocator comes back, and MACS (whose allocator is counted too) holds no more after the twentieth
 * than after the first (its program cache may keep what the first one compiled). */
static void renderers_do_not_leak(void **state)
{
    enum { W = 32, H = 24 };
    util_alloc_counter mc = UTIL_ALLOC_COUNTER;
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(*state);
    cd.get_proc_address_user = macs_headless_proc_user(*state);
    cd.allocator.alloc = util_counted_alloc;
    cd.allocator.realloc = util_counted_realloc;
    cd.allocator.free = util_counted_free;
    cd.allocator.user = &mc;
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&cd, &ctx, NULL, 0), MACS_OK);
    bg_scene *s = util_scene(SCENE_GLASS);
    float px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, px};
    bg_render_settings set = bg_render_settings_init();
    int rounds = util_quick() ? 5 : 20;
    long macs_live_after_first = -1;
    for (int i = 0; i < rounds; i++) {
        util_alloc_counter bc = UTIL_ALLOC_COUNTER;
        bg_renderer_desc d = {0};
        d.context = ctx;
        d.allocator.alloc = util_counted_alloc;
        d.allocator.realloc = util_counted_realloc;
        d.allocator.free = util_counted_free;
        d.allocator.user = &bc;
        bg_renderer *r = NULL;
        assert_int_equal(bg_renderer_create(&d, &r, NULL, 0), BG_OK);
        render_ok(r, s, &set, &img);
        assert_true(bc.allocs > 0); /* the hooks are really used */
        bg_renderer_destroy(r);
        if (bc.allocs != bc.frees)
            fail_msg("renderer %d: %ld allocations, %ld frees", i, bc.allocs, bc.frees);
        long live = mc.allocs - mc.frees;
        if (i == 0)
            macs_live_after_first = live;
        else if (live != macs_live_after_first)
            fail_msg("after renderer %d MACS holds %ld blocks, after the first %ld", i, live, macs_live_after_first);
    }
    bg_scene_destroy(s);
    macs_context_destroy(ctx);
    assert_int_equal(mc.allocs, mc.frees);
}

/* An allocator that fails at creation makes creation fail cleanly. */
static void *no_alloc(size_t size, void *user)
{
    (void)size;
    (void)user;
    return NULL;
}

static void renderer_allocation_failure(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer_desc d = {0};
    d.context = ctx;
    d.allocator.alloc = no_alloc;
    d.allocator.free = util_counted_free;
    util_alloc_counter c = UTIL_ALLOC_COUNTER;
    d.allocator.user = &c;
    bg_renderer *r = (bg_renderer *)ctx;
    assert_int_equal(bg_renderer_create(&d, &r, NULL, 0), BG_ERR_OUT_OF_MEMORY);
    assert_null(r);
    /* half a set of hooks is a caller mistake */
    d.allocator.free = NULL;
    assert_int_equal(bg_renderer_create(&d, &r, NULL, 0), BG_ERR_INVALID_ARGUMENT);
    assert_null(r);
    macs_context_destroy(ctx);
}

/* What a logger was last handed, and how often at each level. */
typedef struct log_record {
    int errors, others;
    char last[512];
} log_record;

static void record_log(bg_log_level level, const char *message, void *user)
{
    log_record *l = user;
    if (level == BG_LOG_ERROR)
        l->errors++;
    else
        l->others++;
    snprintf(l->last, sizeof l->last, "%s", message);
}

/* One failed creation: the status, no renderer, and the reason naming `names` both in the
 * caller's buffer and (when the desc has a logger) at the logger, as one error. */
static void assert_create_fails(const bg_renderer_desc *d, bool with_out, bg_status want, const char *names)
{
    log_record log = {0, 0, ""};
    bg_renderer_desc copy = {0};
    if (d) {
        copy = *d;
        copy.logger.func = record_log;
        copy.logger.user = &log;
    }
    char message[256] = "unchanged";
    bg_renderer *r = (bg_renderer *)message; /* must be reset to NULL on failure */
    assert_int_equal(bg_renderer_create(d ? &copy : NULL, with_out ? &r : NULL, message, sizeof message), want);
    if (with_out)
        assert_null(r);
    if (!strstr(message, names) || !strstr(message, "bg_renderer_create"))
        fail_msg("the message \"%s\" does not name %s", message, names);
    if (d) {
        assert_int_equal(log.errors, 1);
        assert_int_equal(log.others, 0);
        assert_string_equal(log.last, message);
    }
    /* a tiny buffer gets a truncated, terminated message; none at all is fine */
    char tiny[4] = "xxx";
    assert_int_equal(bg_renderer_create(d ? &copy : NULL, with_out ? &r : NULL, tiny, sizeof tiny), want);
    assert_int_equal(strlen(tiny), 3);
    assert_int_equal(bg_renderer_create(d ? &copy : NULL, with_out ? &r : NULL, NULL, 0), want);
}

static void creation_failures_say_why(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    bg_renderer_desc d = {0};
    assert_create_fails(NULL, true, BG_ERR_INVALID_ARGUMENT, "desc");
    assert_create_fails(&d, true, BG_ERR_INVALID_ARGUMENT, "desc->context");
    d.context = ctx;
    assert_create_fails(&d, false, BG_ERR_INVALID_ARGUMENT, "out_renderer");
    util_alloc_counter c = UTIL_ALLOC_COUNTER;
    d.allocator.alloc = no_alloc;
    d.allocator.user = &c;
    assert_create_fails(&d, true, BG_ERR_INVALID_ARGUMENT, "desc->allocator"); /* alloc without free */
    d.allocator.free = util_counted_free;
    assert_create_fails(&d, true, BG_ERR_OUT_OF_MEMORY, "desc->allocator");
    /* success leaves an empty message */
    memset(&d.allocator, 0, sizeof d.allocator);
    char message[64] = "unchanged";
    bg_renderer *r = NULL;
    assert_int_equal(bg_renderer_create(&d, &r, message, sizeof message), BG_OK);
    assert_string_equal(message, "");
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

/* ---- GPU out of memory ---- */

/* A caller who forgot to make the GL context current hears that, not "a shader failed to compile"
 * with an empty log; once it is current again the same renderer renders. */
static void no_current_context(void **state)
{
    macs_headless *h = *state;
    macs_context *ctx = util_context(h, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = small_scene();
    unsigned char px[32 * 24 * 4];
    bg_image img = {32, 24, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init();
    util_release_current();
    bg_status st = bg_render_gpu(r, s, &set, &img);
    assert_int_equal(macs_headless_make_current(h), MACS_OK);
    assert_int_not_equal(st, BG_OK);
    const char *msg = bg_renderer_error_message(r);
    if (!strstr(msg, "no OpenGL context is current"))
        fail_msg("unclear message without a current context: \"%s\"", msg);
    bg_renderer_clear_error(r);
    macs_context_clear_error(ctx);
    render_ok(r, s, &set, &img);
    assert_centre_drawn(px, 32, 24);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

static void gpu_out_of_memory_is_reported_and_recoverable(void **state)
{
    enum { W = 48, H = 32 };
    macs_context *ctx = util_oom_context(*state);
    bg_scene *s = util_scene(SCENE_GLASS);
    bg_render_settings set = bg_render_settings_init();
    float px[W * H * 4], want[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, px};

    bg_renderer *r = util_renderer(ctx);
    util_oom_start(-1);
    bg_status st = bg_render_gpu(r, s, &set, &img);
    util_oom_stop();
    assert_true(util_oom_injected() > 0); /* the render did allocate GPU memory */
    if (st != BG_ERR_GPU_OUT_OF_MEMORY)
        fail_msg("render under GL_OUT_OF_MEMORY returned %s (%s)", bg_status_string(st), bg_renderer_error_message(r));
    assert_int_equal(bg_renderer_error(r), BG_ERR_GPU_OUT_OF_MEMORY);
    assert_true(strlen(bg_renderer_error_message(r)) > 0);
    bg_renderer_clear_error(r);
    macs_context_clear_error(ctx);

    /* the same renderer renders once memory is back, exactly as a fresh one does */
    render_ok(r, s, &set, &img);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    bg_renderer *fresh = util_renderer(ctx);
    bg_image wi = {W, H, BG_PIXEL_RGBA32F, 0, want};
    render_ok(fresh, s, &set, &wi);
    /* Equal on any conforming driver: programs of the same source strings on the same inputs in the
     * same order (GL 2.1 appendix A, rule 4). */
    assert_memory_equal(px, want, sizeof px);
    bg_renderer_destroy(fresh);

    /* running out again later, with everything already allocated at this size, is fine too: a new
     * size needs new textures */
    bg_image small = {W / 2, H / 2, BG_PIXEL_RGBA32F, 0, px};
    util_oom_start(-1);
    st = bg_render_gpu(r, s, &set, &small);
    util_oom_stop();
    assert_int_equal(st, BG_ERR_GPU_OUT_OF_MEMORY);
    bg_renderer_clear_error(r);
    render_ok(r, s, &set, &img);
    assert_memory_equal(px, want, sizeof px);

    bg_renderer_destroy(r);
    bg_scene_destroy(s);
    macs_context_destroy(ctx);
}

/* Every message of a failed call begins with that call's name, once, however deep the failure: GPU
 * memory running out inside a plan reads "bg_render_gpu: ..." under bg_render_gpu and
 * "bg_render_gpu_to_texture: ..." under bg_render_gpu_to_texture (the renderer's sink writes the
 * name the entry point gave it). */
static void assert_named_once(const bg_renderer *r, const char *entry)
{
    const char *message = bg_renderer_error_message(r);
    size_t n = strlen(entry);
    if (strncmp(message, entry, n) != 0 || strncmp(message + n, ": ", 2) != 0)
        fail_msg("a failure of %s reads: %s", entry, message);
    if (strstr(message + n, "bg_render_gpu:") || strstr(message + n, "bg_render_gpu_to_texture:"))
        fail_msg("a failure of %s names an entry point twice: %s", entry, message);
}

static void each_entry_point_names_itself(void **state)
{
    enum { W = 16, H = 16 };
    macs_context *ctx = util_oom_context(*state);
    bg_scene *s = small_scene();
    bg_render_settings set = bg_render_settings_init();
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    macs_texture_desc td = {0};
    td.width = W;
    td.height = H;
    macs_texture *target = NULL;
    assert_int_equal(macs_texture_create(ctx, &td, &target), MACS_OK);

    bg_renderer *r = util_renderer(ctx);
    util_oom_start(-1);
    bg_status st = bg_render_gpu(r, s, &set, &img);
    util_oom_stop();
    assert_int_equal(st, BG_ERR_GPU_OUT_OF_MEMORY);
    assert_named_once(r, "bg_render_gpu");
    bg_renderer_destroy(r);
    macs_context_clear_error(ctx);

    /* The fused plan writes the caller's texture without a texture of its own: the multipass's
     * targets run out. */
    set.gpu_plan = BG_PLAN_MULTIPASS;
    r = util_renderer(ctx);
    util_oom_start(-1);
    st = bg_render_gpu_to_texture(r, s, &set, target);
    util_oom_stop();
    assert_int_equal(st, BG_ERR_GPU_OUT_OF_MEMORY);
    assert_named_once(r, "bg_render_gpu_to_texture");
    bg_renderer_clear_error(r);
    macs_context_clear_error(ctx);

    /* The same renderer, and a failure the entry point's own checks find. */
    assert_int_equal(bg_render_gpu(r, s, &set, NULL), BG_ERR_INVALID_ARGUMENT);
    assert_named_once(r, "bg_render_gpu");
    bg_renderer_clear_error(r);
    assert_int_equal(bg_render_gpu_to_texture(r, s, &set, NULL), BG_ERR_INVALID_ARGUMENT);
    assert_named_once(r, "bg_render_gpu_to_texture");

    bg_renderer_destroy(r);
    macs_texture_destroy(target);
    bg_scene_destroy(s);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(null_arguments),
        cmocka_unit_test(uncommitted_scene),
        cmocka_unit_test(image_sizes),
        cmocka_unit_test(bad_settings),
        cmocka_unit_test(first_error_is_sticky),
        cmocka_unit_test(empty_scene_is_background),
        cmocka_unit_test(unlit_scene_matches_cpu),
        cmocka_unit_test(renderers_do_not_leak),
        cmocka_unit_test(renderer_allocation_failure),
        cmocka_unit_test(creation_failures_say_why),
        cmocka_unit_test(no_current_context),
        cmocka_unit_test(gpu_out_of_memory_is_reported_and_recoverable),
        cmocka_unit_test(each_entry_point_names_itself),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
