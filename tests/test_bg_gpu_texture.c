/* Frames that end in a texture (bg_render_gpu_to_texture): for every plan (fused, multipass, the
 * fused tree) and every target format, the texture read back is bg_render_gpu's image, exactly
 * (RGBA16F: that image's RGBA32F radiance rounded to half), with the texture's row 0 the image's
 * bottom row; no image read-back in the fused and multipass plans, and only the one-bit marks in
 * the tree's; tree pixels whose walks ran out still come from the CPU reference; a caller's own GL
 * texture works as the target and outlives MACS's wrap; bad targets are refused by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/gpu/shared/shared.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_raw_gl.h"

/* Not a multiple of 32, so the tree's marks have a partial texel at each row's end. */
enum { W = 70, H = 45 };

static util_raw_gl raw;

static int setup(void **state)
{
    util_gpu_group_setup(state);
    util_raw_gl_load(util_fx.headless, &raw);
    return 0;
}

static const char *format_name(macs_format f)
{
    return f == MACS_FORMAT_RGBA8 ? "RGBA8" : f == MACS_FORMAT_RGBA16F ? "RGBA16F" : "RGBA32F";
}

/* The spacing of half floats around v (2^-24 below the smallest normal, 2^-14). */
static double half_spacing(double v)
{
    double a = fabs(v);
    if (a < 6.103515625e-05)
        return 5.9604644775390625e-08;
    int e = 0;
    frexp(a, &e); /* a = m 2^e, m in [0.5, 1) */
    return ldexp(1.0, e - 1 - 10);
}

/* Equal on any conforming driver: a frame into a texture runs the passes of the frame read back, on
 * the same inputs, and the texture is what the last of them wrote (GL 2.1 appendix A, rule 4).
 * Fails unless the texture's texels (rows bottom first) are the image's pixels (rows top first)
 * with the rows reversed: exactly for RGBA8 and RGBA32F; for RGBA16F within one half-float step of
 * the RGBA32F value (GL leaves the rounding of a float output to half to the implementation). */
static void expect_texture_is_image(const void *texels, macs_format format, const bg_image *img, const char *label)
{
    size_t pixel = format == MACS_FORMAT_RGBA8 ? 4 : 16;
    size_t row = (size_t)img->width * pixel;
    for (int y = 0; y < img->height; y++) {
        const unsigned char *t = (const unsigned char *)texels + (size_t)y * row;
        const unsigned char *p = (const unsigned char *)img->pixels + (size_t)(img->height - 1 - y) * row;
        if (format != MACS_FORMAT_RGBA16F) {
            if (memcmp(t, p, row) == 0)
                continue;
            for (int x = 0; x < img->width; x++)
                if (memcmp(t + x * pixel, p + x * pixel, pixel) != 0)
                    fail_msg("%s: texel (%d, %d) differs from image pixel (%d, %d)", label, x, y, x,
                             img->height - 1 - y);
        }
        for (int i = 0; i < img->width * 4; i++) {
            float got, want;
            memcpy(&got, t + 4 * (size_t)i, sizeof got);
            memcpy(&want, p + 4 * (size_t)i, sizeof want);
            if (!(fabs((double)got - (double)want) <= half_spacing(want)))
                fail_msg("%s: texel (%d, %d) channel %d is %.9g, the image's RGBA32F %.9g", label, (i / 4), y, i % 4,
                         (double)got, (double)want);
        }
    }
}

static macs_texture *texture(macs_context *ctx, int w, int h, macs_format f)
{
    return util_texture(ctx, w, h, f);
}

static bg_render_stats render_texture(bg_renderer *r, bg_scene *s, const bg_render_settings *set, macs_texture *target,
                                      const char *label)
{
    bg_status st = bg_render_gpu_to_texture(r, s, set, target);
    if (st != BG_OK)
        fail_msg("%s: bg_render_gpu_to_texture: %s: %s (MACS: %s)", label, bg_status_string(st),
                 bg_renderer_error_message(r), macs_context_error_message(util_fx.ctx));
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    return stats;
}

