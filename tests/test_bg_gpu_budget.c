/* The GL work of a cached frame (bg_render_stats.gl_work, counted by MACS at each GL call): the
 * budgets of docs/gpu_pipeline.md, "GL work per frame". A cached frame is the second of the same
 * scene on the same renderer: the scene committed and uploaded, every program built. The counts are
 * exact and the same on every driver, so they are asserted as equalities where the budget is exact. */
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
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 64, H = 48, N = 4 };

static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
static const char *const plan_name[] = {"fused", "tree", "multipass"};
#define PLANS ((int)(sizeof plans / sizeof plans[0]))

static void print_work(const char *label, const macs_work *w)
{
    print_message("%s: draws %llu, program binds %llu, framebuffer binds %llu, uniform calls %llu, uploaded %llu B, "
                  "read back %llu B, syncs %llu, programs compiled %llu\n",
                  label, (unsigned long long)w->draws, (unsigned long long)w->program_binds,
                  (unsigned long long)w->framebuffer_binds, (unsigned long long)w->uniform_calls,
                  (unsigned long long)w->upload_bytes, (unsigned long long)w->readback_bytes,
                  (unsigned long long)w->syncs, (unsigned long long)w->programs_compiled);
}

/* The GL work of the second of two renders of s into an image of format: the cached frame. */
static macs_work cached_frame(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_pixel_format f,
                              void *pixels)
{
    bg_image img = {W, H, f, 0, pixels};
    util_expect_render_ok(r, bg_render_gpu(r, s, set, &img), "first frame");
    util_expect_render_ok(r, bg_render_gpu(r, s, set, &img), "cached frame");
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    return st.gl_work;
}

/* The counters are MACS's, monotonic, and the stats are their difference over the call. */
static void stats_are_the_context_difference(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, 1);
    unsigned char px[W * H * 4];
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    macs_work before, after;
    macs_context_get_work(util_fx.ctx, &before);
    util_expect_render_ok(r, bg_render_gpu(r, s, &set, &img), "frame");
    macs_context_get_work(util_fx.ctx, &after);
    bg_render_stats st;
    bg_renderer_get_stats(r, &st);
    macs_work d = macs_work_since(&after, &before);
    assert_memory_equal(&d, &st.gl_work, sizeof d);
    print_work("paper_earth, first frame", &d);
    assert_true(d.draws > 0 && d.program_binds > 0 && d.framebuffer_binds > 0 && d.uniform_calls > 0);
    assert_true(d.upload_bytes > 0); /* the earth texture and the scene's data go up once */
    assert_int_equal(d.programs_compiled, st.programs_compiled);
    macs_work z;
    macs_context_get_work(NULL, &z);
    assert_int_equal(z.draws + z.syncs + z.readback_bytes, 0);
    /* A read of a texture counts its bytes and one sync, whoever asks. */
    macs_context_get_work(util_fx.ctx, &before);
    macs_context_finish(util_fx.ctx);
    macs_context_get_work(util_fx.ctx, &after);
    d = macs_work_since(&after, &before);
    assert_int_equal(d.syncs, 1);
    assert_int_equal(d.draws, 0);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* paper_earth at one sample into RGBA8: nothing uploaded or compiled, one wait, 4 bytes a pixel. */
static void one_sample_rgba8(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_renderer *r = util_renderer(util_fx.ctx);
    bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, 1);
    unsigned char px[W * H * 4];
    macs_work w = cached_frame(r, s, &set, BG_PIXEL_RGBA8, px);
    print_work("paper_earth, 1 sample, RGBA8, cached", &w);
    assert_int_equal(w.upload_bytes, 0);
    assert_int_equal(w.programs_compiled, 0);
    assert_int_equal(w.syncs, 1);
    assert_int_equal(w.readback_bytes, (uint64_t)W * H * 4);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* The float image: 16 bytes a pixel read back and no more, at one sample and at N. */
