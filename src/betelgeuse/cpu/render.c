/* The CPU reference renderer: argument checks, rows handed to worker threads, output encoding
 * (docs/shading.md sections 1 and 10). Each pixel depends only on the scene and its position, so
 * the image is the same for every thread count. */
#include <pthread.h>
#include <string.h>
#include <unistd.h>

#include "cpu_internal.h"
#include "../common/render_args.h"
#include "../common/render_settings.h"
#include "../common/srgb.h"

#define MAX_THREADS BG_MAX_THREADS

uint8_t bgi_cpu_encode_channel(double linear, bg_output_encoding encoding)
{
    double x = linear < 0.0 ? 0.0 : (linear > 1.0 ? 1.0 : linear);
    if (encoding == BG_ENCODING_SRGB)
        x = bgi_linear_to_srgb(x);
    double y = floor(x * 255.0 + 0.5);
    return (uint8_t)(y < 0.0 ? 0.0 : (y > 255.0 ? 255.0 : y));
}

typedef struct job {
    const bg_scene_state *state;
    const bg_render_settings *settings;
    const bg_image *image;
    size_t stride;
    pthread_mutex_t lock;
    int next_row;
} job;

void bgi_cpu_render_texel(const bg_scene_state *state, const bg_render_settings *settings, int width, int height,
                         int x, int y, bg_pixel_format format, void *texel)
{
    double o[3], d[3], rgb[3];
    bgi_cpu_primary_ray(&state->camera, width, height, x, y, o, d);
    bgi_cpu_shade_ray(state, settings, o, d, rgb);
    if (format == BG_PIXEL_RGBA32F) {
        float px[4] = {(float)rgb[0], (float)rgb[1], (float)rgb[2], 1.0f};
        memcpy(texel, px, sizeof px);
    } else {
        unsigned char *px = texel;
        for (int i = 0; i < 3; i++)
            px[i] = bgi_cpu_encode_channel(rgb[i], settings->encoding);
        px[3] = 255;
    }
}

void bgi_cpu_render_pixel(const bg_scene_state *state, const bg_render_settings *settings, const bg_image *image,
                         size_t stride, int x, int y)
{
    unsigned char *row = (unsigned char *)image->pixels + (size_t)y * stride;
    size_t size = image->format == BG_PIXEL_RGBA32F ? 16 : 4;
    bgi_cpu_render_texel(state, settings, image->width, image->height, x, y, image->format, row + (size_t)x * size);
}

static void render_row(const job *jb, int y)
{
    for (int x = 0; x < jb->image->width; x++)
        bgi_cpu_render_pixel(jb->state, jb->settings, jb->image, jb->stride, x, y);
}

/* Takes rows from the shared counter until none is left (C99 has no atomics, hence the mutex). */
static void *worker(void *arg)
{
    job *jb = arg;
    for (;;) {
        pthread_mutex_lock(&jb->lock);
        int y = jb->next_row;
        if (y < jb->image->height)
            jb->next_row = y + 1;
        pthread_mutex_unlock(&jb->lock);
        if (y >= jb->image->height)
            break;
        render_row(jb, y);
    }
    return NULL;
}

bg_status bg_render_cpu(bg_scene *scene, const bg_render_settings *settings, bg_image *image)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    char message[256];
    size_t stride = 0;
    bg_status st = bgi_render_args_check("bg_render_cpu", settings, image, &stride, message, sizeof message);
    if (st != BG_OK)
        return bgi_scene_fail(scene, st, "%s", message);
    const bg_scene_state *state = bgi_scene_committed(scene);
    if (!state)
        return bgi_scene_fail(scene, BG_ERR_NOT_COMMITTED, "bg_render_cpu: the scene was never committed");

    int threads = settings->threads;
    if (threads == 0) {
        long online = sysconf(_SC_NPROCESSORS_ONLN);
        threads = online < 1 ? 1 : (online > MAX_THREADS ? MAX_THREADS : (int)online);
    }
    if (threads > image->height)
        threads = image->height;

    job jb;
    jb.state = state;
    jb.settings = settings;
    jb.image = image;
    jb.stride = stride;
    jb.next_row = 0;
    if (pthread_mutex_init(&jb.lock, NULL) != 0)
        return bgi_scene_fail(scene, BG_ERR_THREAD, "bg_render_cpu: pthread_mutex_init failed");

    /* The calling thread is worker 0; if a thread cannot be started the others (at least the caller)
     * take its rows, so the image is always complete. */
    pthread_t pool[MAX_THREADS];
    int started = 0;
    for (int i = 1; i < threads; i++) {
        if (pthread_create(&pool[started], NULL, worker, &jb) != 0)
            break;
        started++;
    }
    worker(&jb);
    for (int i = 0; i < started; i++)
        pthread_join(pool[i], NULL);
    pthread_mutex_destroy(&jb.lock);
    return BG_OK;
}
