/* PNG I/O (libpng simplified API), textures from images and files, and the sRGB decode. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/scene/scene_internal.h"
#include "betelgeuse/common/srgb.h"

/* A fresh path under /tmp; the file exists (empty) until the test removes it. */
static void temp_path(char path[64])
{
    strcpy(path, "/tmp/bg_png_test_XXXXXX");
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
}

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

/* Deterministic pseudo-random bytes, so the PNG does not compress to nothing. */
static void fill_noise(unsigned char *p, size_t n, uint32_t seed)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        p[i] = (unsigned char)(seed >> 24);
    }
}

static void test_roundtrip_rgba8_with_stride(void **state)
{
    (void)state;
    enum { W = 37, H = 23, STRIDE = W * 4 + 12 };
    unsigned char *src = calloc(STRIDE * H, 1), *dst = calloc(STRIDE * H, 1);
    fill_noise(src, STRIDE * H, 7);
    char path[64], msg[256];
    temp_path(path);
    bg_image in = {W, H, BG_PIXEL_RGBA8, STRIDE, src};
    assert_int_equal(bg_png_save(path, &in, msg, sizeof msg), BG_OK);
    assert_string_equal(msg, "");
    int w = 0, h = 0;
    assert_int_equal(bg_png_size(path, &w, &h, msg, sizeof msg), BG_OK);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    bg_image out = {W, H, BG_PIXEL_RGBA8, STRIDE, dst};
    assert_int_equal(bg_png_load(path, &out, msg, sizeof msg), BG_OK);
    for (int y = 0; y < H; y++)
        assert_memory_equal(src + y * STRIDE, dst + y * STRIDE, W * 4);
    /* Tightly packed load of the same file. */
    unsigned char *packed = calloc(W * H * 4, 1);
    bg_image tight = {W, H, BG_PIXEL_RGBA8, 0, packed};
    assert_int_equal(bg_png_load(path, &tight, msg, sizeof msg), BG_OK);
    assert_memory_equal(packed + (H - 1) * W * 4, src + (H - 1) * STRIDE, W * 4);
    /* A wrong-sized image is the caller's mistake, not an I/O error. */
    bg_image small = {W - 1, H, BG_PIXEL_RGBA8, 0, packed};
    assert_int_equal(bg_png_load(path, &small, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(msg, "37x23"));
    remove(path);
    free(src);
    free(dst);
    free(packed);
}

static void test_save_float_clamps_and_rounds(void **state)
{
    (void)state;
    float px[2 * 4] = {0.5f, -1.0f, 2.0f, 1.0f, NAN, 0.25f, 1.0f / 255.0f, 0.0f};
    char path[64], msg[256];
    temp_path(path);
    bg_image in = {2, 1, BG_PIXEL_RGBA32F, 0, px};
    assert_int_equal(bg_png_save(path, &in, msg, sizeof msg), BG_OK);
    unsigned char bytes[8];
    bg_image out = {2, 1, BG_PIXEL_RGBA8, 0, bytes};
    assert_int_equal(bg_png_load(path, &out, msg, sizeof msg), BG_OK);
    const unsigned char want[8] = {128, 0, 255, 255, 0, 64, 1, 0};
    assert_memory_equal(bytes, want, 8);
    float back[8];
    bg_image fout = {2, 1, BG_PIXEL_RGBA32F, 0, back};
    assert_int_equal(bg_png_load(path, &fout, msg, sizeof msg), BG_OK);
    for (int i = 0; i < 8; i++)
        assert_true(fabsf(back[i] - want[i] / 255.0f) < 1e-7f);
    remove(path);
}

static void test_missing_file(void **state)
{
    (void)state;
    const char *path = "/tmp/bg_png_test_does_not_exist/nothing.png";
    char msg[256];
    int w, h;
    assert_int_equal(bg_png_size(path, &w, &h, msg, sizeof msg), BG_ERR_IO);
    assert_non_null(strstr(msg, path));
    float px[4];
    bg_image img = {1, 1, BG_PIXEL_RGBA32F, 0, px};
    assert_int_equal(bg_png_load(path, &img, msg, sizeof msg), BG_ERR_IO);
    assert_non_null(strstr(msg, path));
    /* A too-small message buffer is truncated, never overrun. */
    char tiny[8];
    memset(tiny, 'x', sizeof tiny);
    assert_int_equal(bg_png_size(path, &w, &h, tiny, 5), BG_ERR_IO);
    assert_int_equal(strlen(tiny), 4);
    assert_int_equal(tiny[5], 'x');
    assert_int_equal(bg_png_size(path, &w, &h, NULL, 0), BG_ERR_IO);

    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t t = 0;
    assert_int_equal(bg_scene_load_texture_png(s, path, NULL, &t), BG_ERR_IO);
    assert_int_equal(bg_scene_error(s), BG_ERR_IO);
    assert_non_null(strstr(bg_scene_error_message(s), "bg_scene_load_texture_png"));
    assert_non_null(strstr(bg_scene_error_message(s), path));
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bg_scene_committed(s)->texture_count, 0);
    bg_scene_destroy(s);
}