static void float_image(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_renderer *r = util_renderer(util_fx.ctx);
    float *px = malloc((size_t)W * H * 16);
    assert_non_null(px);
    for (int samples = 1; samples <= N; samples += N - 1) {
        bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, samples);
        macs_work w = cached_frame(r, s, &set, BG_PIXEL_RGBA32F, px);
        char label[64];
        snprintf(label, sizeof label, "paper_earth, %d sample(s), RGBA32F, cached", samples);
        print_work(label, &w);
        assert_int_equal(w.readback_bytes, (uint64_t)W * H * 16);
        assert_int_equal(w.syncs, 1);
        assert_int_equal(w.upload_bytes, 0);
        assert_int_equal(w.programs_compiled, 0);
    }
    free(px);
    bg_renderer_destroy(r);
    bg_scene_destroy(s);
}

/* A camera move: the camera is uniforms, so nothing goes up and nothing compiles. */
static void camera_move(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    for (int k = 0; k < PLANS; k++) {
        bg_renderer *r = util_renderer(util_fx.ctx);
        bg_render_settings set = util_plan_settings(plans[k], 1);
        unsigned char px[W * H * 4];
        bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
        util_expect_render_ok(r, bg_render_gpu(r, s, &set, &img), "first frame");
        bg_camera c = bg_camera_init();
        c.position = bg_vec3_make(1.0 + k, 2.0, 9.0);
        c.look_at = bg_vec3_make(0.0, 0.5, 0.0);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        util_expect_render_ok(r, bg_render_gpu(r, s, &set, &img), "moved");
        bg_render_stats st;
        bg_renderer_get_stats(r, &st);
        char label[64];
        snprintf(label, sizeof label, "paper_earth_shadow, %s, camera moved", plan_name[k]);
        print_work(label, &st.gl_work);
        /* The tree plan's nodes are camera-relative (fused/tree_textures.c): a move re-uploads the
         * node texture, the only upload beyond uniforms of any plan; the others upload nothing. */
        if (plans[k] == BG_PLAN_FUSED_TREE)
            assert_true(st.gl_work.upload_bytes > 0);
        else
            assert_int_equal(st.gl_work.upload_bytes, 0);
        assert_int_equal(st.gl_work.programs_compiled, 0);
        assert_int_equal(st.gl_work.syncs, 1);
        assert_int_equal(st.gl_work.readback_bytes, (uint64_t)W * H * 4);
        bg_renderer_destroy(r);
    }
    bg_scene_destroy(s);
}

/* The host's byte of a float sum s of n samples, as samples.c writes it. */
static int host_byte(float s, int n, bg_output_encoding e)
{
    return bgi_encode_channel(s / (float)n, e);
}

static float from_bits(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The exact resolve's premise, on the host: the byte of any sum is the number of thresholds it
 * reaches, which the shader's binary search finds. Checked at each threshold and its two float neighbours, and at 200000 spread sums per
 * (n, encoding), for sample counts a power of two and not. */
static void thresholds_count_bytes(void **state)
{
    (void)state;
    static const int counts[] = {2, 3, 4, 7, 16, 100, 256};
    uint32_t rng = 12345u;
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++)
        for (int e = 0; e < 2; e++) {
            int n = counts[i];
            bg_output_encoding enc = e ? BG_ENCODING_LINEAR : BG_ENCODING_SRGB;
            float t[256];
            t[0] = 0.0f;
            for (int k = 1; k < 256; k++) {
                t[k] = from_bits(bgi_gpu_exact_threshold(k, n, enc));
                assert_true(t[k] >= t[k - 1]);
                assert_true(host_byte(t[k], n, enc) >= k);
                assert_true(host_byte(from_bits(bgi_gpu_exact_threshold(k, n, enc) - 1u), n, enc) < k);
            }
            int wrong = 0;
            for (int j = 0; j < 200000; j++) {
                rng = rng * 1664525u + 1013904223u;
                /* Over [0, 1.25 n): every byte's range, and the clamp above it. */
                float s = (float)((double)(rng >> 8) / 16777216.0 * 1.25 * n);
                /* The shader's search: eight steps, 128 down to 1 (bg_stage_exact_bytes.glsl). */
                int b = 0;
                for (int step = 128; step >= 1; step /= 2)
                    b = s >= t[b + step] ? b + step : b;
                wrong += b != host_byte(s, n, enc);
            }
            assert_int_equal(wrong, 0);
        }
    print_message("thresholds of n = 2 .. 256 samples, sRGB and linear: every byte is the count of thresholds "
                  "reached\n");
}

