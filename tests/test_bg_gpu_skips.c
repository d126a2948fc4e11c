/* Every skip (docs/gpu_pipeline.md) changes no pixel (RGBA32F output with the skip switched off
 * through bg_render_settings.gpu_disable_skips: bit for bit on Mesa, within the error model's bound
 * for other programs on any driver) and really saves work, shown by the
 * statistics on a scene where the skip applies. */
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

enum { W = 96, H = 72 };

/* One render of a scene with some skips switched off. */
typedef struct run {
    float *px;
    bg_render_stats stats;
} run;

static run render(bg_scene *s, unsigned disable, bool timing, int max_depth)
{
    run r;
    r.px = malloc((size_t)W * H * 4 * sizeof(float));
    assert_non_null(r.px);
    bg_render_settings set = util_multipass_settings();
    set.gpu_disable_skips = disable;
    set.gpu_timing = timing;
    if (max_depth >= 0)
        set.max_depth = max_depth;
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, r.px};
    char label[32];
    snprintf(label, sizeof label, "skips 0x%x off", disable);
    util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &img, label);
    bg_renderer_get_stats(util_fx.renderer, &r.stats);
    assert_int_equal(r.stats.timed, timing);
    return r;
}

/* Fails with the first differing value unless both renders hold the same bits. */
static void assert_same_image(const run *on, const run *off, const char *what)
{
    if (memcmp(on->px, off->px, (size_t)W * H * 4 * sizeof(float)) == 0)
        return;
    for (int i = 0; i < W * H * 4; i++)
        if (memcmp(&on->px[i], &off->px[i], sizeof(float)) != 0)
            fail_msg("%s: pixel (%d, %d) channel %d is %.9g with the skip off, %.9g with it on", what, i / 4 % W,
                     i / 4 / W, i % 4, (double)off->px[i], (double)on->px[i]);
}

/* Renders a scene with every skip on and with the given ones off; both runs are returned. */
static void compare(scene_id id, unsigned disable, bool timing, int max_depth, run *on, run *off)
{
    bg_scene *s = util_scene(id);
    *on = render(s, 0, timing, max_depth);
    *off = render(s, disable, timing, max_depth);
    char what[128];
    snprintf(what, sizeof what, "%s, skips 0x%x off", scenes_name(id), disable);
    /* A skip switched off changes the programs too (the stencil, facing and specialisation skips
     * are tests in the shaders' text, the batch skip makes one program per object), so the two
     * images come from other programs over the same formulas (util_expect_gpu_twins): the same bits
     * on Mesa, within the error model's bound on any driver. */
    util_expect_gpu_twins(on->px, off->px, W, H, gpu_threshold_of(id), what);
    bg_scene_destroy(s);
}

static void release(run *a, run *b)
{
    free(a->px);
    free(b->px);
}

/* Every skip off at once, on every shared scene. */
static void all_skips_change_no_pixel(void **state)
{
    (void)state;
    for (int id = 0; id < SCENE_COUNT; id++) {
        run on, off;
        compare((scene_id)id, BG_SKIP_ALL, false, -1, &on, &off);
        int passes_on = 0, passes_off = 0;
        for (int k = 0; k < BG_PASS_KIND_COUNT_; k++) {
            passes_on += on.stats.passes[k];
            passes_off += off.stats.passes[k];
        }
        print_message("%-19s passes %d with every skip, %d without; intersect pixels %llu / %llu\n",
                      scenes_name((scene_id)id), passes_on, passes_off,
                      (unsigned long long)on.stats.intersect_pixels, (unsigned long long)off.stats.intersect_pixels);
        assert_true(passes_off >= passes_on);
        assert_true(off.stats.intersect_pixels > on.stats.intersect_pixels); /* the scissor alone ensures it */
        release(&on, &off);
    }
}

/* Specialisation changes shaders, not passes or coverage: no statistic can show it, so the image
 * identity is the whole assertion, on the scenes that use the fewest and the most material
 * features (untextured mirror, textured glass floor, textures + coats + anisotropy). */
static void specialize(void **state)
{
    (void)state;
    const scene_id ids[3] = {SCENE_MIRROR, SCENE_GLASS, SCENE_TEXTURED_ANISO};
    for (int k = 0; k < 3; k++) {
        run on, off;
        compare(ids[k], BG_SKIP_SPECIALIZE, false, -1, &on, &off);
        release(&on, &off);
    }
}

