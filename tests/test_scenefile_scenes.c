/* The shipped scene files (examples/scenes/json/) against the C builders they transcribe: each
 * renders bit for bit the image of its builder on the CPU reference, and its summary counts what
 * the builder adds. Run from the source tree's root, as every suite is. */
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
#include "betelgeuse_scenefile.h"
#include "scenes/bunny_scene.h"
#include "scenes/scenes.h"

enum { W = 96, H = 72 };

/* Renders a committed scene to linear floats, so that equal images are equal radiance, not only
 * equal after 8-bit rounding. */
static float *render(bg_scene *scene, const bg_render_settings *settings)
{
    float *px = malloc((size_t)W * H * 4 * sizeof *px);
    assert_non_null(px);
    bg_image im = {W, H, BG_PIXEL_RGBA32F, 0, px};
    bg_status st = bg_render_cpu(scene, settings, &im);
    if (st != BG_OK)
        fail_msg("render: %s", bg_scene_error_message(scene));
    return px;
}

static size_t differing_pixels(const float *a, const float *b)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        n += memcmp(a + 4 * i, b + 4 * i, 4 * sizeof *a) != 0;
    return n;
}

/* Pixels off the background: the scene shows something, so equality is not two black images. */
static size_t lit_pixels(const float *a)
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        n += a[4 * i] > 0 || a[4 * i + 1] > 0 || a[4 * i + 2] > 0;
    return n;
}

static void compare(const char *name, bg_scene *built)
{
    char path[256], message[1024];
    snprintf(path, sizeof path, "examples/scenes/json/%s.json", name);
    bg_scene *loaded = NULL;
    assert_int_equal(bg_scene_create(NULL, &loaded), BG_OK);
    bg_scenefile_result r;
    bg_status st = bg_scenefile_load(path, NULL, loaded, &r, message, sizeof message);
    if (st != BG_OK)
        fail_msg("%s: %s", path, message);
    assert_true(r.camera_from_file);
    assert_true(r.lights_from_file);
    assert_true(r.summary.objects >= 1);
    assert_true(r.summary.lights >= 1);
    assert_true(r.summary.bounded);

    /* The builders leave the settings at their defaults; the files write them out. */
    bg_render_settings defaults = bg_render_settings_init();
    assert_int_equal(r.settings.max_depth, defaults.max_depth);
    assert_int_equal(r.image.samples, 1);
    float *a = render(built, &defaults);
    float *b = render(loaded, &r.settings);
    size_t lit = lit_pixels(a), diff = differing_pixels(a, b);
    if (diff != 0 || lit < (size_t)W * H / 10)
        fail_msg("%s: %zu of %d pixels differ from the builder's image (%zu lit)", name, diff, W * H, lit);
    print_message("%s: %d pixels bit-identical (%zu lit), %zu objects, %zu lights\n", name, W * H, lit,
                  r.summary.objects, r.summary.lights);
    free(a);
    free(b);
    bg_scene_destroy(loaded);
}

static void every_builder_scene_matches_its_file(void **state)
{
    (void)state;
    for (int i = 0; i < SCENE_COUNT; i++) {
        bg_scene *built = NULL;
        assert_int_equal(bg_scene_create(NULL, &built), BG_OK);
        assert_int_equal(scenes_build((scene_id)i, built), BG_OK);
        compare(scenes_name((scene_id)i), built);
        bg_scene_destroy(built);
    }
}

static void bunny_file_matches_the_bunny_builder(void **state)
{
    (void)state;
    bg_scene *built = NULL;
    assert_int_equal(bg_scene_create(NULL, &built), BG_OK);
    assert_int_equal(bunny_scene_build(built, "test_scenefile_scenes"), BG_OK);
    compare("bunny", built);
    bg_scene_destroy(built);

    /* The summary counts the mesh as tests/data/README.md describes it. */
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    char message[512];
    assert_int_equal(bg_scenefile_load("examples/scenes/json/bunny.json", NULL, s, &r, message, sizeof message), BG_OK);
    assert_int_equal(r.summary.meshes, 1);
    assert_int_equal(r.summary.objects, 2);
    assert_int_equal(r.summary.triangles, 3674);
    assert_true(r.summary.unbounded);
    assert_true(fabs(r.summary.bounds_max.y - 9.65474796) < 1e-6);
    assert_true(fabs(r.summary.bounds_min.x - -4.95847511) < 1e-6);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_builder_scene_matches_its_file),
        cmocka_unit_test(bunny_file_matches_the_bunny_builder),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
