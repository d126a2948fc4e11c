/* The images of model files, judged by the rendered colours: PNG and JPEG textures next to a model
 * and embedded in a .glb or a data URI, one texture for an image that two materials share, a
 * warning for a format that is not read and an error for a corrupt one, and what the glTF maps in
 * those images mean: roughness from the metallicRoughness texture, ambient occlusion, alphaMode
 * BLEND (the surface behind shows through) and OPAQUE (alpha ignored). The models are those of
 * tests/data/make_image_models.py: quads facing the camera whose images differ between their left
 * and right halves, so each test reads one pixel in each half. */
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
#include "betelgeuse/scene/scene_internal.h"
#include "util_warnings.h"

enum { W = 64, H = 48 };
/* Pixels inside the front quad [-1, 1]^2 seen from (0, 0, 3): texture u 0.2 and 0.8, mid-height. */
enum { LEFT_X = 20, RIGHT_X = 44, MID_Y = 24 };

/* Ambient light 8 and no lamp: a model material's ambient colour is an eighth of its base colour,
 * so each pixel shows the base colour (times the occlusion) exactly. */
#define AMBIENT_ONLY "\"settings\": {\"ambient\": [8, 8, 8]}"
/* No ambient light and one lamp at the camera. */
#define LAMP_ONLY "\"settings\": {\"ambient\": [0, 0, 0]}, \"lights\": [{\"position\": [0, 0, 3]}]"


typedef struct shot {
    unsigned char px[W * H * 4];
    bg_scenefile_result r;
    util_warnings w;
} shot;

/* model (in tests/data) placed in a scene with the camera at (0, 0, 3) and the lighting given,
 * loaded and rendered on the CPU at W x H. */
static shot *render(const char *model, const char *lighting)
{
    shot *s = calloc(1, sizeof *s);
    assert_non_null(s);
    char text[1024];
    snprintf(text, sizeof text,
             "{\"objects\": [{\"mesh\": {\"file\": \"%s\"}}], \"camera\": {\"position\": [0, 0, 3]}, %s}", model,
             lighting);
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    char message[1024];
    bg_scenefile_desc d = {.base_dir = "tests/data", .logger = {util_warnings_collect, &s->w}};
    if (bg_scenefile_load_string(text, &d, scene, &s->r, message, sizeof message) != BG_OK)
        fail_msg("%s: %s", model, message);
    bg_image im = {W, H, BG_PIXEL_RGBA8, 0, s->px};
    assert_int_equal(bg_render_cpu(scene, &s->r.settings, &im), BG_OK);
    bg_scene_destroy(scene);
    return s;
}

static const unsigned char *at(const shot *s, int x, int y)
{
    return &s->px[4 * ((size_t)y * W + x)];
}

/* The pixel is the colour within tol in each channel. */
static void expect_color(const shot *s, const char *what, int x, int y, int r, int g, int b, int tol)
{
    const unsigned char *p = at(s, x, y);
    if (abs(p[0] - r) > tol || abs(p[1] - g) > tol || abs(p[2] - b) > tol)
        fail_msg("%s: pixel (%d, %d) is (%d, %d, %d), expected (%d, %d, %d) within %d", what, x, y, p[0], p[1], p[2],
                 r, g, b, tol);
}

static void embedded_png_and_jpeg_images_are_read(void **state)
{
    (void)state;
    shot *s = render("img_png.glb", AMBIENT_ONLY);
    expect_color(s, "img_png.glb, left", LEFT_X, MID_Y, 255, 0, 0, 2);
    expect_color(s, "img_png.glb, right", RIGHT_X, MID_Y, 0, 0, 255, 2);
    assert_int_equal(s->r.summary.textures, 1);
    assert_int_equal(s->w.count, 0);
    free(s);
    /* JPEG is lossy: 8x8 blocks of one colour come back within a few steps. */
    s = render("img_jpeg.glb", AMBIENT_ONLY);
    expect_color(s, "img_jpeg.glb, left", LEFT_X, MID_Y, 0, 160, 0, 8);
    expect_color(s, "img_jpeg.glb, right", RIGHT_X, MID_Y, 255, 255, 0, 8);
    assert_int_equal(s->r.summary.textures, 1);
    assert_int_equal(s->w.count, 0);
    free(s);
}

