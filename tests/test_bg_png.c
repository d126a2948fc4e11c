/* PNG I/O, textures from images and files, and the sRGB decode. PNGs of every colour type, depth
 * and interlace method are written here with libpng's write API, so no binary fixture is needed. */
#include <math.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <png.h>

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
    assert_int_equal(bgi_scene_committed(s)->texture_count, 0);
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
    assert_int_equal(bgi_scene_committed(s)->texture_count, 0);

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
    int w, h;
    assert_int_equal(bg_png_size("/tmp/x.png", &w, NULL, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(msg, "height is NULL"));
    /* Each NULL argument is named alone, not in a list of three. */
    assert_int_equal(bg_png_size(NULL, &w, &h, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
    assert_string_equal(msg, "bg_png_size: path is NULL");
    assert_int_equal(bg_png_size("/tmp/x.png", NULL, &h, msg, sizeof msg), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(msg, "width is NULL"));
}

/* ---- files of every colour type, depth and interlace, written here with libpng's write API ---- */

/* One PNG to write. samples holds the file's values row by row, as many per pixel as the colour
 * type has channels (a palette image: the index). */
typedef struct test_png {
    const char *label;
    int width, height, bit_depth, color_type, interlace;
    const uint16_t *samples;
    const png_color *palette;
    int palette_size;
    const png_byte *palette_alpha; /* tRNS of a palette image, palette_alpha_count entries */
    int palette_alpha_count;
    bool gamma_linear;             /* a gAMA chunk of 1.0, which loading must not apply */
} test_png;

static int channels_of(int color_type)
{
    switch (color_type) {
    case PNG_COLOR_TYPE_GRAY:
    case PNG_COLOR_TYPE_PALETTE:
        return 1;
    case PNG_COLOR_TYPE_GRAY_ALPHA:
        return 2;
    case PNG_COLOR_TYPE_RGB:
        return 3;
    default:
        return 4;
    }
}

/* One row as the file stores it: 16-bit samples big-endian, smaller ones packed from the high bit. */
static void pack_row(const test_png *t, int y, png_byte *row, size_t row_bytes)
{
    int n = t->width * channels_of(t->color_type);
    const uint16_t *s = t->samples + (size_t)y * (size_t)n;
    memset(row, 0, row_bytes);
    for (int i = 0; i < n; i++) {
        if (t->bit_depth == 16) {
            row[2 * i] = (png_byte)(s[i] >> 8);
            row[2 * i + 1] = (png_byte)(s[i] & 0xff);
        } else {
            int per_byte = 8 / t->bit_depth;
            int shift = 8 - t->bit_depth * (i % per_byte + 1);
            row[i / per_byte] |= (png_byte)(s[i] << shift);
        }
    }
}

static void write_test_png(const char *path, const test_png *t)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    assert_non_null(png);
    png_infop info = png_create_info_struct(png);
    assert_non_null(info);
    size_t row_bytes = ((size_t)t->width * (size_t)channels_of(t->color_type) * (size_t)t->bit_depth + 7) / 8;
    png_byte *row = malloc(row_bytes);
    assert_non_null(row);
    if (setjmp(png_jmpbuf(png)))
        fail_msg("%s: libpng could not write %s", t->label, path);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)t->width, (png_uint_32)t->height, t->bit_depth, t->color_type,
                 t->interlace, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (t->palette)
        png_set_PLTE(png, info, t->palette, t->palette_size);
    if (t->palette_alpha)
        png_set_tRNS(png, info, t->palette_alpha, t->palette_alpha_count, NULL);
    if (t->gamma_linear)
        png_set_gAMA_fixed(png, info, PNG_FP_1);
    png_write_info(png, info);
    int passes = png_set_interlace_handling(png);
    for (int pass = 0; pass < passes; pass++)
        for (int y = 0; y < t->height; y++) {
            pack_row(t, y, row, row_bytes);
            png_write_row(png, row);
        }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    assert_int_equal(fclose(f), 0);
}

/* The file's pixel (x, y) as RGBA at its own depth (palette looked up, grey copied to R, G and B, a
 * missing alpha opaque); returns that depth's largest value. */