/* Renders s into target with a renderer of its own, then with bg_render_gpu into an image of the
 * matching format, and compares them; the texture render must have read nothing back but what
 * readback_bytes says. Then renders into the image again, which must not have changed: the two
 * ends share the plan's cached passes. Returns the texture render's statistics. */
static bg_render_stats compare(bg_scene *s, const bg_render_settings *set, macs_texture *target, size_t readback_bytes,
                               const char *label)
{
    bg_renderer *r = util_renderer(util_fx.ctx);
    macs_format f = macs_texture_format(target);
    int w = 0, h = 0;
    macs_texture_size(target, &w, &h);
    bool bytes = f == MACS_FORMAT_RGBA8;
    size_t size = (size_t)w * (size_t)h * (bytes ? 4 : 16);
    unsigned char *first = malloc(size), *again = malloc(size), *texels = malloc(size);
    assert_non_null(first);
    assert_non_null(again);
    assert_non_null(texels);
    char what[96];
    snprintf(what, sizeof what, "%s into %s", label, format_name(f));

    bg_render_stats ts = render_texture(r, s, set, target, what);
    if (r->readback_size != readback_bytes)
        fail_msg("%s: the read-back buffer holds %zu bytes, want %zu", what, r->readback_size, readback_bytes);
    assert_int_equal(macs_texture_read(target, texels, 0), MACS_OK);
    bg_image img = {w, h, bytes ? BG_PIXEL_RGBA8 : BG_PIXEL_RGBA32F, 0, first};
    util_render_gpu(r, util_fx.ctx, s, set, &img, what);
    bg_render_stats is;
    bg_renderer_get_stats(r, &is);
    assert_int_equal(ts.plan, is.plan);
    assert_int_equal(ts.fallback_pixels, is.fallback_pixels);
    expect_texture_is_image(texels, f, &img, what);

    img.pixels = again;
    render_texture(r, s, set, target, what);
    util_render_gpu(r, util_fx.ctx, s, set, &img, what);
    assert_memory_equal(first, again, size); /* the same frame again: GL 2.1 appendix A, rule 4 */
    print_message("%-40s plan %d, %llu CPU pixels, same as bg_render_gpu\n", what, (int)ts.plan,
                  (unsigned long long)ts.fallback_pixels);
    free(first);
    free(again);
    free(texels);
    bg_renderer_destroy(r);
    return ts;
}

/* Every target format, RGBA8 in both encodings, for one plan; the statistics of each frame are
 * checked by check. */
static void every_format(bg_scene *s, bg_gpu_plan plan, size_t readback_bytes, const char *label,
                         void (*check)(const bg_render_stats *))
{
    static const macs_format formats[] = {MACS_FORMAT_RGBA8, MACS_FORMAT_RGBA8, MACS_FORMAT_RGBA32F,
                                          MACS_FORMAT_RGBA16F};
    for (int i = 0; i < 4; i++) {
        bg_render_settings set = bg_render_settings_init();
        set.gpu_plan = plan;
        if (i == 1)
            set.encoding = BG_ENCODING_LINEAR;
        macs_texture *t = texture(util_fx.ctx, W, H, formats[i]);
        char what[64];
        snprintf(what, sizeof what, "%s%s", label, i == 1 ? " (linear)" : "");
        bg_render_stats st = compare(s, &set, t, readback_bytes, what);
        assert_int_equal(st.plan, plan);
        if (check)
            check(&st);
        macs_texture_destroy(t);
    }
}

static void one_fused_pass(const bg_render_stats *st)
{
    assert_int_equal(st->passes[BG_PASS_INTERSECT], 1);
    assert_int_equal(st->passes[BG_PASS_RESOLVE], 0);
    assert_int_equal(st->fallback_pixels, 0);
}

static void resolved_once(const bg_render_stats *st)
{
    assert_int_equal(st->passes[BG_PASS_RESOLVE], 1);
}

/* ---- the plans ---- */

static void fused_plan(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    every_format(s, BG_PLAN_FUSED, 0, "paper_earth_shadow fused", one_fused_pass);
    bg_scene_destroy(s);
}