static void a_jpeg_file_beside_an_obj_is_read(void **state)
{
    (void)state;
    shot *s = render("img_jpeg.obj", AMBIENT_ONLY);
    expect_color(s, "img_jpeg.obj, left", LEFT_X, MID_Y, 255, 0, 0, 8);
    expect_color(s, "img_jpeg.obj, right", RIGHT_X, MID_Y, 0, 0, 255, 8);
    assert_int_equal(s->r.summary.textures, 1);
    assert_int_equal(s->w.count, 0);
    free(s);
}

/* Two materials and an emissive slot on one image (a data URI): one texture, both quads textured. */
static void an_image_shared_by_two_materials_is_one_texture(void **state)
{
    (void)state;
    shot *s = render("img_shared.gltf", AMBIENT_ONLY);
    if (s->r.summary.textures != 1 || s->r.summary.materials != 2)
        fail_msg("img_shared.gltf: %zu textures, %zu materials; expected 1 and 2", s->r.summary.textures,
                 s->r.summary.materials);
    expect_color(s, "img_shared.gltf front, left", LEFT_X, MID_Y, 255, 0, 0, 2);
    expect_color(s, "img_shared.gltf front, right", RIGHT_X, MID_Y, 0, 0, 255, 2);
    /* The back quad [-2, 2]^2 beside the front one, at u about 0.1 and 0.9: red and blue again. */
    const unsigned char *l = at(s, 5, MID_Y), *r = at(s, W - 6, MID_Y);
    if (l[0] < 200 || l[2] > 60 || r[2] < 200 || r[0] > 60)
        fail_msg("img_shared.gltf back quad: (%d, %d, %d) and (%d, %d, %d)", l[0], l[1], l[2], r[0], r[1], r[2]);
    free(s);
}

/* A WebP is not read: a warning names the material, the slot, the image, the file and the format,
 * and the quad keeps its green base colour factor. */
static void an_unsupported_image_is_left_out_with_a_warning(void **state)
{
    (void)state;
    shot *s = render("img_webp.gltf", AMBIENT_ONLY);
    if (s->w.count != 1 || !strstr(s->w.all, "img_webp.gltf\": material \"webp_material\": its base colour texture "
                                             "\"*0\" (embedded image 0) is left out (WebP images are not read"))
        fail_msg("%d warnings:\n%s", s->w.count, s->w.all);
    assert_int_equal(s->r.summary.textures, 0);
    expect_color(s, "img_webp.gltf", LEFT_X, MID_Y, 0, 255, 0, 2);
    expect_color(s, "img_webp.gltf", RIGHT_X, MID_Y, 0, 255, 0, 2);
    free(s);
}

/* Corrupt image data is an error naming the model, the material, the image and the reason. */
static void a_corrupt_image_is_an_error(void **state)
{
    (void)state;
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    bg_scenefile_result r;
    char message[1024];
    bg_status st = bg_scenefile_load_model("tests/data/img_corrupt.glb", NULL, scene, &r, message, sizeof message);
    bg_scene_destroy(scene);
    assert_int_equal(st, BG_ERR_IO);
    if (!strstr(message, "model file \"tests/data/img_corrupt.glb\": material \"corrupt\": base colour texture "
                         "\"*0\" (embedded image 0): ") ||
        !strstr(message, "JPEG"))
        fail_msg("%s", message);
}

/* A metal (B = 255) whose roughness is G: 0 on the left, a mirror of the black background; 255 on
 * the right, a rough surface lit by the lamp. */
static void roughness_follows_the_metallic_roughness_texture(void **state)
{
    (void)state;
    shot *s = render("img_metal_rough.gltf", LAMP_ONLY);
    const unsigned char *l = at(s, LEFT_X, MID_Y), *r = at(s, RIGHT_X, MID_Y);
    if (l[0] > 20 || r[0] < 100 || abs(r[0] - r[2]) > 2)
        fail_msg("img_metal_rough.gltf: mirror half %d, rough half (%d, %d, %d)", l[0], r[0], r[1], r[2]);
    assert_int_equal(s->w.count, 0);
    free(s);
}

/* Under ambient light alone, a white surface whose occlusion R is 255 on the left and 64 on the
 * right: white, and 64 / 255 of it (sRGB 137) on the right. */
static void occlusion_darkens_the_ambient_light(void **state)
{
    (void)state;
    shot *s = render("img_occlusion.gltf", AMBIENT_ONLY);
    expect_color(s, "img_occlusion.gltf, left", LEFT_X, MID_Y, 255, 255, 255, 2);
    expect_color(s, "img_occlusion.gltf, right", RIGHT_X, MID_Y, 137, 137, 137, 3);
    assert_int_equal(s->w.count, 0);
    free(s);
}

