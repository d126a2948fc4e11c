/* The materials a model file gets, judged by the image as a user would judge it: a PLY or STL without
 * materials is a grey diffuse surface (assimp's invented white ambient made a white silhouette, its
 * white specular a dark mirror), a glTF emissive factor without a texture glows in its own colour, a
 * factor whose texture cannot be read does not turn the surface white, and the ambient light takes
 * the surface's own colour. Each of these images was wrong before its fix. */
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

enum { W = 64, H = 48 };

/* What the covered (non-background) pixels of an image look like. */
typedef struct coverage {
    size_t covered;
    size_t white;     /* every channel >= 250 */
    size_t grey;      /* channels within 2 of each other */
    size_t red;       /* r >= 250 and r > g + 80: a red glow over any base colour */
    size_t blue;      /* b > 2 r */
    double mean;      /* mean of the channels */
} coverage;

/* Loads path (a scene or model file; text instead when not NULL, resolved in tests/data) and renders
 * it on the CPU at W x H. */
static coverage render(const char *path, const char *text)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    char message[1024];
    bg_scenefile_desc d = {.base_dir = "tests/data"};
    bg_status st = text ? bg_scenefile_load_string(text, &d, s, &r, message, sizeof message)
                        : bg_scenefile_load_any(path, NULL, s, &r, message, sizeof message);
    if (st != BG_OK)
        fail_msg("%s: %s", path ? path : text, message);
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    bg_image im = {W, H, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_render_cpu(s, &r.settings, &im), BG_OK);
    coverage c;
    memset(&c, 0, sizeof c);
    double sum = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        int red = px[4 * i], green = px[4 * i + 1], blue = px[4 * i + 2];
        if (!red && !green && !blue)
            continue;
        c.covered++;
        c.white += red >= 250 && green >= 250 && blue >= 250;
        c.grey += abs(red - green) <= 2 && abs(green - blue) <= 2;
        c.red += red >= 250 && red > green + 80;
        c.blue += blue > 2 * red;
        sum += (red + green + blue) / 3.0;
    }
    c.mean = c.covered ? sum / c.covered : 0;
    free(px);
    bg_scene_destroy(s);
    return c;
}

static void files_without_materials_are_grey_diffuse(void **state)
{
    (void)state;
    /* The bunny was white in every pixel; now shaded grey. */
    coverage c = render("tests/data/bunny.ply", NULL);
    assert_true(c.covered > (size_t)W * H / 10);
    if (c.white * 20 > c.covered || c.grey < c.covered * 9 / 10)
        fail_msg("bunny.ply: %zu of %zu pixels white, %zu grey", c.white, c.covered, c.grey);
    /* The STL was a near mirror of the black background; now a lit grey surface. */
    c = render("tests/data/tetra.stl", NULL);
    if (c.covered < 50 || c.grey < c.covered * 9 / 10 || c.mean < 120)
        fail_msg("tetra.stl: %zu pixels, %zu grey, mean %.1f", c.covered, c.grey, c.mean);
}

static void emission_is_factor_times_texture(void **state)
{
    (void)state;
    /* A factor without a texture: a plain colour, red over the blue base. */
    coverage c = render("tests/data/emissive_red.gltf", NULL);
    if (c.covered < 50 || c.red < c.covered * 9 / 10)
        fail_msg("emissive_red.gltf: %zu of %zu pixels red", c.red, c.covered);
    /* A white factor whose texture is a WebP, which is not read: left out with the texture, so the
     * surface shows its blue base colour rather than white. */
    c = render("tests/data/emissive_webp_texture.gltf", NULL);
    if (c.covered < 50 || c.white > 0 || c.blue < c.covered * 9 / 10)
        fail_msg("emissive_webp_texture.gltf: %zu of %zu pixels white, %zu blue", c.white, c.covered, c.blue);
}

/* Under ambient light alone the surface shows its own colour, not a grey the same for every material. */
static void ambient_light_takes_the_base_colour(void **state)
{
    (void)state;
    coverage c = render(NULL, "{\"objects\": [{\"mesh\": {\"file\": \"tetra_pair.gltf\"}}], "
                              "\"camera\": {\"position\": [0.75, 0.4, 4], \"look_at\": [0.75, 0.4, 0]}}");
    if (c.covered < 50 || c.blue < c.covered * 9 / 10)
        fail_msg("tetra_pair.gltf under ambient light: %zu of %zu pixels blue", c.blue, c.covered);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(files_without_materials_are_grey_diffuse),
        cmocka_unit_test(emission_is_factor_times_texture),
        cmocka_unit_test(ambient_light_takes_the_base_colour),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
