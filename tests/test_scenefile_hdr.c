/* Radiance .hdr decoding (src/scenefile/hdr_decode.c) checked row by row against a small decoder of
 * this test's own, written from the format: flat scanlines (4 bytes a pixel, as the shipped sky.hdr
 * is written) and run-length scanlines (a 2 2 hi lo record, then each channel as runs and literal
 * dumps). A decoder that leaves any row unwritten, or decodes one into another, fails here with the
 * row named: Debian unstable's prebuilt libstb left every odd row of sky.hdr unwritten. A header that
 * declares more pixels than the file can hold is refused before anything is allocated. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include <cmocka.h>

#include "util_files.h"

#include "scenefile/scenefile_internal.h"

#define SKY "examples/scenes/json/sky.hdr"

/* RGBE to linear radiance: mantissa times 2^(exponent - 136), exponent 0 is black (the convention
 * of Radiance's own colour conversion without its half-step offset, which stb_image follows). */
static float rgbe_channel(unsigned char m, unsigned char e)
{
    return e == 0 ? 0.0f : ldexpf((float)m, (int)e - 136);
}

/* The test's reference decoder: the pixels after the header of data (size bytes), w x h, into rgbe
 * (4 bytes a pixel); false for a malformed stream. Flat or run-length, per scanline. */
static bool reference_decode(const unsigned char *data, size_t size, int w, int h, unsigned char *rgbe)
{
    size_t at = 0;
    for (int y = 0; y < h; y++) {
        unsigned char *row = rgbe + (size_t)y * (size_t)w * 4;
        bool rle = w >= 8 && w < 32768 && at + 4 <= size && data[at] == 2 && data[at + 1] == 2 &&
                   !(data[at + 2] & 0x80) && ((data[at + 2] << 8) | data[at + 3]) == w;
        if (!rle) {
            if (at + (size_t)w * 4 > size)
                return false;
            memcpy(row, data + at, (size_t)w * 4);
            at += (size_t)w * 4;
            continue;
        }
        at += 4;
        for (int c = 0; c < 4; c++) {
            for (int x = 0; x < w;) {
                if (at >= size)
                    return false;
                int count = data[at++];
                if (count > 128) {
                    count -= 128;
                    if (at >= size || x + count > w)
                        return false;
                    for (int k = 0; k < count; k++)
                        row[(x + k) * 4 + c] = data[at];
                    at++;
                } else {
                    if (count == 0 || x + count > w || at + (size_t)count > size)
                        return false;
                    for (int k = 0; k < count; k++)
                        row[(x + k) * 4 + c] = data[at++];
                }
                x += count;
            }
        }
    }
    return true;
}

/* Where the pixels start: after the blank line that ends the header and the resolution line. */
static size_t pixel_offset(const unsigned char *data, size_t size)
{
    const unsigned char *blank = NULL;
    for (size_t i = 0; i + 1 < size && !blank; i++)
        if (data[i] == '\n' && data[i + 1] == '\n')
            blank = data + i + 2;
    assert_non_null(blank);
    const unsigned char *end = memchr(blank, '\n', size - (size_t)(blank - data));
    assert_non_null(end);
    return (size_t)(end + 1 - data);
}

/* Decodes path with the library and with the reference, and compares every pixel, naming the first
 * row that differs. */
static void expect_rows_match(const char *path, int w, int h)
{
    size_t size = 0;
    unsigned char *data = util_read_file(path, &size);
    size_t at = pixel_offset(data, size);
    unsigned char *rgbe = calloc((size_t)w * (size_t)h, 4);
    assert_non_null(rgbe);
    assert_true(reference_decode(data + at, size - at, w, h, rgbe));

    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char why[256] = "";
    int dw = 0, dh = 0;
    float *texels = bgi_sf_hdr_decode(f, &dw, &dh, why, sizeof why);
    fclose(f);
    if (!texels)
        fail_msg("%s: %s", path, why);
    assert_int_equal(dw, w);
    assert_int_equal(dh, h);
    int rows_checked = 0;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const unsigned char *p = rgbe + ((size_t)y * (size_t)w + (size_t)x) * 4;
            const float *t = texels + ((size_t)y * (size_t)w + (size_t)x) * 4;
            for (int c = 0; c < 3; c++) {
                float want = rgbe_channel(p[c], p[3]);
                if (t[c] != want)
                    fail_msg("%s: row %d, pixel %d, channel %d: decoded %.9g, the format gives %.9g", path, y, x, c,
                             (double)t[c], (double)want);
            }
        }
        rows_checked++;
    }
    assert_int_equal(rows_checked, h);
    bgi_sf_hdr_free(texels);
    free(rgbe);
    free(data);
}

