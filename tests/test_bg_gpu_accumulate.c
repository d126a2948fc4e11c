/* Progressive accumulation (bg_accumulation, docs/gpu_pipeline.md "Accumulation"): after N samples,
 * added one at a time or in chunks, the resolved image is bg_render_gpu's at samples = N bit for bit,
 * on every plan, in RGBA8 and RGBA32F, and with pixels the CPU reference renders (walks that run
 * out); the resolve into a texture gives the same bytes; a cancelled call and every refused argument
 * leave the sum as it was; a camera move compiles no program. */
#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 48, H = 36, N = 4 };

static const bg_gpu_plan plans[] = {BG_PLAN_FUSED_TREE, BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
static const char *const plan_name[] = {"tree", "fused", "multipass"};
#define PLANS ((int)(sizeof plans / sizeof plans[0]))

/* The accumulation's resolve into a fresh image of format (RGBA8 or RGBA32F), malloc'd. */
static void *resolved(bg_renderer *r, const bg_accumulation *a, const bg_render_settings *set, bg_pixel_format f)
{
    size_t texel = f == BG_PIXEL_RGBA32F ? 16 : 4;
    void *px = calloc(W * H, texel);
    assert_non_null(px);
    bg_image img = {W, H, f, 0, px};
    util_expect_render_ok(r, bg_accumulation_resolve(r, a, set, &img), "bg_accumulation_resolve");
    return px;
}

static void *rendered(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_pixel_format f)
{
    size_t texel = f == BG_PIXEL_RGBA32F ? 16 : 4;
    void *px = calloc(W * H, texel);
    assert_non_null(px);
    bg_image img = {W, H, f, 0, px};
    util_expect_render_ok(r, bg_render_gpu(r, s, set, &img), "bg_render_gpu");
    return px;
}

/* N samples of s on plan: one at a time and then 1 + (N - 1), each against bg_render_gpu at N, in
 * RGBA8 and RGBA32F, and the texture resolve against the image one. */
static void same_as_render(bg_scene *s, int k, const char *label)
{
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = util_plan_settings(plans[k], N);
    unsigned char *want8 = rendered(r, s, &set, BG_PIXEL_RGBA8);
    float *want32 = rendered(r, s, &set, BG_PIXEL_RGBA32F);
    bg_accumulation *a = NULL;
    util_expect_render_ok(r, bg_accumulation_create(r, W, H, &a), "bg_accumulation_create");
    for (int i = 0; i < N; i++)
        util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, i, 1), "one sample");
    assert_int_equal(bg_accumulation_samples(a), N);
    unsigned char *got8 = resolved(r, a, &set, BG_PIXEL_RGBA8);
    float *got32 = resolved(r, a, &set, BG_PIXEL_RGBA32F);
    /* Equal on any conforming driver: bg_render_gpu sums its samples with the same sample and sum
     * passes in the same order (samples.c, accumulate.c), so both run programs of the same source
     * strings on the same inputs, and the RGBA32F sum stores each float as it is (GL 2.1 appendix A, rule 4). */
    assert_memory_equal(got8, want8, W * H * 4);
    assert_memory_equal(got32, want32, W * H * 16);
    free(got8);
    free(got32);

    util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 0, 1), "start over");
    assert_int_equal(bg_accumulation_samples(a), 1);
    util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 1, N - 1), "the rest");
    got8 = resolved(r, a, &set, BG_PIXEL_RGBA8);
    assert_memory_equal(got8, want8, W * H * 4);

    /* The resolve on the GPU, into an RGBA8 texture: the same bytes (rows bottom first there). */
    macs_texture_desc td;
    memset(&td, 0, sizeof td);
    td.width = W;
    td.height = H;
    td.format = MACS_FORMAT_RGBA8;
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(util_fx.ctx, &td, &t), MACS_OK);
    util_expect_render_ok(r, bg_accumulation_resolve_to_texture(r, a, &set, t), "bg_accumulation_resolve_to_texture");
    unsigned char *tex = malloc(W * H * 4);
    assert_non_null(tex);
    assert_int_equal(macs_texture_read(t, tex, 0), MACS_OK);
    /* The texture resolve gives the host's bytes exactly: the exact-bytes pass compares the float sum
     * with the host's own thresholds (docs/gpu_pipeline.md, "Exact bytes"); before it, the shader's
     * float pow moved one byte of paper_earth_shadow's 6912 in the progressive sample order. */
    int differ = 0;
    for (int y = 0; y < H; y++)
        for (int i = 0; i < W * 4; i++)
            differ += tex[(H - 1 - y) * W * 4 + i] != got8[y * W * 4 + i];
    print_message("%s (%s): %d samples one by one and in two calls equal bg_render_gpu's; the texture resolve "
                  "differs in %d bytes\n", label, plan_name[k], N, differ);
    assert_int_equal(differ, 0);
    macs_texture_destroy(t);
    free(tex);
    free(got8);
    bg_accumulation_destroy(a);
    free(want8);
    free(want32);
    bg_renderer_destroy(r);
}