/* Two materials bake from the same two images: the second reads them decoded again after the first
 * released them (red | blue base, occlusion 255 | 64), on the front quad and on the back one. */
static void a_second_bake_decodes_its_images_again(void **state)
{
    (void)state;
    shot *s = render("img_occlusion_shared.gltf", AMBIENT_ONLY);
    expect_color(s, "img_occlusion_shared.gltf, front left", LEFT_X, MID_Y, 255, 0, 0, 2);
    expect_color(s, "img_occlusion_shared.gltf, front right", RIGHT_X, MID_Y, 0, 0, 137, 3);
    expect_color(s, "img_occlusion_shared.gltf, back left", 6, MID_Y, 255, 0, 0, 2);
    expect_color(s, "img_occlusion_shared.gltf, back right", 58, MID_Y, 0, 0, 137, 3);
    assert_int_equal(s->r.summary.materials, 2);
    assert_int_equal(s->r.summary.textures, 3); /* the base colour, and a bake per material */
    assert_int_equal(s->w.count, 0);
    free(s);
}

/* BLEND: the blue quad's texture alpha is 0 on the left, where the red quad behind shows, and 1 on
 * the right. */
static void blend_shows_what_is_behind(void **state)
{
    (void)state;
    shot *s = render("img_blend.gltf", AMBIENT_ONLY);
    expect_color(s, "img_blend.gltf, left", LEFT_X, MID_Y, 255, 0, 0, 3);
    expect_color(s, "img_blend.gltf, right", RIGHT_X, MID_Y, 0, 0, 255, 3);
    free(s);
}

/* OPAQUE: a base colour alpha of 0.2 is ignored (it made the quad 80% transparent), the quad is blue. */
static void opaque_ignores_alpha(void **state)
{
    (void)state;
    shot *s = render("img_opaque.gltf", AMBIENT_ONLY);
    expect_color(s, "img_opaque.gltf, left", LEFT_X, MID_Y, 0, 0, 255, 2);
    expect_color(s, "img_opaque.gltf, right", RIGHT_X, MID_Y, 0, 0, 255, 2);
    free(s);
}

/* Every texture of a model file keeps its image's 8 bits a channel, 4 bytes a texel (docs/shading.md
 * 5.2), the loader's bakes (occlusion, blend alpha) included. */
static void model_textures_stay_8_bit(void **state)
{
    (void)state;
    static const char *const models[] = {"img_png.glb", "img_jpeg.obj", "img_occlusion.gltf", "img_blend.gltf",
                                         "img_metal_rough.gltf", "img_occlusion_shared.gltf"};
    for (size_t i = 0; i < sizeof models / sizeof models[0]; i++) {
        char text[256], message[1024];
        snprintf(text, sizeof text, "{\"objects\": [{\"mesh\": {\"file\": \"%s\"}}]}", models[i]);
        bg_scene *scene = NULL;
        assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
        bg_scenefile_result r;
        util_warnings w = {0};
        bg_scenefile_desc d = {.base_dir = "tests/data", .logger = {util_warnings_collect, &w}};
        if (bg_scenefile_load_string(text, &d, scene, &r, message, sizeof message) != BG_OK)
            fail_msg("%s: %s", models[i], message);
        assert_int_equal(bg_scene_commit(scene), BG_OK);
        const bg_scene_state *st = bgi_scene_committed(scene);
        assert_true(st->texture_count > 0);
        for (uint32_t k = 0; k < st->texture_count; k++)
            if (!st->textures[k].bytes || st->textures[k].texels || bgi_texture_bytes(&st->textures[k]) !=
                                                                        (size_t)st->textures[k].width * st->textures[k].height * 4)
                fail_msg("%s: texture %u of %u is not 4 bytes a texel", models[i], k + 1, st->texture_count);
        bg_scene_destroy(scene);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(embedded_png_and_jpeg_images_are_read),
        cmocka_unit_test(a_jpeg_file_beside_an_obj_is_read),
        cmocka_unit_test(an_image_shared_by_two_materials_is_one_texture),
        cmocka_unit_test(an_unsupported_image_is_left_out_with_a_warning),
        cmocka_unit_test(a_corrupt_image_is_an_error),
        cmocka_unit_test(roughness_follows_the_metallic_roughness_texture),
        cmocka_unit_test(occlusion_darkens_the_ambient_light),
        cmocka_unit_test(a_second_bake_decodes_its_images_again),
        cmocka_unit_test(blend_shows_what_is_behind),
        cmocka_unit_test(opaque_ignores_alpha),
        cmocka_unit_test(model_textures_stay_8_bit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
