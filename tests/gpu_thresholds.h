/* How far the GPU renderer may stray from the double-precision CPU reference, per shared scene: the
 * one table behind test_bg_gpu_scenes (160x120) and test_smoke_bg_gpu (96x96, every backend and
 * driver). Errors are in 0..255 units of the sRGB-encoded RGBA8 output; image_metrics computes them.
 *
 * The bounds follow from an error model (docs/architecture.md, "Tests": "The error model"), not from
 * what one driver happens to give. Per channel, away from silhouettes:
 *   - float against double in intersection and shading: a few hundred float roundings (2^-24 each)
 *     between the camera and a pixel's linear radiance x, a relative difference below 2^-16, which
 *     the sRGB encoding turns into at most 255 * 2^-16 * max(x srgb'(x)) < 0.002 of an 8-bit step;
 *   - texture filtering, now in the shader with float weights (docs/shading.md 5.1): at most
 *     2^-22 (J_x W + J_y H) in linear value, J the largest step between neighbouring texels; for
 *     the scenes' textures (at most 256 texels a side) under 1.3e-4 J, under 0.002 of an 8-bit step
 *     on average. A texture unit's 8-bit weights would
 *     add J/1024 per axis on average, 60-120 times more: the means of 0.013-0.018 an NVIDIA H200
 *     gave with GL_LINEAR;
 *   - the 8-bit encoding: CPU and GPU each round to the nearest step, so a difference d of the
 *     encoded values before rounding gives an error of ceil(|d|) steps at most, and an error at all
 *     with probability |d|.
 * So a non-silhouette pixel is off by at most 1 step (interior_max 2: one more for GPUs whose pow,
 * atan and acos, which GLSL leaves without a stated precision, are less exact than Mesa's), the
 * mean error over those pixels is the expected |d|, at most 0.004 with both terms doubled for the
 * same reason, and with every error at most 2 steps, MSE <= 2 * mean, so PSNR >= 10 log10(255^2 /
 * 0.008) = 69.1 dB: these three are taken over the interior pixels.
 *
 * Silhouettes (the silhouette allowance): where a ray grazes an edge (an object's rim, a shadow's
 * edge, a texel edge of a NEAREST texture), float and double may pick another object or shadow
 * outcome: any error, on isolated pixels. A reference pixel is a silhouette pixel when a neighbour
 * differs from it by more than 24 (GPU_SILHOUETTE_THRESHOLD); the allowance is the share of pixels,
 * silhouettes included, that may be off by more than 8 (over: 0.001, 19 pixels at 160x120, 9 at
 * 96x96). An edge moved by a third of a pixel or more changes each of its silhouette pixels by more
 * than 24 / 3 = 8, so a shifted or missing edge shows in over (the half-pixel camera offset below
 * puts 1 % of pixels or more there).
 *
 * Measured on Mesa 22.3 (llvmpipe through OSMesa and EGL surfaceless, softpipe through OSMesa) at
 * 160x120 and 96x96, every pixel (beside each row): far inside the model, as it should be. Measured
 * with each mistake built into the CPU renderer and compared with the unchanged one (every scene the
 * mistake changes, at 160x120 and 96x96; all were caught):
 *   half-pixel camera offset            over >= 0.010 and PSNR <= 34 dB on every scene
 *   no shadows                          interior max >= 149, PSNR <= 27 dB
 *   normals left in object space        interior max >= 31, PSNR <= 35 dB
 *   normals tilted by about 3 degrees   interior max >= 3 (paper_earth), PSNR <= 50 dB
 *   Schlick's approximation for Fresnel interior max 9 (glass), 4 (many_spheres)
 *   s-polarised Fresnel term only       interior max >= 17, PSNR <= 42 dB
 * test_bg_gpu_scenes checks the first of these against this table on every run. */
#ifndef GPU_THRESHOLDS_H
#define GPU_THRESHOLDS_H

#include <stdbool.h>
#include <stdio.h>

#include "scenes/image_metrics.h"
#ifndef GPU_THRESHOLDS_NO_PROFILES
#include "util_gl.h"
#endif
#include "scenes/scenes.h"

/* A reference pixel is a silhouette pixel when a neighbour differs from it by more than this. */
#define GPU_SILHOUETTE_THRESHOLD 24

/* The bounds of one scene. */
typedef struct gpu_threshold {
    scene_id scene;
    double interior_max; /* largest error of any RGB channel over non-silhouette pixels */
    double mean;         /* mean error of each RGB channel over non-silhouette pixels */
    double psnr;         /* lowest PSNR over non-silhouette pixels, dB */
    double over;         /* largest share of pixels with a channel error above 8 (every pixel) */
} gpu_threshold;