/* N samples into RGBA8: the divide and the encoding on the GPU, 4 bytes a pixel read back, and each
 * byte the host's encoding of the RGBA32F image's value (sum / N in float), in both encodings. */
static void n_samples_rgba8(void **state)
{
    (void)state;
    static const scene_id scenes[] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW, SCENE_MIRROR, SCENE_GLASS,
                                      SCENE_TEXTURED_ANISO};
    float *want = malloc((size_t)W * H * 16);
    unsigned char *got = malloc((size_t)W * H * 4);
    assert_non_null(want);
    assert_non_null(got);
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        bg_scene *s = util_scene(scenes[i]);
        bg_renderer *r = util_renderer(util_fx.ctx);
        for (int e = 0; e < 2; e++) {
            bg_render_settings set = util_plan_settings(BG_PLAN_AUTO, N);
            set.encoding = e ? BG_ENCODING_LINEAR : BG_ENCODING_SRGB;
            macs_work w = cached_frame(r, s, &set, BG_PIXEL_RGBA8, got);
            bg_image fimg = {W, H, BG_PIXEL_RGBA32F, 0, want};
            util_expect_render_ok(r, bg_render_gpu(r, s, &set, &fimg), "float frame");
            int differ = 0;
            for (int p = 0; p < W * H; p++)
                for (int c = 0; c < 4; c++) {
                    int b = c == 3 ? 255 : bgi_encode_channel(want[p * 4 + c], set.encoding);
                    differ += got[p * 4 + c] != b;
                }
            char label[96];
            snprintf(label, sizeof label, "%s, %d samples, RGBA8 %s, cached (%d bytes differ from the host's)",
                     scenes_name(scenes[i]), N, e ? "linear" : "sRGB", differ);
            print_work(label, &w);
            assert_int_equal(differ, 0);
            assert_int_equal(w.upload_bytes, 0);
            assert_int_equal(w.programs_compiled, 0);
            assert_int_equal(w.syncs, 1);
            assert_int_equal(w.readback_bytes, (uint64_t)W * H * 4);
        }
        bg_renderer_destroy(r);
        bg_scene_destroy(s);
    }
    free(want);
    free(got);
}

/* Into an RGBA8 texture nothing comes back and nothing waits, at one sample and at N (the exact
 * resolve writes the target), on the plans without run-out marks to read; the tree plan reads its
 * packed marks once, at one sample or N: one pass more, one sync, ceil(W / 32) x H x 4 bytes. */