/* paper_earth has neither mirrors nor glass: no spawn pass unless the cull is off. */
static void bounce_cull(void **state)
{
    (void)state;
    run on, off;
    compare(SCENE_PAPER_EARTH, BG_SKIP_BOUNCE_CULL, false, -1, &on, &off);
    assert_int_equal(on.stats.passes[BG_PASS_SPAWN], 0);
    assert_int_equal(on.stats.levels, 0);
    assert_true(off.stats.passes[BG_PASS_SPAWN] > 0);
    release(&on, &off);
}

/* mirror has one mirror sphere among diffuse objects: what it reflects is diffuse, so the ray set
 * spawned at level 2 holds no live ray. With 16 levels allowed, the occlusion query stops there;
 * without it every allowed level is traced. */
static void occlusion(void **state)
{
    (void)state;
    run on, off;
    compare(SCENE_MIRROR, BG_SKIP_OCCLUSION, false, 16, &on, &off);
    print_message("mirror, 16 levels: %d ray sets (%d skipped), %d levels; occlusion off: %d ray sets, %d levels\n",
                  on.stats.ray_sets, on.stats.ray_sets_skipped, on.stats.levels, off.stats.ray_sets,
                  off.stats.levels);
    assert_true(on.stats.ray_sets_skipped > 0);
    assert_true(on.stats.levels < 16);
    assert_true(off.stats.ray_sets > on.stats.ray_sets);
    assert_true(off.stats.levels > on.stats.levels);
    release(&on, &off);
}

/* With the stencil skip off, passes also run on dead rays (weight 0, in reflected and transmitted
 * sets), and the light pass then shades them and adds 0 instead of discarding them: with gpu_timing,
 * shaded_fragments (fragments kept by shadow and light passes) grows on scenes with dead rays (mirror,
 * glass). paper_earth has only camera rays, all alive, so nothing changes there; missed pixels never
 * reach shadow or light passes either way (the stencil's hit bit is not a skip). */
static void stencil(void **state)
{
    (void)state;
    const scene_id ids[3] = {SCENE_PAPER_EARTH, SCENE_MIRROR, SCENE_GLASS};
    for (int k = 0; k < 3; k++) {
        run on, off;
        compare(ids[k], BG_SKIP_STENCIL, true, -1, &on, &off);
        print_message("%s: shaded fragments %llu with the stencil, %llu without\n", scenes_name(ids[k]),
                      (unsigned long long)on.stats.shaded_fragments, (unsigned long long)off.stats.shaded_fragments);
        assert_true(on.stats.shaded_fragments > 0);
        if (ids[k] == SCENE_PAPER_EARTH)
            assert_true(off.stats.shaded_fragments == on.stats.shaded_fragments);
        else
            assert_true(off.stats.shaded_fragments > on.stats.shaded_fragments);
        release(&on, &off);
    }
}

/* The earth covers much less than the frame: camera-ray intersection covers its rectangle only. */
static void scissor(void **state)
{
    (void)state;
    run on, off;
    compare(SCENE_PAPER_EARTH, BG_SKIP_SCISSOR, false, -1, &on, &off);
    assert_true(on.stats.intersect_pixels > 0);
    assert_true(on.stats.intersect_pixels < (uint64_t)W * H);
    assert_true(off.stats.intersect_pixels >= (uint64_t)W * H);
    release(&on, &off);
}

/* A single convex object can only shadow itself: paper_earth needs no shadow pass at all, while
 * paper_earth_shadow (the sphere shadows the plane) does. */
static void shadow_cull(void **state)
{
    (void)state;
    run on, off;
    compare(SCENE_PAPER_EARTH, BG_SKIP_SHADOW_CULL, false, -1, &on, &off);
    assert_int_equal(on.stats.passes[BG_PASS_SHADOW], 0);
    assert_true(off.stats.passes[BG_PASS_SHADOW] > 0);
    release(&on, &off);
    /* Both lights and the sphere are in front of the wall: the wall can shadow nothing, so only the
     * sphere's pass (one group of two lights) is drawn; without the cull the wall's is drawn too. */
    compare(SCENE_PAPER_EARTH_SHADOW, BG_SKIP_SHADOW_CULL, false, -1, &on, &off);
    assert_int_equal(on.stats.passes[BG_PASS_SHADOW], 1);
    assert_int_equal(off.stats.passes[BG_PASS_SHADOW], 2);
    release(&on, &off);
}

