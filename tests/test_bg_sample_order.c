/* The order in which a pixel's samples are taken (bgi_sample_order, docs/shading.md 1.1): a
 * permutation of the pattern's samples for every count 1 .. BG_MAX_SAMPLES, whose every first k
 * spread over the pixel: the mean of their positions is the pixel centre exactly for every balanced
 * prefix and within 1 / (2k) of it otherwise, the first two lie in different halves and the first
 * four in different quadrants wherever the grid has halves, and on grids of 2^a x 2^b cells the
 * first 2^j fill the 2^ceil(j/2) x 2^floor(j/2) blocks once each. A preview of the first k of 16
 * samples of a slanted edge comes within bounds measured here of the exact coverage, bounds the cell
 * order before (row by row from the top) exceeds. */
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
#include "betelgeuse/common/render_view.h"
#include "betelgeuse/cpu/cpu_internal.h"
#include "util_coverage.h"

static void grid_of(int n, int *rows, int *columns)
{
    *rows = bgi_sample_rows(n);
    *columns = n / *rows;
}

static void order_is_a_permutation(void **state)
{
    (void)state;
    for (int n = 1; n <= BG_MAX_SAMPLES; n++) {
        unsigned char seen[BG_MAX_SAMPLES] = {0};
        for (int k = 0; k < n; k++) {
            int s = bgi_sample_order(n, k);
            if (s < 0 || s >= n || seen[s])
                fail_msg("n = %d: the %d-th sample taken is %d, %s", n, k, s,
                         s < 0 || s >= n ? "outside the pattern" : "taken before");
            seen[s] = 1;
        }
    }
    /* One sample (0 and 1 alike) is the pixel centre, as before. */
    assert_int_equal(bgi_sample_order(0, 0), 0);
    assert_int_equal(bgi_sample_order(1, 0), 0);
    double px, py;
    bgi_sample_position(1, bgi_sample_order(1, 0), &px, &py);
    assert_true(px == 0.5 && py == 0.5);
}

/* The positions are multiples of 2^-10 and a pair's two sum to 1 exactly, so the sums are exact. */
static void prefixes_are_centred(void **state)
{
    (void)state;
    for (int n = 1; n <= BG_MAX_SAMPLES; n++) {
        double sx = 0.0, sy = 0.0;
        for (int k = 1; k <= n; k++) {
            double px, py;
            bgi_sample_position(n, bgi_sample_order(n, k - 1), &px, &py);
            sx += px;
            sy += py;
            double dx = fabs(sx / k - 0.5), dy = fabs(sy / k - 0.5);
            /* Balanced: every pair complete (even k of an even n; odd k of an odd n, whose first
             * sample is the centre cell). */
            bool balanced = (k % 2) == (n % 2);
            if (balanced ? dx != 0.0 || dy != 0.0 : dx > 0.5 / k || dy > 0.5 / k)
                fail_msg("n = %d: the first %d samples have their mean %.4f, %.4f off the pixel centre (bound %s)", n,
                         k, sx / k - 0.5, sy / k - 0.5, balanced ? "0" : "1 / (2k)");
        }
    }
}

/* The first k of n in distinct blocks of a grid of bx x by blocks (bx divides columns, by rows). */
static bool distinct_blocks(int n, int k, int bx, int by)
{
    int rows, columns;
    grid_of(n, &rows, &columns);
    unsigned char hit[BG_MAX_SAMPLES] = {0};
    for (int i = 0; i < k; i++) {
        int s = bgi_sample_order(n, i);
        int block = (s / columns) * by / rows * bx + (s % columns) * bx / columns;
        if (hit[block])
            return false;
        hit[block] = 1;
    }
    return true;
}

static void halves_and_quadrants(void **state)
{
    (void)state;
    for (int n = 2; n <= BG_MAX_SAMPLES; n++) {
        int rows, columns;
        grid_of(n, &rows, &columns);
        bool even_x = columns % 2 == 0, even_y = rows % 2 == 0;
        if (even_x && !distinct_blocks(n, 2, 2, 1))
            fail_msg("n = %d (%d x %d): the first two samples share a column half", n, rows, columns);
        if (even_y && !distinct_blocks(n, 2, 1, 2))
            fail_msg("n = %d (%d x %d): the first two samples share a row half", n, rows, columns);
        if (even_x && even_y && n >= 4 && !distinct_blocks(n, 4, 2, 2))
            fail_msg("n = %d (%d x %d): the first four samples share a quadrant", n, rows, columns);
        /* A grid of 2^a x 2^b: the first 2^j fill the blocks of j digits, columns taking the first. */
        if ((n & (n - 1)) == 0)
            for (int j = 1, k = 2; k <= n; j++, k *= 2)
                if (!distinct_blocks(n, k, 1 << ((j + 1) / 2), 1 << (j / 2)))
                    fail_msg("n = %d: the first %d samples do not fill the %d x %d blocks", n, k, 1 << ((j + 1) / 2),
                             1 << (j / 2));
    }
}

/* The preview of the first k of 16 samples of the slanted edge (20 degrees from the vertical),
 * RGBA32F, through the CPU's own sample loop (sample_first 0, sample_count k), against the exact
 * coverage; the CPU reference is deterministic, so the bounds sit just above what was measured
 * (64 x 48): k = 1, 2, 4, 8: max 0.5533, 0.3695, 0.1510, 0.1084, mean 0.00429, 0.00281, 0.00126,
 * 0.00084. The cell order before (the pixel's top row first) gave max 0.7334, 0.4614, 0.2334, 0.1510
 * and mean 0.00524, 0.00312, 0.00215, 0.00141, above every bound; a near-vertical edge is the kind
 * that order handled best, since its top row spans the pixel's width. */
enum { W = 64, H = 48, N = 16 };

static void previews_follow_the_coverage(void **state)
{
    (void)state;
    static const int counts[] = {1, 2, 4, 8};
    static const double max_bound[] = {0.56, 0.38, 0.16, 0.11}, mean_bound[] = {0.0045, 0.0029, 0.0013, 0.0009};
    bg_scene *s = util_edge_scene();
    bg_render_settings set = util_edge_settings(N);
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_non_null(st);
    float *rgba = malloc((size_t)W * H * 16);
    assert_non_null(rgba);
    for (int i = 0; i < 4; i++) {
        bgi_render_view view = {W, H, 0, 0, W, H, N, 0, counts[i]};
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                bgi_cpu_render_texel(st, &set, &view, x, y, BG_PIXEL_RGBA32F, rgba + ((size_t)y * W + x) * 4);
        double max, mean;
        util_edge_error(rgba, W, H, &max, &mean);
        print_message("first %d of %d samples: max error %.4f, mean %.5f\n", counts[i], N, max, mean);
        assert_true(max <= max_bound[i]);
        assert_true(mean <= mean_bound[i]);
    }
    free(rgba);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(order_is_a_permutation),
        cmocka_unit_test(prefixes_are_centred),
        cmocka_unit_test(halves_and_quadrants),
        cmocka_unit_test(previews_follow_the_coverage),
    };
    return cmocka_run_group_tests_name("bg_sample_order", tests, NULL, NULL);
}