static void multipass_plan(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_MIRROR);
    every_format(s, BG_PLAN_MULTIPASS, 0, "mirror multipass", resolved_once);
    bg_scene_destroy(s);
}

/* What the tree's frame reads back: the marks (4 bytes per 32 pixels of a row) and one row of the
 * target's texels for the CPU reference's pixels, 16 bytes each whatever the format. */
static size_t marks_bytes(int w, int h)
{
    return (size_t)((w + 31) / 32) * 4 * (size_t)h + (size_t)w * 16;
}

static void tree_plan(void **state)
{
    (void)state;
    scene_params p = {0};
    p.spheres = 16;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(scenes_build_ex(SCENE_MANY_SPHERES, &p, s), BG_OK);
    assert_true(bgi_scene_committed(s)->tree_count >= 8);
    every_format(s, BG_PLAN_FUSED_TREE, marks_bytes(W, H), "16 spheres tree", one_fused_pass);
    bg_scene_destroy(s);
}

/* The pixels the shader gave up on are in the texture as the CPU reference renders them (the
 * comparison with bg_render_gpu, which renders them the same way, is exact), none left black
 * with the shader's alpha-0 mark. */
static void tree_fallback_pixels(void **state)
{
    (void)state;
    enum { TW = 48, TH = 36 };
    bg_scene *s = util_tube_scene();
    static const macs_format formats[] = {MACS_FORMAT_RGBA8, MACS_FORMAT_RGBA32F, MACS_FORMAT_RGBA16F};
    for (int i = 0; i < 3; i++) {
        bg_render_settings set = bg_render_settings_init();
        macs_texture *t = texture(util_fx.ctx, TW, TH, formats[i]);
        bg_render_stats st = compare(s, &set, t, marks_bytes(TW, TH), "tube");
        assert_int_equal(st.plan, BG_PLAN_FUSED_TREE);
        if (st.fallback_pixels == 0 || st.fallback_pixels == (uint64_t)TW * TH)
            fail_msg("tube into %s: %llu CPU pixels; some (not all) should be", format_name(formats[i]),
                     (unsigned long long)st.fallback_pixels);
        float texels[TW * TH * 4];
        unsigned char bytes[TW * TH * 4];
        assert_int_equal(macs_texture_read(t, i == 0 ? (void *)bytes : (void *)texels, 0), MACS_OK);
        for (int k = 0; k < TW * TH; k++)
            if (i == 0 ? bytes[4 * k + 3] != 255 : texels[4 * k + 3] != 1.0f)
                fail_msg("tube into %s: texel %d kept the shader's mark", format_name(formats[i]), k);
        macs_texture_destroy(t);
    }
    bg_scene_destroy(s);
}

/* The same for a mesh scene in every plan: the pixels whose mesh walks ran out arrive in the
 * texture as the CPU reference renders them. */
static void mesh_fallback_pixels(void **state)
{
    (void)state;
    enum { TW = 24, TH = 24 }; /* small: a pixel that runs out walks the whole budget, then the CPU's */
    bg_scene *s = util_triangle_stack_scene();
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED_TREE, BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
    static const macs_format formats[] = {MACS_FORMAT_RGBA8, MACS_FORMAT_RGBA32F};
    for (int p = 0; p < 3; p++)
        for (int i = 0; i < 2; i++) {
            bg_render_settings set = bg_render_settings_init();
            set.gpu_plan = plans[p];
            macs_texture *t = texture(util_fx.ctx, TW, TH, formats[i]);
            bg_render_stats st = compare(s, &set, t, marks_bytes(TW, TH), "triangle stack");
            assert_int_equal(st.plan, plans[p]);
            if (st.fallback_pixels == 0 || st.fallback_pixels == (uint64_t)TW * TH)
                fail_msg("triangle stack (plan %d) into %s: %llu CPU pixels; some (not all) should be", (int)plans[p],
                         format_name(formats[i]), (unsigned long long)st.fallback_pixels);
            macs_texture_destroy(t);
        }
    bg_scene_destroy(s);
}

/* ---- the caller's own GL texture ---- */

