/* Times the CPU reference renderer on the paper's two scenes at 512x512 and 1024x1024.
 *
 * Usage: cpu_time [runs [threads]]
 *   runs     renders per case, default 5; the median is printed
 *   threads  worker threads, default 0 (the online cores)
 * Prints one line per case: scene, size, median and minimum milliseconds. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "betelgeuse.h"
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

int main(int argc, char **argv)
{
    int runs = argc > 1 ? atoi(argv[1]) : 5;
    int threads = argc > 2 ? atoi(argv[2]) : 0;
    if (runs < 1 || runs > 1000 || threads < 0 || threads > 256) {
        fprintf(stderr, "usage: cpu_time [runs 1..1000 [threads 0..256]]\n");
        return 2;
    }
    const scene_id ids[2] = {SCENE_PAPER_EARTH, SCENE_PAPER_EARTH_SHADOW};
    const int sizes[2] = {512, 1024};
    double *times = malloc(sizeof(double) * (size_t)runs);
    unsigned char *pixels = malloc((size_t)1024 * 1024 * 4);
    if (!times || !pixels) {
        fprintf(stderr, "cpu_time: out of memory\n");
        return 1;
    }
    printf("%-20s %-10s %10s %10s  (runs %d, threads %d)\n", "scene", "size", "median_ms", "min_ms", runs, threads);
    for (int s = 0; s < 2; s++) {
        bg_scene *scene = NULL;
        if (bg_scene_create(NULL, &scene) != BG_OK || scenes_build(ids[s], scene) != BG_OK) {
            fprintf(stderr, "cpu_time: cannot build %s\n", scenes_name(ids[s]));
            return 1;
        }
        for (int z = 0; z < 2; z++) {
            bg_image image = {sizes[z], sizes[z], BG_PIXEL_RGBA8, 0, pixels};
            bg_render_settings settings = bg_render_settings_init();
            settings.threads = threads;
            for (int r = 0; r < runs; r++) {
                double t0 = now_ms();
                if (bg_render_cpu(scene, &settings, &image) != BG_OK) {
                    fprintf(stderr, "cpu_time: %s\n", bg_scene_error_message(scene));
                    return 1;
                }
                times[r] = now_ms() - t0;
            }
            qsort(times, (size_t)runs, sizeof(double), cmp_double);
            double median = runs % 2 ? times[runs / 2] : 0.5 * (times[runs / 2 - 1] + times[runs / 2]);
            char size[32];
            snprintf(size, sizeof size, "%dx%d", sizes[z], sizes[z]);
            printf("%-20s %-10s %10.1f %10.1f\n", scenes_name(ids[s]), size, median, times[0]);
        }
        bg_scene_destroy(scene);
    }
    free(times);
    free(pixels);
    return 0;
}
