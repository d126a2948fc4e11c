/* Shared benchmark plumbing: see bench_util.h. */
#include "bench_util.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "scenes/scenes.h"

double bench_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

bench_times bench_times_of(double *times, int n)
{
    bench_times t = {n, 0.0, 0.0, 0.0};
    if (n < 1)
        return t;
    qsort(times, (size_t)n, sizeof *times, compare_double);
    t.median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
    t.min = times[0];
    t.max = times[n - 1];
    return t;
}

bool bench_gpu_open(bench_gpu *gpu)
{
    memset(gpu, 0, sizeof *gpu);
    const char *b = getenv("MACS_TEST_BACKEND");
    macs_headless_desc hd;
    memset(&hd, 0, sizeof hd);
    hd.backend = !b                       ? MACS_HEADLESS_DEFAULT
                 : strcmp(b, "egl") == 0    ? MACS_HEADLESS_EGL
                 : strcmp(b, "device") == 0 ? MACS_HEADLESS_EGL_DEVICE
                                            : MACS_HEADLESS_DEFAULT;
    char message[512];
    if (macs_headless_create(&hd, &gpu->headless, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "headless GL context: %s\n", message);
        return false;
    }
    macs_context_desc cd;
    memset(&cd, 0, sizeof cd);
    cd.get_proc_address = macs_headless_get_proc_address(gpu->headless);
    cd.get_proc_address_user = macs_headless_proc_user(gpu->headless);
    /* Float depth is allowed so that a renderer asking for it (the depth trade-off) can have it. */
    cd.allow_float_depth = true;
    if (macs_context_create(&cd, &gpu->context, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "MACS context: %s\n", message);
        bench_gpu_close(gpu);
        return false;
    }
    macs_gl_info info;
    macs_context_get_gl_info(gpu->context, &info);
    snprintf(gpu->renderer_name, sizeof gpu->renderer_name, "%s", info.renderer ? info.renderer : "?");
    bg_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    gpu->renderer = bench_gpu_renderer(gpu, rd);
    if (!gpu->renderer) {
        bench_gpu_close(gpu);
        return false;
    }
    return true;
}

void bench_gpu_close(bench_gpu *gpu)
{
    bg_renderer_destroy(gpu->renderer);
    macs_context_destroy(gpu->context);
    macs_headless_destroy(gpu->headless);
    memset(gpu, 0, sizeof *gpu);
}

bg_renderer *bench_gpu_renderer(bench_gpu *gpu, bg_renderer_desc desc)
{
    desc.context = gpu->context;
    bg_renderer *r = NULL;
    char message[512];
    bg_status st = bg_renderer_create(&desc, &r, message, sizeof message);
    if (st != BG_OK) {
        fprintf(stderr, "renderer: %s: %s\n", bg_status_string(st), message);
        return NULL;
    }
    return r;
}

bool bench_image_alloc(bg_image *image, int width, int height, bg_pixel_format format)
{
    size_t texel = format == BG_PIXEL_RGBA32F ? 16 : 4;
    memset(image, 0, sizeof *image);
    image->pixels = calloc((size_t)width * (size_t)height, texel);
    if (!image->pixels) {
        fprintf(stderr, "out of memory for a %dx%d image\n", width, height);
        return false;
    }
    image->width = width;
    image->height = height;
    image->format = format;
    return true;
}

void bench_image_free(bg_image *image)
{
    free(image->pixels);
    memset(image, 0, sizeof *image);
}

bg_scene *bench_scene(int id, const struct scene_params *params)
{
    bg_scene *scene = NULL;
    if (bg_scene_create(NULL, &scene) != BG_OK) {
        fprintf(stderr, "cannot create a scene\n");
        return NULL;
    }
    if (scenes_build_ex((scene_id)id, params, scene) != BG_OK) {
        fprintf(stderr, "cannot build %s: %s\n", scenes_name((scene_id)id), bg_scene_error_message(scene));
        bg_scene_destroy(scene);
        return NULL;
    }
    return scene;
}

const char *bench_out_dir(int argc, char **argv)
{
    return argc > 1 ? argv[1] : "bench/out";
}

FILE *bench_csv_open(const char *dir, const char *name, const char *header)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "cannot create %s: %s\n", dir, strerror(errno));
        return NULL;
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "cannot write %s: %s\n", path, strerror(errno));
        return NULL;
    }
    fprintf(f, "%s\n", header);
    return f;
}

bool bench_quick(void)
{
    const char *q = getenv("QUICK");
    return q && *q && strcmp(q, "0") != 0;
}

void bench_progress(const char *format, ...)
{
    static double start = -1.0;
    double now = bench_now_ms();
    if (start < 0.0)
        start = now;
    fprintf(stderr, "[%6.1f s] ", (now - start) * 1e-3);
    va_list ap;
    va_start(ap, format);
    vfprintf(stderr, format, ap);
    va_end(ap);
    fputc('\n', stderr);
}
