/* Image comparison metrics: per-channel errors, PSNR, share of differing pixels, silhouette mask. */
#include "image_metrics.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Sums over one pixel set while it is being scanned. */
typedef struct diff_sum {
    image_diff d;
    double sum_abs[3];
    double sum_sq;
    int worst;
} diff_sum;

static const unsigned char *pixel8(const bg_image *image, int x, int y)
{
    size_t stride = image->stride ? image->stride : (size_t)image->width * 4;
    return (const unsigned char *)image->pixels + (size_t)y * stride + (size_t)x * 4;
}

static bool is_rgba8(const bg_image *image)
{
    return image && image->pixels && image->format == BG_PIXEL_RGBA8 && image->width > 0 && image->height > 0 &&
           (image->stride == 0 || image->stride >= (size_t)image->width * 4);
}

/* True when a neighbour of (x, y) in the reference differs from it by more than threshold. */
static bool silhouette(const bg_image *ref, int x, int y, int threshold)
{
    const unsigned char *p = pixel8(ref, x, y);
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= ref->width || ny >= ref->height)
                continue;
            const unsigned char *q = pixel8(ref, nx, ny);
            for (int c = 0; c < 3; c++)
                if (p[c] > q[c] + threshold || q[c] > p[c] + threshold)
                    return true;
        }
    return false;
}

static void add_pixel(diff_sum *s, const int e[3], int x, int y)
{
    int worst = 0;
    for (int c = 0; c < 3; c++) {
        s->sum_abs[c] += e[c];
        s->sum_sq += (double)e[c] * e[c];
        if (e[c] > s->d.max_abs[c])
            s->d.max_abs[c] = e[c];
        if (e[c] > worst)
            worst = e[c];
    }
    if (worst > s->worst || s->d.pixels == 0) {
        s->worst = worst;
        s->d.worst_x = x;
        s->d.worst_y = y;
    }
    s->d.over_count += worst > IMAGE_METRICS_OVER;
    s->d.pixels++;
}

static image_diff finish(const diff_sum *s)
{
    image_diff d = s->d;
    if (d.pixels == 0) {
        d.psnr_db = IMAGE_METRICS_PSNR_IDENTICAL;
        return d;
    }
    for (int c = 0; c < 3; c++)
        d.mean_abs[c] = s->sum_abs[c] / (double)d.pixels;
    double mse = s->sum_sq / (3.0 * (double)d.pixels);
    d.psnr_db = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : IMAGE_METRICS_PSNR_IDENTICAL;
    d.over_share = (double)d.over_count / (double)d.pixels;
    return d;
}

bool image_metrics_compare(const bg_image *reference, const bg_image *test, int silhouette_threshold,
                           image_metrics *out)
{
    if (!out)
        return false;
    memset(out, 0, sizeof *out);
    if (!is_rgba8(reference) || !is_rgba8(test) || reference->width != test->width ||
        reference->height != test->height)
        return false;
    diff_sum all, interior;
    memset(&all, 0, sizeof all);
    memset(&interior, 0, sizeof interior);
    for (int y = 0; y < reference->height; y++)
        for (int x = 0; x < reference->width; x++) {
            const unsigned char *a = pixel8(reference, x, y), *b = pixel8(test, x, y);
            int e[3];
            for (int c = 0; c < 3; c++)
                e[c] = a[c] > b[c] ? a[c] - b[c] : b[c] - a[c];
            add_pixel(&all, e, x, y);
            if (silhouette(reference, x, y, silhouette_threshold))
                out->silhouette_pixels++;
            else
                add_pixel(&interior, e, x, y);
        }
    out->width = reference->width;
    out->height = reference->height;
    out->silhouette_threshold = silhouette_threshold;
    out->all = finish(&all);
    out->interior = finish(&interior);
    return true;
}