static unsigned file_rgba(const test_png *t, int x, int y, unsigned rgba[4])
{
    int n = channels_of(t->color_type);
    const uint16_t *s = t->samples + ((size_t)y * (size_t)t->width + (size_t)x) * (size_t)n;
    unsigned max = (1u << t->bit_depth) - 1;
    switch (t->color_type) {
    case PNG_COLOR_TYPE_PALETTE: {
        const png_color *p = &t->palette[s[0]];
        rgba[0] = p->red;
        rgba[1] = p->green;
        rgba[2] = p->blue;
        rgba[3] = s[0] < t->palette_alpha_count ? t->palette_alpha[s[0]] : 255;
        return 255;
    }
    case PNG_COLOR_TYPE_GRAY:
    case PNG_COLOR_TYPE_GRAY_ALPHA:
        rgba[0] = rgba[1] = rgba[2] = s[0];
        rgba[3] = n == 2 ? s[1] : max;
        return max;
    default:
        for (int c = 0; c < 3; c++)
            rgba[c] = s[c];
        rgba[3] = n == 4 ? s[3] : max;
        return max;
    }
}

/* What RGBA8 must hold: 8-bit samples as they are, smaller depths scaled exactly to 0..255, 16-bit
 * samples round(v / 257). */
static unsigned expected_byte(unsigned v, unsigned max)
{
    if (max == 65535)
        return (unsigned)floor(v / 257.0 + 0.5);
    return v * (255 / max);
}

/* The sample over its depth's range: what RGBA32F must hold (still encoded), and what a texture
 * decodes. Depths below 8 are first expanded to 8 bits, as libpng does. */
static double expected_unit(unsigned v, unsigned max)
{
    return max == 65535 ? v / 65535.0 : expected_byte(v, max) / 255.0;
}

/* Writes t, then loads it as RGBA8 (into a padded stride), as RGBA32F, and as an sRGB and a linear
 * texture, and checks every channel of every pixel exactly. */
static void check_loads(const test_png *t)
{
    char path[64], msg[256];
    temp_path(path);
    write_test_png(path, t);
    int w = t->width, h = t->height;
    int gw = 0, gh = 0;
    assert_int_equal(bg_png_size(path, &gw, &gh, msg, sizeof msg), BG_OK);
    assert_int_equal(gw, w);
    assert_int_equal(gh, h);

    size_t stride8 = (size_t)w * 4 + 5;
    unsigned char *bytes = calloc(stride8 * (size_t)h, 1);
    float *floats = calloc((size_t)w * (size_t)h * 4, sizeof(float));
    bg_image img8 = {w, h, BG_PIXEL_RGBA8, stride8, bytes};
    bg_image img32 = {w, h, BG_PIXEL_RGBA32F, 0, floats};
    if (bg_png_load(path, &img8, msg, sizeof msg) != BG_OK || bg_png_load(path, &img32, msg, sizeof msg) != BG_OK)
        fail_msg("%s: bg_png_load failed: %s", t->label, msg);

    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t srgb = 0, lin = 0;
    bg_texture_desc linear = {.wrap = BG_WRAP_REPEAT, .encoding = BG_TEXTURE_LINEAR};
    if (bg_scene_load_texture_png(s, path, NULL, &srgb) != BG_OK ||
        bg_scene_load_texture_png(s, path, &linear, &lin) != BG_OK)
        fail_msg("%s: bg_scene_load_texture_png failed: %s", t->label, bg_scene_error_message(s));
    assert_int_equal(bg_scene_commit(s), BG_OK);
    /* An 8-bit file keeps its bytes, a 16-bit one linear floats: each read as the samplers read it. */
    const bg_texture_data *ts = &bgi_scene_committed(s)->textures[srgb - 1];
    const bg_texture_data *tl = &bgi_scene_committed(s)->textures[lin - 1];
    assert_true(t->bit_depth == 16 ? ts->texels && tl->texels : ts->bytes && tl->bytes);

    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            unsigned rgba[4];
            unsigned max = file_rgba(t, x, y, rgba);
            size_t texel = ((size_t)(h - 1 - y) * (size_t)w + (size_t)x) * 4; /* textures are bottom up */
            for (int c = 0; c < 4; c++) {
                unsigned got8 = bytes[(size_t)y * stride8 + (size_t)x * 4 + (size_t)c];
                unsigned want8 = expected_byte(rgba[c], max);
                if (got8 != want8)
                    fail_msg("%s: RGBA8 pixel (%d, %d) channel %d is %u, want %u (file sample %u of %u)", t->label,
                             x, y, c, got8, want8, rgba[c], max);
                double unit = expected_unit(rgba[c], max);
                float got32 = floats[((size_t)y * (size_t)w + (size_t)x) * 4 + (size_t)c];
                if (got32 != (float)unit)
                    fail_msg("%s: RGBA32F pixel (%d, %d) channel %d is %.9g, want %.9g", t->label, x, y, c,
                             (double)got32, (double)(float)unit);
                float want_srgb = c < 3 ? (float)bgi_srgb_to_linear(unit) : (float)unit;
                if ((float)bgi_texture_channel(ts, texel / 4, c) != want_srgb || (float)bgi_texture_channel(tl, texel / 4, c) != (float)unit)
                    fail_msg("%s: texel (%d, %d) channel %d is %.9g (sRGB) and %.9g (linear), want %.9g and %.9g",
                             t->label, x, y, c, (double)(float)bgi_texture_channel(ts, texel / 4, c), (double)(float)bgi_texture_channel(tl, texel / 4, c),
                             (double)want_srgb, (double)(float)unit);
            }
        }
    bg_scene_destroy(s);
    free(bytes);
    free(floats);
    remove(path);
}