static void to_texture(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    macs_texture_desc td;
    memset(&td, 0, sizeof td);
    td.width = W;
    td.height = H;
    td.format = MACS_FORMAT_RGBA8;
    macs_texture *t = NULL;
    assert_int_equal(macs_texture_create(util_fx.ctx, &td, &t), MACS_OK);
    static const bg_gpu_plan unmarked[] = {BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
    for (int k = 0; k < 2; k++) {
        bg_renderer *r = util_renderer(util_fx.ctx);
        for (int samples = 1; samples <= N; samples += N - 1) {
            bg_render_settings set = util_plan_settings(unmarked[k], samples);
            util_expect_render_ok(r, bg_render_gpu_to_texture(r, s, &set, t), "first frame");
            util_expect_render_ok(r, bg_render_gpu_to_texture(r, s, &set, t), "cached frame");
            bg_render_stats st;
            bg_renderer_get_stats(r, &st);
            char label[96];
            snprintf(label, sizeof label, "paper_earth_shadow, %s, %d sample(s), to an RGBA8 texture, cached",
                     k ? "multipass" : "fused", samples);
            print_work(label, &st.gl_work);
            assert_int_equal(st.gl_work.readback_bytes, 0);
            assert_int_equal(st.gl_work.syncs, 0);
            assert_int_equal(st.gl_work.upload_bytes, 0);
            assert_int_equal(st.gl_work.programs_compiled, 0);
        }
        bg_renderer_destroy(r);
    }
    bg_renderer *r = util_renderer(util_fx.ctx);
    for (int samples = 1; samples <= N; samples += N - 1) {
        bg_render_settings set = util_plan_settings(BG_PLAN_FUSED_TREE, samples);
        util_expect_render_ok(r, bg_render_gpu_to_texture(r, s, &set, t), "first frame");
        util_expect_render_ok(r, bg_render_gpu_to_texture(r, s, &set, t), "cached frame");
        bg_render_stats st;
        bg_renderer_get_stats(r, &st);
        char label[96];
        snprintf(label, sizeof label, "paper_earth_shadow, tree, %d sample(s), to an RGBA8 texture, cached", samples);
        print_work(label, &st.gl_work);
        uint64_t n = (uint64_t)samples, multi = samples > 1;
        assert_int_equal(st.gl_work.readback_bytes, (uint64_t)((W + 31) / 32) * H * 4);
        assert_int_equal(st.gl_work.syncs, 1);
        assert_int_equal(st.gl_work.upload_bytes, 0);
        assert_int_equal(st.gl_work.programs_compiled, 0);
        assert_int_equal(st.gl_work.draws, multi ? 2 * n + 2 : 2);
        assert_int_equal(st.fallback_pixels, 0);
    }
    bg_renderer_destroy(r);
    macs_texture_destroy(t);
    bg_scene_destroy(s);
}

/* Each plan's cached frame of the paper scenes at 1 and 16 samples into RGBA8: the table of
 * docs/gpu_pipeline.md, "GL work per frame", held where it is exact. */
static void plan_budgets(void **state)
{
    (void)state;
    static const scene_id scenes[] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW};
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        bg_scene *s = util_scene(scenes[i]);
        for (int k = 0; k < PLANS; k++) {
            bg_renderer *r = util_renderer(util_fx.ctx);
            for (int samples = 1; samples <= 16; samples += 15) {
                bg_render_settings set = util_plan_settings(plans[k], samples);
                macs_work w = cached_frame(r, s, &set, BG_PIXEL_RGBA8, px);
                char label[96];
                snprintf(label, sizeof label, "%s, %s, %d sample(s), RGBA8, cached", scenes_name(scenes[i]),
                         plan_name[k], samples);
                print_work(label, &w);
                bg_render_stats st;
                bg_renderer_get_stats(r, &st);
                uint64_t n = (uint64_t)samples, multi = samples > 1;
                /* The tree plan's run-out marks cost nothing of their own, at one sample or n: the
                 * sum's alpha counts them and the one read-back carries them (samples.c). */
                assert_int_equal(w.upload_bytes, 0);
                assert_int_equal(w.programs_compiled, 0);
                assert_int_equal(w.program_binds, 2 * w.draws); /* each run binds, and unbinds at its end */
                assert_int_equal(w.syncs, 1);
                assert_int_equal(w.readback_bytes, (uint64_t)W * H * 4);
                if (plans[k] != BG_PLAN_MULTIPASS) {
                    /* One pass a sample, and with samples the add pass each and the exact resolve. */
                    assert_int_equal(w.draws, multi ? 2 * n + 1 : 1);
                    assert_int_equal(w.framebuffer_binds, multi ? 6 * n + 2 : 2);
                } else {
                    /* Its passes are the scene's (stats.passes, and MACS may split them into chunks). */
                    assert_true(w.draws >= (uint64_t)st.chunks * n + (multi ? n + 1 : 0));
                }
            }
            bg_renderer_destroy(r);
        }
        bg_scene_destroy(s);
    }
    free(px);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(stats_are_the_context_difference),
        cmocka_unit_test(one_sample_rgba8),
        cmocka_unit_test(float_image),
        cmocka_unit_test(camera_move),
        cmocka_unit_test(thresholds_count_bytes),
        cmocka_unit_test(n_samples_rgba8),
        cmocka_unit_test(to_texture),
        cmocka_unit_test(plan_budgets),
    };
    return cmocka_run_group_tests_name("bg_gpu_budget", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