static void every_plan_equals_render(void **state)
{
    (void)state;
    static const scene_id scenes[] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS, SCENE_TEXTURED_ANISO};
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        bg_scene *s = util_scene(scenes[i]);
        for (int k = 0; k < PLANS; k++)
            same_as_render(s, k, scenes_name(scenes[i]));
        bg_scene_destroy(s);
    }
}

/* Pixels whose walks run out come from the CPU reference, for all their samples, in the sum too. */
static void cpu_pixels_join_the_sum(void **state)
{
    (void)state;
    bg_scene *s = util_triangle_stack_scene();
    same_as_render(s, 0, "triangle stack");
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = util_plan_settings(BG_PLAN_FUSED_TREE, N);
    bg_accumulation *a = NULL;
    util_expect_render_ok(r, bg_accumulation_create(r, W, H, &a), "bg_accumulation_create");
    util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 0, N), "N samples");
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    print_message("triangle stack: %llu CPU pixels, each for its %d samples\n", (unsigned long long)st.fallback_pixels, N);
    assert_true(st.fallback_pixels > 0);
    bg_accumulation_destroy(a);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

static bool cancel_after_one(double fraction, void *user)
{
    int *calls = user;
    (void)fraction;
    return (*calls)++ < 1;
}

/* A cancelled call and every refused argument leave the sum, its count and the resolved image. */
static void refusals_and_cancels_change_nothing(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    bg_renderer *r = util_renderer(util_fx.ctx), *other = util_renderer(util_fx.ctx);
    bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, N);
    bg_accumulation *a = NULL, *b = NULL;
    util_expect_render_ok(r, bg_accumulation_create(r, W, H, &a), "create");
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_accumulation_resolve(r, a, &set, &img), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_renderer_error_message(r), "no samples"));
    util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 0, 2), "two samples");
    unsigned char *before = resolved(r, a, &set, BG_PIXEL_RGBA8);

    bg_renderer_clear_error(r);
    int calls = 0;
    bg_render_settings cancelling = set;
    cancelling.progress = cancel_after_one;
    cancelling.progress_user = &calls;
    /* A cancelled or refused call draws nothing into the sum: equal whatever the driver. */
    assert_int_equal(bg_render_gpu_accumulate(r, s, &cancelling, a, 2, 2), BG_ERR_CANCELLED);
    print_message("cancelled: %s\n", bg_renderer_error_message(r));
    assert_int_equal(bg_accumulation_samples(a), 2);
    unsigned char *after = resolved(r, a, &set, BG_PIXEL_RGBA8);
    assert_memory_equal(after, before, W * H * 4);
    free(after);

    bg_render_settings eight = util_plan_settings(BG_PLAN_AUTO, 8);
    struct {
        bg_status st;
        const char *words;
    } refused[10];
    int n = 0;