/* The largest channel difference of test over reference at (x, y), and of reference over test. */
static void channel_drops(const bg_image *ref, const bg_image *test, int x, int y, int *darker, int *brighter)
{
    const unsigned char *a = pixel8(ref, x, y), *b = pixel8(test, x, y);
    *darker = 0;
    *brighter = 0;
    for (int c = 0; c < 3; c++) {
        int d = (int)a[c] - (int)b[c];
        if (d > *darker)
            *darker = d;
        if (-d > *brighter)
            *brighter = -d;
    }
}

static bool differs(const bg_image *ref, const bg_image *test, int x, int y)
{
    int darker, brighter;
    channel_drops(ref, test, x, y, &darker, &brighter);
    return darker > IMAGE_METRICS_OVER || brighter > IMAGE_METRICS_OVER;
}

static bool lone(const bg_image *ref, const bg_image *test, int x, int y)
{
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= ref->width || ny >= ref->height)
                continue;
            if (differs(ref, test, nx, ny))
                return false;
        }
    return true;
}

bool image_metrics_acne(const bg_image *reference, const bg_image *test, int silhouette_threshold, image_acne *out)
{
    if (!out)
        return false;
    memset(out, 0, sizeof *out);
    out->first_x = out->first_y = -1;
    if (!is_rgba8(reference) || !is_rgba8(test) || reference->width != test->width ||
        reference->height != test->height)
        return false;
    for (int y = 0; y < reference->height; y++)
        for (int x = 0; x < reference->width; x++) {
            if (silhouette(reference, x, y, silhouette_threshold))
                continue;
            out->interior++;
            int darker, brighter;
            channel_drops(reference, test, x, y, &darker, &brighter);
            bool shadowed = darker > IMAGE_METRICS_OVER && brighter <= IMAGE_METRICS_ACNE_ROUNDING;
            bool speckle = (darker > IMAGE_METRICS_OVER || brighter > IMAGE_METRICS_OVER) && lone(reference, test, x, y);
            out->shadowed += shadowed;
            out->speckles += speckle;
            if (shadowed || speckle) {
                if (out->pixels == 0) {
                    out->first_x = x;
                    out->first_y = y;
                }
                out->pixels++;
            }
        }
    return true;
}

size_t image_metrics_count_nonfinite(const bg_image *image)
{
    if (!image || !image->pixels || image->format != BG_PIXEL_RGBA32F || image->width <= 0 || image->height <= 0)
        return (size_t)-1;
    size_t stride = image->stride ? image->stride : (size_t)image->width * 4 * sizeof(float);
    size_t n = 0;
    for (int y = 0; y < image->height; y++) {
        const float *row = (const float *)(const void *)((const unsigned char *)image->pixels + (size_t)y * stride);
        for (int i = 0; i < image->width * 4; i++)
            n += !isfinite(row[i]);
    }
    return n;
}

static double max3(const double v[3])
{
    return fmax(v[0], fmax(v[1], v[2]));
}

char *image_metrics_format(const image_metrics *m, char *buffer, size_t size)
{
    if (!buffer || size == 0)
        return buffer;
    if (!m) {
        buffer[0] = '\0';
        return buffer;
    }
    snprintf(buffer, size,
             "%dx%d all: max %.0f/%.0f/%.0f mean %.3f/%.3f/%.3f psnr %.2f over %.4f (%ld) | "
             "interior (silhouette %ld px at >%d): max %.0f/%.0f/%.0f at (%d,%d) mean %.3f psnr %.2f over %.4f (%ld)",
             m->width, m->height, m->all.max_abs[0], m->all.max_abs[1], m->all.max_abs[2], m->all.mean_abs[0],
             m->all.mean_abs[1], m->all.mean_abs[2], m->all.psnr_db, m->all.over_share, m->all.over_count,
             m->silhouette_pixels, m->silhouette_threshold, m->interior.max_abs[0], m->interior.max_abs[1],
             m->interior.max_abs[2], m->interior.worst_x, m->interior.worst_y, max3(m->interior.mean_abs),
             m->interior.psnr_db, m->interior.over_share, m->interior.over_count);
    return buffer;
}
