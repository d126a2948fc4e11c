/* A progressive preview's error (docs/shading.md 1.1 and 1.2): the image of the first k of a pixel's
 * n = 64 samples, as bg_render_gpu_accumulate(first 0, count k) and the CPU's sample_first/count
 * take them, against the image of all 64, for k = 1, 2, 4, 8, on scenes with edges and distribution
 * effects. The preview is biased when the first k samples sit in one part of the pixel; the order in
 * which samples are taken (bgi_sample_order) decides where they sit.
 *
 * Usage: bench_progressive [out_dir]   (default bench/out; a 96 x 96 image, QUICK=1 for 48 x 48)
 * The CPU reference renders every pixel single-threaded through bgi_cpu_render_texel with a view of
 * samples = 64 and sample_first = 0, sample_count = k (the preview), then with count 64 (the image);
 * both are RGBA8 with the sRGB encoding, what a viewer shows. Each row: the RMSE of the preview
 * against the image over all pixels and channels RGB, in 8-bit steps (0..255), and the share of
 * pixels with a channel off by more than 8 steps. Prints a table and writes out_dir/progressive.csv
 * (scene, k, rmse, over_share). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "betelgeuse/cpu/cpu_internal.h"
#include "lib/bench_util.h"
#include "lib/distribution_scenes.h"
#include "scenes/scenes.h"

#define SAMPLES 64
#define DEFAULT_SIZE 96
#define QUICK_SIZE 48

typedef struct progressive_case {
    const char *name;
    bg_status (*build)(bg_scene *scene, bool effect); /* NULL: the shared scene `shared` */
    scene_id shared;
} progressive_case;

static const progressive_case cases[] = {
    {"area_lights", distribution_area_lights, SCENE_COUNT},
    {"depth_of_field", distribution_depth_of_field, SCENE_COUNT},
    {"glossy", distribution_glossy, SCENE_COUNT},
    {"all_primitives", NULL, SCENE_ALL_PRIMITIVES},
};
#define CASE_COUNT (int)(sizeof cases / sizeof cases[0])

static const int previews[] = {1, 2, 4, 8};
#define PREVIEW_COUNT (int)(sizeof previews / sizeof previews[0])

static bool build_case(const progressive_case *c, bg_scene *scene)
{
    bg_status st = c->build ? c->build(scene, true) : scenes_build(c->shared, scene);
    if (st == BG_OK && c->build)
        st = bg_scene_commit(scene);
    if (st != BG_OK)
        fprintf(stderr, "%s: %s\n", c->name, bg_scene_error_message(scene));
    return st == BG_OK;
}

/* Samples [0, count) of n of every pixel of a size x size frame, RGBA8 sRGB. */
static void render(const bg_scene_state *state, const bg_render_settings *settings, int size, int count,
                   unsigned char *pixels)
{
    bgi_render_view view = {size, size, 0, 0, size, size, SAMPLES, 0, count};
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++)
            bgi_cpu_render_texel(state, settings, &view, x, y, BG_PIXEL_RGBA8, pixels + ((size_t)y * size + x) * 4);
}

int main(int argc, char **argv)
{
    int size = bench_quick() ? QUICK_SIZE : DEFAULT_SIZE;
    FILE *csv = bench_csv_open(bench_out_dir(argc, argv), "progressive.csv", "scene,k,rmse,over_share");
    if (!csv)
        return 1;
    size_t bytes = (size_t)size * size * 4;
    unsigned char *full = malloc(bytes), *preview = malloc(bytes);
    if (!full || !preview) {
        fprintf(stderr, "bench_progressive: out of memory\n");
        fclose(csv);
        return 1;
    }
    bg_render_settings settings = bg_render_settings_init();
    settings.samples = SAMPLES;
    printf("Preview of k of %d samples against all %d, CPU reference, %dx%d, RGBA8 sRGB\n", SAMPLES, SAMPLES,
           size, size);
    printf("%-16s", "scene");
    for (int i = 0; i < PREVIEW_COUNT; i++)
        printf("   k=%d rmse (>8)", previews[i]);
    printf("\n");
    int status = 0;
    for (int c = 0; c < CASE_COUNT; c++) {
        bg_scene *scene = NULL;
        if (bg_scene_create(NULL, &scene) != BG_OK || !build_case(&cases[c], scene)) {
            bg_scene_destroy(scene);
            status = 1;
            continue;
        }
        const bg_scene_state *state = bgi_scene_committed(scene);
        render(state, &settings, size, SAMPLES, full);
        printf("%-16s", cases[c].name);
        for (int i = 0; i < PREVIEW_COUNT; i++) {
            render(state, &settings, size, previews[i], preview);
            double sq = 0.0;
            long over = 0;
            for (size_t p = 0; p < (size_t)size * size; p++) {
                bool off = false;
                for (int ch = 0; ch < 3; ch++) {
                    double d = (double)preview[p * 4 + ch] - (double)full[p * 4 + ch];
                    sq += d * d;
                    off = off || fabs(d) > 8.0;
                }
                over += off;
            }
            double rmse = sqrt(sq / ((double)size * size * 3)), share = (double)over / ((double)size * size);
            printf("  %8.2f (%4.1f%%)", rmse, 100.0 * share);
            fprintf(csv, "%s,%d,%.4f,%.5f\n", cases[c].name, previews[i], rmse, share);
        }
        printf("\n");
        fflush(stdout);
        bg_scene_destroy(scene);
    }
    free(full);
    free(preview);
    if (fclose(csv) != 0) {
        fprintf(stderr, "bench_progressive: writing progressive.csv failed\n");
        status = 1;
    }
    return status;
}
