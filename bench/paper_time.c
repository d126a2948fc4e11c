/* Times the GPU renderer (MACS on a headless context) and the CPU reference side by side on the
 * paper's two scenes at 512x512 and 1024x1024, and reports the GPU image's error against the CPU one.
 *
 * Usage: paper_time [runs [threads]]
 *   runs     timed renders per case and renderer, default 5 (after one untimed warm-up render each)
 *   threads  CPU renderer threads, default 0 (the online cores)
 * Per case, after one untimed warm-up render each: `runs` GPU renders back to back, then `runs` CPU
 * renders, then `runs` GPU renders each followed by a CPU render (gpu_alt: the GPU frame after a CPU
 * frame, with llvmpipe's threads and caches cold). Medians, minima and the ratio of the back-to-back
 * medians are printed, one line per case. GPU times are wall times of bg_render_gpu including the
 * read-back into the caller's RGBA8 image. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "betelgeuse.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

int main(int argc, char **argv)
{
    int runs = argc > 1 ? atoi(argv[1]) : 5;
    int threads = argc > 2 ? atoi(argv[2]) : 0;
    if (runs < 1 || runs > 1000 || threads < 0 || threads > 256) {
        fprintf(stderr, "usage: paper_time [runs 1..1000 [threads 0..256]]\n");
        return 2;
    }
    char message[512];
    macs_headless *gl = NULL;
    macs_context *ctx = NULL;
    bg_renderer *renderer = NULL;
    if (macs_headless_create(NULL, &gl, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "paper_time: %s\n", message);
        return 1;
    }
    macs_context_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.get_proc_address = macs_headless_get_proc_address(gl);
    cd.get_proc_address_user = macs_headless_proc_user(gl);
    if (macs_context_create(&cd, &ctx, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "paper_time: %s\n", message);
        return 1;
    }
    bg_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.context = ctx;
    if (bg_renderer_create(&rd, &renderer) != BG_OK) {
        fprintf(stderr, "paper_time: cannot create the renderer\n");
        return 1;
    }
    macs_gl_info info;
    macs_context_gl_info(ctx, &info);
    const char *lp = getenv("LP_NUM_THREADS");
    printf("GL renderer: %s; LP_NUM_THREADS=%s; CPU threads %d (0 = online cores); runs %d\n",
           info.renderer ? info.renderer : "?", lp ? lp : "(unset)", threads, runs);
    printf("%-20s %-10s %9s %9s %9s %9s %7s %9s | %s\n", "scene", "size", "gpu_med", "gpu_min", "cpu_med", "cpu_min",
           "cpu/gpu", "gpu_alt", "GPU error against the CPU reference");

    const scene_id ids[2] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW};
    const int sizes[2] = {512, 1024};
    double *tg = malloc(sizeof(double) * (size_t)runs), *tc = malloc(sizeof(double) * (size_t)runs);
    double *ta = malloc(sizeof(double) * (size_t)runs);
    unsigned char *pg = malloc((size_t)1024 * 1024 * 4), *pc = malloc((size_t)1024 * 1024 * 4);
    if (!tg || !tc || !ta || !pg || !pc) {
        fprintf(stderr, "paper_time: out of memory\n");
        return 1;
    }
    int status = 0;
    for (int s = 0; s < 2 && !status; s++) {
        bg_scene *scene = NULL;
        if (bg_scene_create(NULL, &scene) != BG_OK || scenes_build(ids[s], scene) != BG_OK) {
            fprintf(stderr, "paper_time: cannot build %s\n", scenes_name(ids[s]));
            return 1;
        }
        for (int z = 0; z < 2 && !status; z++) {
            bg_image gimg = {sizes[z], sizes[z], BG_PIXEL_RGBA8, 0, pg};
            bg_image cimg = {sizes[z], sizes[z], BG_PIXEL_RGBA8, 0, pc};
            bg_render_settings settings = bg_render_settings_init();
            settings.threads = threads;
            /* Warm-up: shader compilation and allocation belong to the first frame only. */
            if (bg_render_gpu(renderer, scene, &settings, &gimg) != BG_OK ||
                bg_render_cpu(scene, &settings, &cimg) != BG_OK) {
                fprintf(stderr, "paper_time: %s\n", bg_renderer_error_message(renderer));
                status = 1;
                break;
            }
            /* Back to back: the steady state of a program rendering frame after frame. */
            for (int r = 0; r < runs && !status; r++) {
                double t0 = now_ms();
                status |= bg_render_gpu(renderer, scene, &settings, &gimg) != BG_OK;
                tg[r] = now_ms() - t0;
            }
            for (int r = 0; r < runs && !status; r++) {
                double t0 = now_ms();
                status |= bg_render_cpu(scene, &settings, &cimg) != BG_OK;
                tc[r] = now_ms() - t0;
            }
            /* Alternating with CPU renders: llvmpipe's threads and caches start cold every frame. */
            for (int r = 0; r < runs && !status; r++) {
                double t0 = now_ms();
                status |= bg_render_gpu(renderer, scene, &settings, &gimg) != BG_OK;
                ta[r] = now_ms() - t0;
                status |= bg_render_cpu(scene, &settings, &cimg) != BG_OK;
            }
            if (status) {
                fprintf(stderr, "paper_time: render failed: %s\n", bg_renderer_error_message(renderer));
                break;
            }
            image_metrics m;
            image_metrics_compare(&cimg, &gimg, 24, &m);
            char line[512];
            image_metrics_format(&m, line, sizeof line);
            double gm = median(tg, runs), cm = median(tc, runs), am = median(ta, runs);
            char size[32];
            snprintf(size, sizeof size, "%dx%d", sizes[z], sizes[z]);
            printf("%-20s %-10s %9.1f %9.1f %9.1f %9.1f %7.2f %9.1f | %s\n", scenes_name(ids[s]), size, gm, tg[0], cm,
                   tc[0], cm / gm, am, line);
            fflush(stdout);
        }
        bg_scene_destroy(scene);
    }
    free(tg);
    free(tc);
    free(ta);
    free(pg);
    free(pc);
    bg_renderer_destroy(renderer);
    macs_context_destroy(ctx);
    macs_headless_destroy(gl);
    return status;
}