/* The shipped sky: 256 x 128 flat scanlines, every row (odd ones included) as the format says. */
static void shipped_sky_decodes_every_row(void **state)
{
    (void)state;
    expect_rows_match(SKY, 256, 128);
}

/* Appends one run-length scanline of w pixels: each channel alternates a run and a literal dump. */
static size_t put_rle_row(unsigned char *out, const unsigned char *row, int w)
{
    size_t n = 0;
    out[n++] = 2;
    out[n++] = 2;
    out[n++] = (unsigned char)(w >> 8);
    out[n++] = (unsigned char)(w & 0xff);
    for (int c = 0; c < 4; c++) {
        for (int x = 0; x < w;) {
            int run = 1;
            while (x + run < w && run < 127 && row[(x + run) * 4 + c] == row[x * 4 + c])
                run++;
            if (run >= 3) {
                out[n++] = (unsigned char)(128 + run);
                out[n++] = row[x * 4 + c];
                x += run;
            } else {
                int lit = 0;
                while (x + lit < w && lit < 128 &&
                       !(x + lit + 2 < w && row[(x + lit) * 4 + c] == row[(x + lit + 1) * 4 + c] &&
                         row[(x + lit) * 4 + c] == row[(x + lit + 2) * 4 + c]))
                    lit++;
                if (lit == 0)
                    lit = 1;
                out[n++] = (unsigned char)lit;
                for (int k = 0; k < lit; k++)
                    out[n++] = row[(x + k) * 4 + c];
                x += lit;
            }
        }
    }
    return n;
}

/* A run-length file written here (40 x 9, runs and literal dumps on every row, values that differ
 * per row): every row decodes as written. */
static void run_length_file_decodes_every_row(void **state)
{
    (void)state;
    enum { W = 40, H = 9 };
    unsigned char pixels[W * H * 4];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            unsigned char *p = pixels + (y * W + x) * 4;
            p[0] = (unsigned char)(x < 10 ? 200 : 128 + ((x * 7 + y * 13) % 120)); /* a run, then literals */
            p[1] = (unsigned char)(128 + y * 9);                                 /* one run per row */
            p[2] = (unsigned char)(x % 4 < 2 ? 140 : 250 - y);                   /* short runs */
            p[3] = (unsigned char)(120 + y);                                      /* exponent per row */
        }
    const char *path = "test_scenefile_hdr_rle.hdr";
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fprintf(f, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", H, W);
    unsigned char line[W * 4 * 2 + 16];
    for (int y = 0; y < H; y++) {
        size_t n = put_rle_row(line, pixels + y * W * 4, W);
        assert_true(n < (size_t)W * 4); /* really run-length coded, not longer than flat */
        assert_int_equal(fwrite(line, 1, n, f), n);
    }
    fclose(f);
    expect_rows_match(path, W, H);
    remove(path);
}

/* A 40-byte file whose header declares 16384 x 8191 pixels is refused before the decoder allocates
 * 2 GiB for them, with the size and what the file holds. */
static void declared_size_beyond_the_file_is_refused(void **state)
{
    (void)state;
    const char *path = "test_scenefile_hdr_huge.hdr";
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fprintf(f, "#?RADIANCE\n\n-Y 8191 +X 16384\n");
    fwrite("\x02\x02\x40\x00", 1, 4, f);
    fclose(f);
    f = fopen(path, "rb");
    assert_non_null(f);
    char why[256] = "";
    int w = 0, h = 0;
    float *texels = bgi_sf_hdr_decode(f, &w, &h, why, sizeof why);
    fclose(f);
    remove(path);
    assert_null(texels);
    print_message("refused: %s\n", why);
    assert_non_null(strstr(why, "16384 x 8191"));
    assert_non_null(strstr(why, "the file holds 4"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shipped_sky_decodes_every_row),
        cmocka_unit_test(run_length_file_decodes_every_row),
        cmocka_unit_test(declared_size_beyond_the_file_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