/* A shadow pass tests a light's segment only where the surface faces the light. shaded_fragments
 * counts the fragments a shadow pass keeps (those it finds blocked), so the saving shows where a
 * surface faces away from a light and another object also stands in that light's way: in
 * many_lights the sphere, box and cylinder shade each other's far sides (measured at 96x72: 8304
 * kept fragments with the skip, 8341 without; a fragment a batch of objects blocks counts once). paper_earth has no shadow pass at all, and there the
 * image identity is what is checked. */
static void facing(void **state)
{
    (void)state;
    run on, off;
    compare(SCENE_MANY_LIGHTS, BG_SKIP_FACING, true, -1, &on, &off);
    print_message("many_lights: %llu fragments kept with the facing skip, %llu without\n",
                  (unsigned long long)on.stats.shaded_fragments, (unsigned long long)off.stats.shaded_fragments);
    assert_true(on.stats.shaded_fragments > 0);
    assert_true(off.stats.shaded_fragments > on.stats.shaded_fragments);
    release(&on, &off);
    compare(SCENE_PAPER_EARTH, BG_SKIP_FACING, true, -1, &on, &off);
    release(&on, &off);
}

/* Batching tests several objects in one intersection or shadow pass: the nearest root is chosen in
 * the shader by the depth buffer's own comparison, ties to the object drawn first, so the image keeps
 * every bit while the pass counts drop. The scenes mix every shape and UV mapping (all_primitives),
 * textures, coats and anisotropy (textured_aniso), glass and mirrors over many secondary sets
 * (glass, many_spheres), and four light groups (many_lights). */
static void batch(void **state)
{
    (void)state;
    const scene_id ids[5] = {SCENE_MANY_SPHERES, SCENE_ALL_PRIMITIVES, SCENE_TEXTURED_ANISO, SCENE_GLASS,
                             SCENE_MANY_LIGHTS};
    for (int k = 0; k < 5; k++) {
        run on, off;
        compare(ids[k], BG_SKIP_BATCH, false, -1, &on, &off);
        print_message("%s: intersection passes %d (%d objects) batched, %d without; shadow passes %d (%d objects), "
                      "%d without\n",
                      scenes_name(ids[k]), on.stats.passes[BG_PASS_INTERSECT], on.stats.intersect_objects,
                      off.stats.passes[BG_PASS_INTERSECT], on.stats.passes[BG_PASS_SHADOW], on.stats.shadow_objects,
                      off.stats.passes[BG_PASS_SHADOW]);
        /* Without batching every pass tests one object; with it the same objects take fewer passes. */
        assert_int_equal(off.stats.intersect_objects, off.stats.passes[BG_PASS_INTERSECT]);
        assert_int_equal(off.stats.shadow_objects, off.stats.passes[BG_PASS_SHADOW]);
        assert_int_equal(on.stats.intersect_objects, off.stats.intersect_objects);
        assert_int_equal(on.stats.shadow_objects, off.stats.shadow_objects);
        assert_true(on.stats.passes[BG_PASS_INTERSECT] < off.stats.passes[BG_PASS_INTERSECT]);
        if (off.stats.passes[BG_PASS_SHADOW] > 1)
            assert_true(on.stats.passes[BG_PASS_SHADOW] < off.stats.passes[BG_PASS_SHADOW]);
        release(&on, &off);
    }
}

/* gpu_timing only measures: it changes no pixel and no pass (its times are never asserted). */
static void timing_changes_nothing(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_GLASS);
    run plain = render(s, 0, false, -1), timed = render(s, 0, true, -1);
    /* Equal on any conforming driver: timing adds queries around the passes and changes no program,
     * input or order (GL 2.1 appendix A, rule 4). */
    assert_same_image(&plain, &timed, "glass, gpu_timing on");
    assert_memory_equal(plain.stats.passes, timed.stats.passes, sizeof plain.stats.passes);
    assert_int_equal(plain.stats.chunks, timed.stats.chunks);
    assert_true(timed.stats.shaded_fragments > 0);
    release(&plain, &timed);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(all_skips_change_no_pixel),
        cmocka_unit_test(specialize),
        cmocka_unit_test(bounce_cull),
        cmocka_unit_test(occlusion),
        cmocka_unit_test(stencil),
        cmocka_unit_test(batch),
        cmocka_unit_test(scissor),
        cmocka_unit_test(shadow_cull),
        cmocka_unit_test(facing),
        cmocka_unit_test(timing_changes_nothing),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