#define REFUSE(call, words_)                                                                                          \
    do {                                                                                                           \
        bg_renderer_clear_error(r);                                                                                \
        refused[n].st = (call);                                                                                    \
        refused[n].words = (words_);                                                                               \
        assert_int_not_equal(refused[n].st, BG_OK);                                                                \
        if (!strstr(bg_renderer_error_message(r), refused[n].words))                                                \
            fail_msg("\"%s\" lacks \"%s\"", bg_renderer_error_message(r), refused[n].words);                     \
        n++;                                                                                                       \
    } while (0)
    REFUSE(bg_render_gpu_accumulate(r, NULL, &set, a, 2, 1), "scene is NULL");
    REFUSE(bg_render_gpu_accumulate(r, s, &set, NULL, 2, 1), "accumulation is NULL");
    REFUSE(bg_render_gpu_accumulate(r, s, &set, a, 1, 1), "first = 1, but the accumulation holds 2 samples");
    REFUSE(bg_render_gpu_accumulate(r, s, &set, a, 2, 0), "are not within the 4 of settings.samples");
    REFUSE(bg_render_gpu_accumulate(r, s, &set, a, 2, 3), "are not within the 4 of settings.samples");
    /* Ends past INT_MAX are written as they are, not wrapped to a negative number. */
    REFUSE(bg_render_gpu_accumulate(r, s, &set, a, 1, INT_MAX), "[1, 2147483648) are not within");
    REFUSE(bg_render_gpu_accumulate(r, s, &set, a, INT_MAX, 1), "[2147483647, 2147483648) are not within");
    REFUSE(bg_render_gpu_accumulate(r, s, &eight, a, 2, 1), "of the pattern of 4");
    util_expect_render_ok(other, bg_accumulation_create(other, W, H, &b), "another renderer's");
    REFUSE(bg_render_gpu_accumulate(r, s, &set, b, 0, 1), "made by another renderer");
    bg_image small = {W - 1, H, BG_PIXEL_RGBA8, 0, px};
    REFUSE(bg_accumulation_resolve(r, a, &set, &small), "image is 47x36, the accumulation 48x36");
#undef REFUSE
    assert_int_equal(bg_accumulation_samples(a), 2);
    assert_int_equal(bg_accumulation_samples(b), 0);
    after = resolved(r, a, &set, BG_PIXEL_RGBA8);
    assert_memory_equal(after, before, W * H * 4);
    free(after);
    free(before);

    bg_accumulation *c = NULL;
    assert_int_equal(bg_accumulation_create(r, 0, H, &c), BG_ERR_INVALID_ARGUMENT);
    assert_null(c);
    assert_int_equal(bg_accumulation_create(r, W, H, NULL), BG_ERR_INVALID_ARGUMENT);
    bg_accumulation_destroy(NULL);
    bg_accumulation_destroy(b);
    bg_accumulation_destroy(a);
    bg_renderer_destroy(other);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* After the first frame, starting over from a moved camera compiles nothing. */
static void a_camera_move_compiles_nothing(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_GLASS);
    for (int k = 0; k < PLANS; k++) {
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_settings set = util_plan_settings(plans[k], N);
        bg_accumulation *a = NULL;
        util_expect_render_ok(r, bg_accumulation_create(r, W, H, &a), "create");
        util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 0, 2), "first frame");
        bg_camera c = bg_camera_init();
        c.position = bg_vec3_make(1.0 + k, 2.0, 9.0);
        c.look_at = bg_vec3_make(0.0, 0.5, 0.0);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        uint64_t compiled = macs_context_programs_compiled(util_fx.ctx);
        util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 0, 1), "moved");
        util_expect_render_ok(r, bg_render_gpu_accumulate(r, s, &set, a, 1, 1), "at rest");
        bg_render_stats st;
        bg_renderer_get_stats(r, &st);
        assert_int_equal(st.programs_compiled, 0);
        assert_int_equal(macs_context_programs_compiled(util_fx.ctx), compiled);
        bg_accumulation_destroy(a);
        bg_renderer_destroy(r);
    }
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(refusals_and_cancels_change_nothing),
        cmocka_unit_test(a_camera_move_compiles_nothing),
        cmocka_unit_test(every_plan_equals_render),
        cmocka_unit_test(cpu_pixels_join_the_sum),
    };
    return cmocka_run_group_tests_name("bg_gpu_accumulate", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