/* Samples in [0, max], spread over the whole range (both ends included) and otherwise pseudo-random. */
static void fill_samples(uint16_t *s, size_t n, unsigned max, uint32_t seed)
{
    for (size_t i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        s[i] = (uint16_t)(i == 0 ? 0 : i == 1 ? max : (seed >> 8) % (max + 1));
    }
}

enum { TEST_W = 13, TEST_H = 7 }; /* odd sizes, so that Adam7's passes are uneven */

/* Every direct colour type at the given depth and interlace method, on noise samples. */
static void check_direct_colour_types(int bit_depth, int interlace, const char *what)
{
    static const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                PNG_COLOR_TYPE_RGB_ALPHA};
    static const char *const names[] = {"grey", "grey+alpha", "RGB", "RGBA"};
    uint16_t samples[TEST_W * TEST_H * 4];
    for (int i = 0; i < 4; i++) {
        char label[96];
        snprintf(label, sizeof label, "%d-bit %s%s", bit_depth, names[i], what);
        fill_samples(samples, TEST_W * TEST_H * 4, (1u << bit_depth) - 1, (uint32_t)(bit_depth * 10 + i));
        test_png t = {label, TEST_W, TEST_H, bit_depth, types[i], interlace, samples, NULL, 0, NULL, 0, false};
        check_loads(&t);
    }
}

static void test_load_8bit_colour_types(void **state)
{
    (void)state;
    check_direct_colour_types(8, PNG_INTERLACE_NONE, "");
}

static void test_load_16bit_colour_types(void **state)
{
    (void)state;
    check_direct_colour_types(16, PNG_INTERLACE_NONE, "");
}

static void test_load_adam7_interlaced(void **state)
{
    (void)state;
    check_direct_colour_types(8, PNG_INTERLACE_ADAM7, " (Adam7)");
    check_direct_colour_types(16, PNG_INTERLACE_ADAM7, " (Adam7)");
    /* Smaller than one 8x8 Adam7 block: some passes are empty. */
    uint16_t samples[3 * 2 * 3] = {1, 2, 3, 40000, 5, 6, 7, 65535, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18};
    test_png t = {"16-bit RGB 3x2 (Adam7)", 3, 2, 16, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_ADAM7, samples,
                  NULL, 0, NULL, 0, false};
    check_loads(&t);
}