/* The model's bounds for every shared scene (see above); measured on Mesa over every pixel. */
static const gpu_threshold gpu_thresholds[SCENE_COUNT] = {
    /* scene                 interior_max mean   psnr  over      measured: interior max, mean, PSNR, over */
    {SCENE_PAPER_EARTH,          2.0,  0.004, 69.0, 0.001}, /* 1, < 0.0005, 90.96, 0 */
    {SCENE_PAPER_EARTH_SHADOW,   2.0,  0.004, 69.0, 0.001}, /* 1, < 0.0005, 87.78, 0 */
    {SCENE_MIRROR,               2.0,  0.004, 69.0, 0.001}, /* 0, 0, identical, 0 */
    {SCENE_GLASS,                2.0,  0.004, 69.0, 0.001}, /* 0, 0.0013, 74.77, 0 */
    {SCENE_MANY_SPHERES,         2.0,  0.004, 69.0, 0.001}, /* 1, 0.00011, 87.78, 0 */
    {SCENE_MANY_LIGHTS,          2.0,  0.004, 69.0, 0.001}, /* 0, 0, identical, 0 */
    {SCENE_ALL_PRIMITIVES,       2.0,  0.004, 69.0, 0.001}, /* 0, 0, identical, 0 */
    {SCENE_TEXTURED_ANISO,       2.0,  0.004, 69.0, 0.001}, /* 1, 0.0010, 80.55, 0 */
};

/* The row of the stress suite's mesh scenes (examples/scenes/stress_cases.c, the terrain at 1e-3,
 * 1 and 1e4, measured alike at every scale): a ray leaving a triangle starts 256 ulps of the point
 * off it in float on the GPU, in double on the CPU, so the GPU's shadow segments start higher and
 * pass over a ridge that the CPU's graze, which moves cast shadows' edges by a pixel in places (up
 * to 77/255 on 6 of 19200 pixels, every one a silhouette pixel: the model's silhouette allowance);
 * measured 1, < 0.0005, 90.63 dB over the interior, over 0.00031. So the common row of the model.
 * With the GPU's offset at 0 the terrain at scale 1 has an acne pixel off by 144 (interior), which
 * this row catches. */
static const gpu_threshold gpu_mesh_threshold = {SCENE_COUNT, 2.0, 0.004, 69.0, 0.001};

/* A row widened for a context that blends only 16-bit floats, where the multipass accumulates its
 * light passes in RGBA16F (src/betelgeuse/gpu/multipass/targets.c). Each add rounds the running sum
 * to 11 significant bits, a relative error up to 2^-11, which the encoding turns into at most
 * 255 * 2^-11 * max(x srgb'(x)) = 255 * 2^-11 * 0.44 = 0.055 of an 8-bit step per add (x srgb'(x)
 * is largest at x = 1); a pixel takes 2 to 5 adds (ambient and emission, each light, each level),
 * whose roundings are independent and partly cancel. The expected |d| of the model above thus gains
 * at most 0.055 per add: the mean bound becomes 0.06 (measured 0.023 to 0.029 under the geforce7
 * profile on llvmpipe, 160x120), the PSNR floor 10 log10(255^2 / (2 * 0.06)) = 57.3 dB. The
 * interior max stays: one add's error is far below a step, so a pixel is still off by 1 at most
 * (2 with the slack above). Only the tests under such a profile use it. */
static inline gpu_threshold gpu_threshold_half_accumulation(const gpu_threshold *row)
{
    gpu_threshold t = *row;
    t.mean = t.mean > 0.06 ? t.mean : 0.06;
    t.psnr = t.psnr < 57.0 ? t.psnr : 57.0;
    return t;
}

/* The row of a scene (the table is in scene_id order). */
static inline const gpu_threshold *gpu_threshold_of(scene_id id)
{
    return &gpu_thresholds[id];
}

/* True when m is within t; otherwise writes the first bound broken into why. interior_max, mean and
 * PSNR over the interior pixels, over over every pixel (the error model above). */
static inline bool gpu_threshold_check(const gpu_threshold *t, const image_metrics *m, char *why, size_t size)
{
    /* Under a profile whose context blends no RGBA32F target, every check takes the wider row. */
#ifndef GPU_THRESHOLDS_NO_PROFILES /* bench/stress.c: no test context, no profile */
    gpu_threshold half;
    if (util_half_accumulation()) {
        half = gpu_threshold_half_accumulation(t);
        t = &half;
    }
#endif
    for (int c = 0; c < 3; c++) {
        if (m->interior.max_abs[c] > t->interior_max) {
            snprintf(why, size, "channel %d: interior max error %.0f > %.1f at pixel (%d, %d)", c,
                     m->interior.max_abs[c], t->interior_max, m->interior.worst_x, m->interior.worst_y);
            return false;
        }
        if (m->interior.mean_abs[c] > t->mean) {
            snprintf(why, size, "channel %d: interior mean error %.4f > %.4f", c, m->interior.mean_abs[c], t->mean);
            return false;
        }
    }
    if (m->interior.psnr_db < t->psnr) {
        snprintf(why, size, "interior PSNR %.2f dB < %.2f dB", m->interior.psnr_db, t->psnr);
        return false;
    }
    if (m->all.over_share > t->over) {
        snprintf(why, size, "%ld pixels (share %.5f > %.5f) differ by more than %d/255", m->all.over_count,
                 m->all.over_share, t->over, IMAGE_METRICS_OVER);
        return false;
    }
    return true;
}

#endif