static void caller_gl_texture_as_target(void **state)
{
    (void)state;
    util_require_texture_size(util_fx.ctx, W, H);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    GLuint name = util_raw_texture(&raw, W, H, GL_RGBA8, GL_UNSIGNED_BYTE, NULL);
    macs_texture_wrap_desc d = {name, W, H, MACS_FORMAT_RGBA8, MACS_FILTER_LINEAR, MACS_WRAP_DEFAULT};
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_wrap(util_fx.ctx, &d, &t), MACS_OK);
    assert_int_equal(macs_texture_gl_name(t), name);
    bg_render_settings set = bg_render_settings_init();
    compare(s, &set, t, 0, "wrapped, auto plan");
    set.gpu_plan = BG_PLAN_MULTIPASS;
    compare(s, &set, t, 0, "wrapped, multipass");

    /* MACS forgets the wrap without deleting the texture, which holds the last frame for the
     * caller's own GL to draw. */
    unsigned char px[W * H * 4], texels[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &img, "wrapped, image");
    macs_texture_destroy(t);
    assert_true(raw.IsTexture(name));
    raw.BindTexture(GL_TEXTURE_2D, name);
    raw.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    raw.BindTexture(GL_TEXTURE_2D, 0);
    expect_texture_is_image(texels, MACS_FORMAT_RGBA8, &img, "the caller's texture after the wrap");
    raw.DeleteTextures(1, &name);
    assert_int_equal(raw.GetError(), GL_NO_ERROR);
    bg_scene_destroy(s);
}

/* ---- refusals ---- */

static void expect_refused(bg_renderer *r, bg_status st, bg_status want, const char *a, const char *b)
{
    const char *m = bg_renderer_error_message(r);
    if (st != want || !strstr(m, a) || (b && !strstr(m, b)))
        fail_msg("status %d (want %d), message \"%s\" should name \"%s\"%s%s", (int)st, (int)want, m, a,
                 b ? " and " : "", b ? b : "");
    bg_renderer_clear_error(r);
}

static void expect_wrap_refused(macs_status st, macs_status want, const char *a, const char *b)
{
    const char *m = macs_context_error_message(util_fx.ctx);
    if (st != want || !strstr(m, a) || (b && !strstr(m, b)))
        fail_msg("wrap: status %d (want %d), message \"%s\" should name \"%s\"%s%s", (int)st, (int)want, m, a,
                 b ? " and " : "", b ? b : "");
    macs_context_clear_error(util_fx.ctx);
}