/* Grey at 1, 2 and 4 bits is expanded to 0..255 exactly (the sample times 255, 85 or 17). */
static void test_load_low_bit_depth_grey(void **state)
{
    (void)state;
    static const int depths[] = {1, 2, 4};
    uint16_t samples[TEST_W * TEST_H];
    for (int i = 0; i < 3; i++) {
        char label[64];
        snprintf(label, sizeof label, "%d-bit grey", depths[i]);
        fill_samples(samples, TEST_W * TEST_H, (1u << depths[i]) - 1, (uint32_t)i);
        test_png t = {label, TEST_W, TEST_H, depths[i], PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, samples,
                      NULL, 0, NULL, 0, false};
        check_loads(&t);
    }
}

static void test_load_palette_with_and_without_trns(void **state)
{
    (void)state;
    png_color palette[16];
    png_byte alpha[16];
    for (int i = 0; i < 16; i++) {
        palette[i].red = (png_byte)(i * 17);
        palette[i].green = (png_byte)(255 - i * 13);
        palette[i].blue = (png_byte)(i * i);
        alpha[i] = (png_byte)(i * 31);
    }
    uint16_t samples[TEST_W * TEST_H];
    fill_samples(samples, TEST_W * TEST_H, 15, 5);
    test_png opaque = {"8-bit palette", TEST_W, TEST_H, 8, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE, samples,
                       palette, 16, NULL, 0, false};
    check_loads(&opaque);
    /* tRNS gives the first 6 entries an alpha; the others stay opaque. */
    test_png trns = {"8-bit palette with tRNS", TEST_W, TEST_H, 8, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE,
                     samples, palette, 16, alpha, 6, false};
    check_loads(&trns);
    test_png packed = {"4-bit palette with tRNS (Adam7)", TEST_W, TEST_H, 4, PNG_COLOR_TYPE_PALETTE,
                       PNG_INTERLACE_ADAM7, samples, palette, 16, alpha, 16, false};
    check_loads(&packed);
}

/* The file's samples are what loading gives, whatever its gAMA chunk says. */
static void test_load_keeps_encoding_despite_gamma_chunk(void **state)
{
    (void)state;
    uint16_t samples[TEST_W * TEST_H * 3];
    fill_samples(samples, TEST_W * TEST_H * 3, 255, 11);
    test_png t8 = {"8-bit RGB with gAMA 1.0", TEST_W, TEST_H, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, samples,
                   NULL, 0, NULL, 0, true};
    check_loads(&t8);
    fill_samples(samples, TEST_W * TEST_H * 3, 65535, 12);
    test_png t16 = {"16-bit RGB with gAMA 1.0", TEST_W, TEST_H, 16, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                    samples, NULL, 0, NULL, 0, true};
    check_loads(&t16);
}