static void test_truncated_and_corrupt_files(void **state)
{
    (void)state;
    enum { W = 64, H = 64 };
    unsigned char *px = malloc(W * H * 4);
    fill_noise(px, W * H * 4, 3);
    char path[64], msg[256];
    temp_path(path);
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_png_save(path, &img, msg, sizeof msg), BG_OK);
    long n = file_size(path);
    assert_true(n > 1000);
    assert_int_equal(truncate(path, n / 2), 0);

    assert_int_equal(bg_png_load(path, &img, msg, sizeof msg), BG_ERR_IO);
    assert_non_null(strstr(msg, path));
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t t = 0;
    assert_int_equal(bg_scene_load_texture_png(s, path, NULL, &t), BG_ERR_IO);
    assert_non_null(strstr(bg_scene_error_message(s), path));
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bg_scene_committed(s)->texture_count, 0);

    /* Not a PNG at all. */
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs("this is not a PNG file, just text long enough to read a header from", f);
    fclose(f);
    int w, h;
    assert_int_equal(bg_png_size(path, &w, &h, msg, sizeof msg), BG_ERR_IO);
    assert_non_null(strstr(msg, path));
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_load_texture_png(s, path, NULL, &t), BG_ERR_IO);
    assert_non_null(strstr(bg_scene_error_message(s), path));
    bg_scene_destroy(s);
    remove(path);
    free(px);
}

static void test_png_argument_errors(void **state)
{
    (void)state;
    char msg[256];
    unsigned char px[4] = {0};
    bg_image bad = {0, 1, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_png_save("/tmp/x.png", &bad, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(msg, "width"));
    bg_image ok = {1, 1, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_png_save(NULL, &ok, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(msg, "path"));
    assert_int_equal(bg_png_save("/tmp/bg_png_test_no_such_dir/x.png", &ok, msg, sizeof msg), BG_ERR_IO);
    assert_non_null(strstr(msg, "/tmp/bg_png_test_no_such_dir/x.png"));
    int w;
    assert_int_equal(bg_png_size("/tmp/x.png", &w, NULL, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
}

/* ---- textures ---- */

static void test_texture_from_png_file(void **state)
{
    (void)state;
    /* 1x2: top row red, bottom row half-grey; stored rows are flipped (row 0 = bottom). */
    unsigned char px[8] = {255, 0, 0, 255, 128, 128, 128, 64};
    char path[64], msg[256];
    temp_path(path);
    bg_image img = {1, 2, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_png_save(path, &img, msg, sizeof msg), BG_OK);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t t = 0;
    bg_texture_desc d = {BG_WRAP_CLAMP, BG_TEXTURE_LINEAR};
    assert_int_equal(bg_scene_load_texture_png(s, path, &d, &t), BG_OK);
    assert_int_equal(t, 1);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_texture_data *tex = &bg_scene_committed(s)->textures[0];
    assert_int_equal(tex->width, 1);
    assert_int_equal(tex->height, 2);
    assert_int_equal(tex->wrap, BG_WRAP_CLAMP);
    assert_true(tex->texels[0] == (float)(128 / 255.0) && tex->texels[3] == (float)(64 / 255.0));
    assert_true(tex->texels[4] == 1.0f && tex->texels[5] == 0.0f && tex->texels[7] == 1.0f);
    bg_scene_destroy(s);
    remove(path);
}

static void test_texture_flip_stride_and_float(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    /* 2x3 float image with a padded stride of 12 floats per row; value = 10 * row + column. */
    float fpx[3 * 12];
    for (int i = 0; i < 3 * 12; i++)
        fpx[i] = 99.0f;
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 2; x++)
            for (int c = 0; c < 4; c++)
                fpx[y * 12 + x * 4 + c] = (float)(10 * y + x) + c * 0.25f;
    bg_image img = {2, 3, BG_PIXEL_RGBA32F, 12 * sizeof(float), fpx};
    uint32_t t;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &t), BG_OK); /* sRGB ignored for floats */
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_texture_data *tex = &bg_scene_committed(s)->textures[0];
    assert_int_equal(tex->wrap, BG_WRAP_REPEAT);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 2; x++)
            for (int c = 0; c < 4; c++)
                assert_true(tex->texels[(y * 2 + x) * 4 + c] == (float)(10 * (2 - y) + x) + c * 0.25f);
    /* The caller's buffer can go away: the scene copied it. */
    memset(fpx, 0, sizeof fpx);
    assert_true(tex->texels[0] == 20.0f);
    bg_scene_destroy(s);
}