static void bad_targets_are_refused(void **state)
{
    (void)state;
    util_require_texture_size(util_fx.ctx, W + 1, H); /* a 71-wide texture is refused by its width */
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_render_settings set = bg_render_settings_init();
    macs_texture *t = texture(util_fx.ctx, W, H, MACS_FORMAT_RGBA8);

    expect_refused(r, bg_render_gpu_to_texture(r, s, &set, NULL), BG_ERR_INVALID_ARGUMENT,
                   "bg_render_gpu_to_texture: target is NULL", NULL);
    expect_refused(r, bg_render_gpu_to_texture(r, NULL, &set, t), BG_ERR_INVALID_ARGUMENT, "scene is NULL", NULL);
    expect_refused(r, bg_render_gpu_to_texture(r, s, NULL, t), BG_ERR_INVALID_ARGUMENT, "settings is NULL", NULL);
    set.max_depth = -1;
    expect_refused(r, bg_render_gpu_to_texture(r, s, &set, t), BG_ERR_INVALID_ARGUMENT, "settings.max_depth", NULL);
    set = bg_render_settings_init();
    assert_int_equal(bg_render_gpu_to_texture(NULL, s, &set, t), BG_ERR_INVALID_ARGUMENT);

    /* A texture of another MACS context, even on the same GL context. */
    macs_context *other = util_context(util_fx.headless, NULL);
    macs_texture *foreign = texture(other, W, H, MACS_FORMAT_RGBA8);
    expect_refused(r, bg_render_gpu_to_texture(r, s, &set, foreign), BG_ERR_INVALID_ARGUMENT,
                   "target belongs to another macs_context", NULL);
    macs_context_destroy(other);

    bg_scene *empty = NULL;
    assert_int_equal(bg_scene_create(NULL, &empty), BG_OK);
    expect_refused(r, bg_render_gpu_to_texture(r, empty, &set, t), BG_ERR_NOT_COMMITTED,
                   "bg_render_gpu_to_texture: the scene was never committed", NULL);
    bg_scene_destroy(empty);

    /* A forced plan that cannot run says which entry point refused. */
    set.gpu_plan = BG_PLAN_FUSED;
    set.max_depth = 20; /* 2^21 - 1 rays a pixel without min_weight's pruning */
    set.min_weight = 0.0;
    bg_scene *glass = util_scene(SCENE_GLASS);
    expect_refused(r, (bg_render_gpu_to_texture)(r, glass, &set, t), BG_ERR_LIMIT,
                   "bg_render_gpu_to_texture: BG_PLAN_FUSED cannot render this frame", NULL);
    bg_scene_destroy(glass);
    set = bg_render_settings_init();

    /* Caller textures that cannot become targets are refused when wrapped: a size or format that is
     * not the texture's, a name that is no texture, a texture beyond the context's limits. */
    GLuint name = util_raw_texture(&raw, W, H, GL_RGBA8, GL_UNSIGNED_BYTE, NULL);
    macs_texture *wrapped = NULL;
    macs_texture_wrap_desc d = {name, W + 1, H, MACS_FORMAT_RGBA8, MACS_FILTER_DEFAULT, MACS_WRAP_DEFAULT};
    expect_wrap_refused(macs_texture_wrap(util_fx.ctx, &d, &wrapped), MACS_ERR_INVALID_ARGUMENT, "desc.width 71",
                        "width 70");
    d.width = W;
    d.format = MACS_FORMAT_RGBA32F;
    expect_wrap_refused(macs_texture_wrap(util_fx.ctx, &d, &wrapped), MACS_ERR_INVALID_ARGUMENT,
                        "desc.format RGBA32F", NULL);
    raw.DeleteTextures(1, &name);
    d.format = MACS_FORMAT_DEFAULT;
    expect_wrap_refused(macs_texture_wrap(util_fx.ctx, &d, &wrapped), MACS_ERR_INVALID_ARGUMENT, "desc.gl_name",
                        "glIsTexture");
    assert_null(wrapped);
    macs_limits caps = {0};
    caps.max_texture_size = 64;
    macs_context *small = util_context(util_fx.headless, &caps);
    GLuint big = util_raw_texture(&raw, 128, 16, GL_RGBA8, GL_UNSIGNED_BYTE, NULL);
    macs_texture_wrap_desc bd = {big, 0, 0, MACS_FORMAT_DEFAULT, MACS_FILTER_DEFAULT, MACS_WRAP_DEFAULT};
    assert_int_equal(macs_texture_wrap(small, &bd, &wrapped), MACS_ERR_LIMIT);
    assert_non_null(strstr(macs_context_error_message(small), "128x16"));
    raw.DeleteTextures(1, &big);
    macs_context_destroy(small);

    /* After all that the renderer renders, and keeps no hold on a target destroyed after its frame. */
    assert_int_equal(bg_render_gpu_to_texture(r, s, &set, t), BG_OK);
    macs_texture_destroy(t);
    t = texture(util_fx.ctx, W, H, MACS_FORMAT_RGBA32F);
    assert_int_equal(bg_render_gpu_to_texture(r, s, &set, t), BG_OK);
    assert_int_equal(bg_renderer_error(r), BG_OK);
    macs_texture_destroy(t);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fused_plan),
        cmocka_unit_test(multipass_plan),
        cmocka_unit_test(tree_plan),
        cmocka_unit_test(tree_fallback_pixels),
        cmocka_unit_test(mesh_fallback_pixels),
        cmocka_unit_test(caller_gl_texture_as_target),
        cmocka_unit_test(bad_targets_are_refused),
    };
    return cmocka_run_group_tests(tests, setup, util_gpu_group_teardown);
}
