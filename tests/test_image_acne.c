/* The acne metric of image_metrics.h on synthetic images: it must count planted acne (darkened
 * interior pixels, a self-shadowed patch, lone bright speckles) and must not count what is not acne
 * (a silhouette shifted by a pixel, rounding noise, a uniformly brighter image). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "scenes/image_metrics.h"

enum { W = 64, H = 48, SIL = 24 };

/* A smooth, lit-looking background (a slow gradient whose steps stay far below the silhouette
 * threshold) with a saturated red disc of radius 14 centred at (cx, 24). */
static void paint(unsigned char *px, int cx)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            unsigned char *p = px + (y * W + x) * 4;
            int dx = x - cx, dy = y - 24;
            if (dx * dx + dy * dy <= 14 * 14) {
                p[0] = 200; p[1] = 30; p[2] = 20;
            } else {
                p[0] = (unsigned char)(90 + x);
                p[1] = (unsigned char)(110 + y);
                p[2] = (unsigned char)(140 + (x + y) / 2);
            }
            p[3] = 255;
        }
}

static image_acne acne_of(const unsigned char *ref, const unsigned char *test)
{
    bg_image a = {W, H, BG_PIXEL_RGBA8, 0, (void *)ref}, b = {W, H, BG_PIXEL_RGBA8, 0, (void *)test};
    image_acne out;
    assert_true(image_metrics_acne(&a, &b, SIL, &out));
    return out;
}

static void identical_images_have_no_acne(void **state)
{
    (void)state;
    unsigned char ref[W * H * 4];
    paint(ref, 32);
    image_acne a = acne_of(ref, ref);
    assert_int_equal(a.pixels, 0);
    assert_int_equal(a.first_x, -1);
    assert_true(a.interior > W * H / 2 && a.interior < W * H);
}

/* A disc moved by one pixel differs by far more than 8/255 along its edge, but only on silhouette
 * pixels of the reference: no acne. */
static void shifted_silhouette_is_not_acne(void **state)
{
    (void)state;
    unsigned char ref[W * H * 4], test[W * H * 4];
    paint(ref, 32);
    paint(test, 33);
    bg_image a = {W, H, BG_PIXEL_RGBA8, 0, ref}, b = {W, H, BG_PIXEL_RGBA8, 0, test};
    image_metrics m;
    assert_true(image_metrics_compare(&a, &b, SIL, &m));
    assert_true(m.all.over_count > 20); /* the shift is a real difference... */
    assert_int_equal(acne_of(ref, test).pixels, 0); /* ...but not acne */
}

/* Rounding noise of up to 2/255 either way, and a uniformly brighter image: error, not acne. */
static void noise_and_brightening_are_not_acne(void **state)
{
    (void)state;
    unsigned char ref[W * H * 4], test[W * H * 4];
    paint(ref, 32);
    srand(7);
    for (int i = 0; i < W * H * 4; i++)
        test[i] = (unsigned char)(ref[i] + (i % 4 == 3 ? 0 : rand() % 3 - 1 + (ref[i] > 250 ? -2 : 0)));
    assert_int_equal(acne_of(ref, test).pixels, 0);
    for (int i = 0; i < W * H * 4; i++)
        test[i] = (unsigned char)(i % 4 == 3 || ref[i] > 230 ? ref[i] : ref[i] + 20);
    assert_int_equal(acne_of(ref, test).pixels, 0);
}

/* Random interior pixels darkened as a blocked light would: every one counted, as shadowed, and
 * (being alone) as a speckle too. */
static void planted_dark_pixels_are_counted(void **state)
{
    (void)state;
    unsigned char ref[W * H * 4], test[W * H * 4];
    paint(ref, 32);
    memcpy(test, ref, sizeof test);
    int planted = 0;
    /* Every pixel of a coarse grid (keeping them apart) inside the disc or the background, away from
     * the disc's edge. */
    for (int y = 2; y < H - 2; y += 5)
        for (int x = 2; x < W - 2; x += 5) {
            int dx = x - 32, dy = y - 24, r2 = dx * dx + dy * dy;
            if (r2 > 12 * 12 && r2 < 16 * 16)
                continue;
            unsigned char *p = test + (y * W + x) * 4;
            for (int c = 0; c < 3; c++)
                p[c] = (unsigned char)(p[c] * 3 / 10);
            planted++;
        }
    image_acne a = acne_of(ref, test);
    assert_true(planted > 50);
    assert_int_equal(a.pixels, planted);
    assert_int_equal(a.shadowed, planted);
    assert_int_equal(a.speckles, planted);
    assert_int_equal(a.first_x, 2);
    assert_int_equal(a.first_y, 2);
}

/* A self-shadowed patch (a 10x10 block of the disc losing its light) is shadowed, not speckle; a
 * lone bright pixel (a light leak) is a speckle, not shadowed. */
static void planted_patch_and_leak_are_counted(void **state)
{
    (void)state;
    unsigned char ref[W * H * 4], test[W * H * 4];
    paint(ref, 32);
    memcpy(test, ref, sizeof test);
    for (int y = 20; y < 30; y++)
        for (int x = 27; x < 37; x++) {
            unsigned char *p = test + (y * W + x) * 4;
            p[0] = 60; p[1] = 9; p[2] = 6;
        }
    unsigned char *leak = test + (5 * W + 5) * 4;
    leak[0] = 255; leak[1] = 255; leak[2] = 255;
    image_acne a = acne_of(ref, test);
    assert_int_equal(a.shadowed, 100);
    assert_int_equal(a.speckles, 1);
    assert_int_equal(a.pixels, 101);
}

static void bad_arguments_are_rejected(void **state)
{
    (void)state;
    unsigned char ref[W * H * 4];
    paint(ref, 32);
    bg_image a = {W, H, BG_PIXEL_RGBA8, 0, ref}, small = {W - 1, H, BG_PIXEL_RGBA8, 0, ref};
    bg_image f = {W, H, BG_PIXEL_RGBA32F, 0, ref};
    image_acne out;
    assert_false(image_metrics_acne(&a, &small, SIL, &out));
    assert_int_equal(out.pixels, 0);
    assert_false(image_metrics_acne(&a, &f, SIL, &out));
    assert_false(image_metrics_acne(NULL, &a, SIL, &out));
    assert_false(image_metrics_acne(&a, &a, SIL, NULL));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(identical_images_have_no_acne),
        cmocka_unit_test(shifted_silhouette_is_not_acne),
        cmocka_unit_test(noise_and_brightening_are_not_acne),
        cmocka_unit_test(planted_dark_pixels_are_counted),
        cmocka_unit_test(planted_patch_and_leak_are_counted),
        cmocka_unit_test(bad_arguments_are_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
