/* The limits matrix (docs/architecture.md, "Tests"): draw buffers and colour attachments capped at 1, 2, 4
 * and 8, and texture units at 8 and 16, give the uncapped context's image (RGBA32F output; the
 * same bits on Mesa, within the error model's bound for other programs elsewhere) on the glass
 * scene (bounces: the most pass kinds) and textured_aniso (textures, coats and anisotropy: the most
 * G-buffer targets); and the caps really split passes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"
#include "util_thresholds.h"

enum { W = 80, H = 60 };

/* Renders a scene on a fresh context with the given caps (NULL: none) into a new RGBA32F buffer. */
static float *render(macs_headless *h, const macs_limits *caps, scene_id id, bg_render_stats *stats)
{
    macs_context *ctx = util_context(h, caps);
    if (caps) {
        macs_limits real, eff;
        macs_context_get_limits(ctx, &real, &eff);
        if (caps->max_draw_buffers && eff.max_draw_buffers != (caps->max_draw_buffers < real.max_draw_buffers
                                                                    ? caps->max_draw_buffers
                                                                    : real.max_draw_buffers))
            fail_msg("draw buffer cap %d not applied: effective %d", caps->max_draw_buffers, eff.max_draw_buffers);
    }
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = util_scene(id);
    float *px = malloc((size_t)W * H * 4 * sizeof(float));
    assert_non_null(px);
    bg_render_settings set = util_multipass_settings();
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, px};
    bg_status st = bg_render_gpu(r, s, &set, &img);
    if (st != BG_OK)
        fail_msg("%s, caps draw buffers %d, attachments %d, texture units %d: %s: %s", scenes_name(id),
                 caps ? caps->max_draw_buffers : 0, caps ? caps->max_color_attachments : 0,
                 caps ? caps->max_texture_units : 0, bg_status_string(st), bg_renderer_error_message(r));
    bg_renderer_get_stats(r, stats);
    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
    return px;
}

/* A capped render against the uncapped one. A cap on draw buffers splits passes into chunks, each a
 * program of its own that runs main again for its outputs, and a cap on texture units makes smaller
 * batches: other programs over the same formulas, which GL does not promise to round alike
 * (util_expect_gpu_twins). Mesa's do, to the bit. */
static void assert_same_image(const float *a, const float *b, scene_id id, const char *what)
{
    util_expect_gpu_twins(a, b, W, H, gpu_threshold_of(id), what);
}

static void check_caps(macs_headless *h, scene_id id)
{
    const char *name = scenes_name(id);
    char what[128];
    bg_render_stats base_stats;
    float *base = render(h, NULL, id, &base_stats);
    /* The uncapped context's own outputs per chunk: under a limit profile (MACS_TEST_PROFILE) it has
     * fewer than the driver, and a cap at or above it changes nothing. */
    macs_limits base_limits;
    macs_context *probe = util_context(h, NULL);
    macs_context_get_limits(probe, NULL, &base_limits);
    macs_context_destroy(probe);
    int base_outputs = base_limits.max_draw_buffers < base_limits.max_color_attachments
                           ? base_limits.max_draw_buffers
                           : base_limits.max_color_attachments;

    const int caps_db[4] = {1, 2, 4, 8};
    int chunks[4];
    for (int k = 0; k < 4; k++) {
        macs_limits caps = {0};
        caps.max_draw_buffers = caps.max_color_attachments = caps_db[k];
        bg_render_stats st;
        float *px = render(h, &caps, id, &st);
        snprintf(what, sizeof what, "%s with %d draw buffers and colour attachments", name, caps_db[k]);
        assert_same_image(base, px, id, what);
        chunks[k] = st.chunks;
        print_message("%s: cap %d: %d chunks (uncapped %d, G-buffer targets %d)\n", name, caps_db[k], st.chunks,
                      base_stats.chunks, base_stats.gbuffer_targets);
        /* Same passes, possibly in more chunks. */
        assert_memory_equal(st.passes, base_stats.passes, sizeof st.passes);
        if (st.chunks < base_stats.chunks)
            fail_msg("%s: %d chunks, fewer than the %d uncapped", what, st.chunks, base_stats.chunks);
        if (caps_db[k] < base_stats.gbuffer_targets && caps_db[k] < base_outputs && st.chunks <= base_stats.chunks)
            fail_msg("%s: G-buffer of %d targets, yet no more chunks (%d) than uncapped", what,
                     base_stats.gbuffer_targets, st.chunks);
        free(px);
    }
    /* One draw buffer splits every pass with several outputs; fewer buffers never mean fewer chunks. */
    assert_true(chunks[0] > base_stats.chunks || base_outputs == 1);
    for (int k = 1; k < 4; k++)
        if (chunks[k] > chunks[k - 1])
            fail_msg("%s: %d chunks at cap %d but %d at cap %d", name, chunks[k], caps_db[k], chunks[k - 1],
                     caps_db[k - 1]);

    const int units[2] = {8, 16};
    for (int k = 0; k < 2; k++) {
        macs_limits caps = {0};
        caps.max_texture_units = units[k];
        bg_render_stats st;
        float *px = render(h, &caps, id, &st);
        snprintf(what, sizeof what, "%s with %d texture units", name, units[k]);
        assert_same_image(base, px, id, what);
        free(px);
    }
    /* Everything capped at once: the smallest hardware of the matrix. */
    macs_limits all = {0};
    all.max_draw_buffers = all.max_color_attachments = 1;
    all.max_texture_units = 8;
    bg_render_stats st;
    float *px = render(h, &all, id, &st);
    snprintf(what, sizeof what, "%s with 1 draw buffer and 8 texture units", name);
    assert_same_image(base, px, id, what);
    free(px);
    free(base);
}

static void glass_is_cap_independent(void **state)
{
    check_caps(*state, SCENE_GLASS);
}

static void textured_aniso_is_cap_independent(void **state)
{
    bg_render_stats st;
    float *px = render(*state, NULL, SCENE_TEXTURED_ANISO, &st);
    free(px);
    /* the scene this test relies on for splitting writes a G-buffer of several targets */
    assert_true(st.gbuffer_targets >= 2);
    check_caps(*state, SCENE_TEXTURED_ANISO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(glass_is_cap_independent),
        cmocka_unit_test(textured_aniso_is_cap_independent),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