/* The example, and the rounding of 16 bits to 8 at its edges, as literal values. */
static void test_load_16bit_reduces_by_rounding(void **state)
{
    (void)state;
    /* round(v / 257): 128 -> 0 (0.498), 129 -> 1 (0.502), 65406 -> 254 (254.498), 65407 -> 255. */
    const uint16_t samples[2 * 3] = {37, 19055, 38073, 128, 129, 65407};
    const uint16_t samples_b[2 * 3] = {65406, 65535, 0, 257, 385, 386};
    const unsigned char want[8] = {0, 74, 148, 255, 0, 1, 255, 255};
    const unsigned char want_b[8] = {254, 255, 0, 255, 1, 1, 2, 255};
    const uint16_t *inputs[2] = {samples, samples_b};
    const unsigned char *wants[2] = {want, want_b};
    for (int i = 0; i < 2; i++) {
        test_png t = {"16-bit RGB, literal", 2, 1, 16, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, inputs[i],
                      NULL, 0, NULL, 0, false};
        char path[64], msg[256];
        temp_path(path);
        write_test_png(path, &t);
        unsigned char got[8];
        bg_image img = {2, 1, BG_PIXEL_RGBA8, 0, got};
        assert_int_equal(bg_png_load(path, &img, msg, sizeof msg), BG_OK);
        assert_memory_equal(got, wants[i], 8);
        /* Floats keep all 16 bits: 19055 / 65535, not 74 / 255. */
        float f[8];
        bg_image img32 = {2, 1, BG_PIXEL_RGBA32F, 0, f};
        assert_int_equal(bg_png_load(path, &img32, msg, sizeof msg), BG_OK);
        for (int c = 0; c < 3; c++)
            assert_true(f[c] == (float)(inputs[i][c] / 65535.0));
        assert_true(f[3] == 1.0f);
        /* So does a linear texture; an sRGB one decodes the 16-bit value. */
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        uint32_t lin = 0, srgb = 0;
        bg_texture_desc d = {.wrap = BG_WRAP_CLAMP, .encoding = BG_TEXTURE_LINEAR};
        assert_int_equal(bg_scene_load_texture_png(s, path, &d, &lin), BG_OK);
        assert_int_equal(bg_scene_load_texture_png(s, path, NULL, &srgb), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        const float *tl = bgi_scene_committed(s)->textures[lin - 1].texels;
        const float *ts = bgi_scene_committed(s)->textures[srgb - 1].texels;
        for (int c = 0; c < 3; c++) {
            assert_true(tl[c] == (float)(inputs[i][c] / 65535.0));
            assert_true(ts[c] == (float)bgi_srgb_to_linear(inputs[i][c] / 65535.0));
        }
        assert_true(tl[3] == 1.0f && ts[3] == 1.0f);
        bg_scene_destroy(s);
        remove(path);
    }
}

/* A loading failure names the file and says what is wrong with it. */
static void expect_load_error(const char *path, const char *reason)
{
    char msg[256];
    unsigned char px[64 * 64 * 4];
    bg_image img = {64, 64, BG_PIXEL_RGBA8, 0, px};
    assert_int_equal(bg_png_load(path, &img, msg, sizeof msg), BG_ERR_IO);
    if (!strstr(msg, path) || !strstr(msg, reason))
        fail_msg("bg_png_load: \"%s\" does not name %s and \"%s\"", msg, path, reason);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t t = 0;
    assert_int_equal(bg_scene_load_texture_png(s, path, NULL, &t), BG_ERR_IO);
    const char *smsg = bg_scene_error_message(s);
    if (!strstr(smsg, "bg_scene_load_texture_png") || !strstr(smsg, path) || !strstr(smsg, reason))
        fail_msg("bg_scene_load_texture_png: \"%s\" does not name the call, %s and \"%s\"", smsg, path, reason);
    bg_scene_destroy(s);
}

static void test_corrupt_files_name_file_and_reason(void **state)
{
    (void)state;
    enum { W = 64, H = 64 };
    uint16_t *samples = malloc(W * H * 4 * sizeof *samples);
    fill_samples(samples, W * H * 4, 65535, 9);
    test_png t = {"16-bit RGBA 64x64", W, H, 16, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, samples,
                  NULL, 0, NULL, 0, false};
    char path[64];
    temp_path(path);
    write_test_png(path, &t);
    long n = file_size(path);

    /* A flipped byte inside the image data: its chunk's CRC no longer matches. */
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, n / 2, SEEK_SET), 0);
    int byte = fgetc(f);
    assert_int_equal(fseek(f, n / 2, SEEK_SET), 0);
    fputc(byte ^ 0x55, f);
    fclose(f);
    expect_load_error(path, "CRC");

    /* Cut in the middle of the image data, and in the middle of the header. */
    write_test_png(path, &t);
    assert_int_equal(truncate(path, n / 2), 0);
    expect_load_error(path, "truncated");
    assert_int_equal(truncate(path, 20), 0);
    expect_load_error(path, "truncated");
    int w, h;
    char msg[256];
    assert_int_equal(bg_png_size(path, &w, &h, msg, sizeof msg), BG_ERR_IO);
    assert_non_null(strstr(msg, "truncated"));

    /* Not a PNG at all. */
    f = fopen(path, "wb");
    assert_non_null(f);
    fputs("this is not a PNG file, just text long enough to read a header from", f);
    fclose(f);
    expect_load_error(path, "not a PNG file");
    remove(path);
    free(samples);
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
    bg_texture_desc d = {BG_WRAP_CLAMP, BG_TEXTURE_LINEAR, BG_FILTER_LINEAR};
    assert_int_equal(bg_scene_load_texture_png(s, path, &d, &t), BG_OK);
    assert_int_equal(t, 1);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_texture_data *tex = &bgi_scene_committed(s)->textures[0];
    assert_int_equal(tex->width, 1);
    assert_int_equal(tex->height, 2);
    assert_int_equal(tex->wrap, BG_WRAP_CLAMP);
    assert_non_null(tex->bytes); /* an 8-bit file stays 8-bit */
    assert_true(tex->texels == NULL && !tex->srgb);
    assert_memory_equal(tex->bytes, ((const unsigned char[8]){128, 128, 128, 64, 255, 0, 0, 255}), 8);
    assert_true(bgi_texture_channel(tex, 0, 0) == 128 / 255.0 && bgi_texture_channel(tex, 0, 3) == 64 / 255.0);
    assert_true(bgi_texture_channel(tex, 1, 0) == 1.0 && bgi_texture_channel(tex, 1, 1) == 0.0);
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
    const bg_texture_data *tex = &bgi_scene_committed(s)->textures[0];
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
    assert_true(bgi_srgb_to_linear(0.0) == 0.0);
    assert_true(bgi_srgb_to_linear(1.0) == 1.0);
    /* Both branches meet at the 0.04045 boundary (linear 0.0031308). */
    double lo = 0.04045 / 12.92, hi = pow((0.04045 + 0.055) / 1.055, 2.4);
    assert_true(fabs(bgi_srgb_to_linear(0.04045) - lo) < 1e-15);
    assert_true(fabs(lo - hi) < 1e-7);
    assert_true(fabs(bgi_srgb_to_linear(0.5) - 0.21404114048223255) < 1e-12);
    assert_true(fabs(bgi_linear_to_srgb(bgi_srgb_to_linear(0.7)) - 0.7) < 1e-12);

    /* Through a texture: bytes 0, 10 (linear branch), 11 (power branch), 255; alpha stays linear. */
    unsigned char px[16] = {0, 10, 11, 255, 255, 128, 0, 128, 0, 0, 0, 0, 0, 0, 0, 0};
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_image img = {4, 1, BG_PIXEL_RGBA8, 0, px};
    uint32_t srgb, lin;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &srgb), BG_OK);
    bg_texture_desc d = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR, BG_FILTER_LINEAR};
    assert_int_equal(bg_scene_add_texture(s, &img, &d, &lin), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_texture_data *ta = &bgi_scene_committed(s)->textures[0], *tb = &bgi_scene_committed(s)->textures[1];
    assert_true(ta->bytes && ta->srgb && tb->bytes && !tb->srgb);
    float a[16], b[16];
    for (int k = 0; k < 16; k++) {
        a[k] = (float)bgi_texture_channel(ta, (size_t)k / 4, k % 4);
        b[k] = (float)bgi_texture_channel(tb, (size_t)k / 4, k % 4);
    }
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
        cmocka_unit_test(test_load_8bit_colour_types),
        cmocka_unit_test(test_load_16bit_colour_types),
        cmocka_unit_test(test_load_adam7_interlaced),
        cmocka_unit_test(test_load_low_bit_depth_grey),
        cmocka_unit_test(test_load_palette_with_and_without_trns),
        cmocka_unit_test(test_load_keeps_encoding_despite_gamma_chunk),
        cmocka_unit_test(test_load_16bit_reduces_by_rounding),
        cmocka_unit_test(test_corrupt_files_name_file_and_reason),
        cmocka_unit_test(test_texture_from_png_file),
        cmocka_unit_test(test_texture_flip_stride_and_float),
        cmocka_unit_test(test_srgb_decode),
    };
    return cmocka_run_group_tests_name("bg_png", tests, NULL, NULL);
}