static void test_srgb_decode(void **state)
{
    (void)state;
    assert_true(bg_srgb_to_linear(0.0) == 0.0);
    assert_true(bg_srgb_to_linear(1.0) == 1.0);
    /* Both branches meet at the 0.04045 boundary (linear 0.0031308). */
    double lo = 0.04045 / 12.92, hi = pow((0.04045 + 0.055) / 1.055, 2.4);
    assert_true(fabs(bg_srgb_to_linear(0.04045) - lo) < 1e-15);
    assert_true(fabs(lo - hi) < 1e-7);
    assert_true(fabs(bg_srgb_to_linear(0.5) - 0.21404114048223255) < 1e-12);
    assert_true(fabs(bg_linear_to_srgb(bg_srgb_to_linear(0.7)) - 0.7) < 1e-12);

    /* Through a texture: bytes 0, 10 (linear branch), 11 (power branch), 255; alpha stays linear. */
    unsigned char px[16] = {0, 10, 11, 255, 255, 128, 0, 128, 0, 0, 0, 0, 0, 0, 0, 0};
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_image img = {4, 1, BG_PIXEL_RGBA8, 0, px};
    uint32_t srgb, lin;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &srgb), BG_OK);
    bg_texture_desc d = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR};
    assert_int_equal(bg_scene_add_texture(s, &img, &d, &lin), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const float *a = bg_scene_committed(s)->textures[0].texels, *b = bg_scene_committed(s)->textures[1].texels;
    assert_true(a[0] == 0.0f);
    assert_true(a[1] == (float)(10.0 / 255.0 / 12.92));
    assert_true(a[2] == (float)pow((11.0 / 255.0 + 0.055) / 1.055, 2.4));
    assert_true(a[3] == 1.0f);                      /* alpha */
    assert_true(a[4] == 1.0f);
    assert_true(fabsf(a[5] - 0.2158605f) < 1e-6f);  /* 128 */
    assert_true(a[7] == (float)(128 / 255.0));      /* alpha not decoded */
    assert_true(b[1] == (float)(10 / 255.0) && b[5] == (float)(128 / 255.0));
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_roundtrip_rgba8_with_stride),
        cmocka_unit_test(test_save_float_clamps_and_rounds),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_truncated_and_corrupt_files),
        cmocka_unit_test(test_png_argument_errors),
        cmocka_unit_test(test_texture_from_png_file),
        cmocka_unit_test(test_texture_flip_stride_and_float),
        cmocka_unit_test(test_srgb_decode),
    };
    return cmocka_run_group_tests_name("bg_png", tests, NULL, NULL);
}
