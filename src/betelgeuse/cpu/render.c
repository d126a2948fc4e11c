/* The CPU reference renderer: argument checks, rows handed to worker threads, samples averaged,
 * output encoding, progress and cancelling (docs/shading.md sections 1 and 10). Each pixel depends
 * only on the scene, the settings and its position in the frame, so the image is the same for every
 * thread count and a crop window is the same rectangle of the full frame bit for bit. */
#include <pthread.h>
#include <string.h>
#include <unistd.h>

#include "cpu_internal.h"
#include "../common/render_args.h"
#include "../common/render_settings.h"
#include "../common/render_view.h"
#include "../common/encoding.h"

#define MAX_THREADS BG_MAX_THREADS

typedef struct job {
    const bg_scene_state *state;
    const bg_render_settings *settings;
    const bgi_render_view *view;
    const bg_image *image;
    size_t stride;
    pthread_mutex_t lock;
    pthread_cond_t row_finished; /* signalled after each row, for the caller's thread */
    int next_row;
    int rows_done;
    int rows_reported; /* rows told to progress so far, by the caller's thread */
    bool cancelled;    /* set under lock by the caller's thread when progress asks to stop */
} job;

void bgi_cpu_render_texel(const bg_scene_state *state, const bg_render_settings *settings,
                         const bgi_render_view *view, int x, int y, bg_pixel_format format, void *texel)
{
    double rgb[3];
    int first = view->sample_first, count = view->sample_count;
    for (int k = first; k < first + count; k++) {
        /* The k-th sample taken (docs/shading.md 1.1): its place in the pixel and its points are
         * sample s's, so that the first k of any count spread over the pixel. */
        int s = bgi_sample_order(view->samples, k);
        double px, py, o[3], d[3], one[3];
        bgi_sample_position(view->samples, s, &px, &py);
        bgi_cpu_frame_ray(&state->camera, view->frame_width, view->frame_height, (double)(view->x0 + x) + px,
                          (double)(view->y0 + y) + py, o, d);
        /* The sample points cost a few hashes a sample: only a scene or an integrator that spends
         * them makes them. */
        bgi_sample_point sample = {0};
        if (state->distribution || settings->integrator == BG_INTEGRATOR_PATH)
            bgi_sample_point_make(view->x0 + x, view->y0 + y, s, view->samples, &sample);
        if (state->camera.camera.aperture_radius > 0.0)
            bgi_cpu_lens_ray(&state->camera, &sample, o, d);
        bgi_cpu_shade_ray(state, settings, &sample, o, d, one);
        /* Summed in the order taken, then divided once (docs/shading.md 1.1); one sample is kept as
         * it is, so that samples 1 is today's image bit for bit (0 + -0 would be +0). */
        for (int i = 0; i < 3; i++)
            rgb[i] = k == first ? one[i] : rgb[i] + one[i];
    }
    if (count > 1)
        for (int i = 0; i < 3; i++)
            rgb[i] /= count;
    if (format == BG_PIXEL_RGBA32F) {
        float px[4] = {(float)rgb[0], (float)rgb[1], (float)rgb[2], 1.0f};
        memcpy(texel, px, sizeof px);
    } else {
        unsigned char *px = texel;
        for (int i = 0; i < 3; i++)
            px[i] = bgi_encode_channel(rgb[i], settings->encoding);
        px[3] = 255;
    }
}

void bgi_cpu_render_pixel(const bg_scene_state *state, const bg_render_settings *settings,
                         const bgi_render_view *view, const bg_image *image, size_t stride, int x, int y)
{
    unsigned char *row = (unsigned char *)image->pixels + (size_t)y * stride;
    size_t size = image->format == BG_PIXEL_RGBA32F ? 16 : 4;
    bgi_cpu_render_texel(state, settings, view, x, y, image->format, row + (size_t)x * size);
}

static void render_row(const job *jb, int y)
{
    for (int x = 0; x < jb->image->width; x++)
        bgi_cpu_render_pixel(jb->state, jb->settings, jb->view, jb->image, jb->stride, x, y);
}

/* Tells progress of every row finished since the last report, one call per row, so that what
 * progress hears does not depend on which thread rendered which row; the last row is told as the
 * final 1 after every thread has finished. Only the caller's thread calls it, with the lock held,
 * which it releases around the callback. */
static void report_finished_rows(job *jb)
{
    while (!jb->cancelled && jb->rows_reported < jb->rows_done && jb->rows_reported + 1 < jb->image->height) {
        int row = ++jb->rows_reported;
        pthread_mutex_unlock(&jb->lock);
        bool go_on = bgi_render_progress(jb->settings, (double)row / jb->image->height);
        pthread_mutex_lock(&jb->lock);
        if (!go_on)
            jb->cancelled = true;
    }
}

/* Takes rows from the shared counter until none is left or the render is cancelled (C99 has no
 * atomics, hence the mutex). The caller's thread (reporter) tells progress after each of its rows,
 * then waits for the rows the other threads still render and tells those too; rows_done only grows,
 * so the fractions it reports never decrease. */
static void work(job *jb, bool reporter)
{
    for (;;) {
        pthread_mutex_lock(&jb->lock);
        int y = jb->next_row;
        bool take = y < jb->image->height && !jb->cancelled;
        if (take)
            jb->next_row = y + 1;
        pthread_mutex_unlock(&jb->lock);
        if (!take)
            break;
        render_row(jb, y);
        pthread_mutex_lock(&jb->lock);
        jb->rows_done++;
        pthread_cond_signal(&jb->row_finished);
        if (reporter)
            report_finished_rows(jb);
        pthread_mutex_unlock(&jb->lock);
    }
    if (!reporter)
        return;
    pthread_mutex_lock(&jb->lock);
    for (;;) {
        report_finished_rows(jb);
        if (jb->cancelled || jb->rows_done == jb->next_row)
            break;
        pthread_cond_wait(&jb->row_finished, &jb->lock);
    }
    pthread_mutex_unlock(&jb->lock);
}

static void *worker(void *arg)
{
    work(arg, false);
    return NULL;
}

bg_status bg_render_cpu(bg_scene *scene, const bg_render_settings *settings, bg_image *image)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    char message[256];
    size_t stride = 0;
    bgi_render_view view;
    bg_status st = bgi_render_args_check("bg_render_cpu", settings, image, &stride, &view, message, sizeof message);
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

    if (!bgi_render_progress(settings, 0.0))
        return bgi_scene_fail(scene, BG_ERR_CANCELLED, "bg_render_cpu: cancelled by settings.progress before the "
                              "first row; the image is untouched");
    job jb;
    jb.state = state;
    jb.settings = settings;
    jb.view = &view;
    jb.image = image;
    jb.stride = stride;
    jb.next_row = 0;
    jb.rows_done = 0;
    jb.rows_reported = 0;
    jb.cancelled = false;
    if (pthread_mutex_init(&jb.lock, NULL) != 0)
        return bgi_scene_fail(scene, BG_ERR_THREAD, "bg_render_cpu: pthread_mutex_init failed");
    if (pthread_cond_init(&jb.row_finished, NULL) != 0) {
        pthread_mutex_destroy(&jb.lock);
        return bgi_scene_fail(scene, BG_ERR_THREAD, "bg_render_cpu: pthread_cond_init failed");
    }

    /* The calling thread is worker 0; if a thread cannot be started the others (at least the caller)
     * take its rows, so the image is always complete. */
    pthread_t pool[MAX_THREADS];
    int started = 0;
    for (int i = 1; i < threads; i++) {
        if (pthread_create(&pool[started], NULL, worker, &jb) != 0)
            break;
        started++;
    }
    work(&jb, true);
    for (int i = 0; i < started; i++)
        pthread_join(pool[i], NULL);
    pthread_cond_destroy(&jb.row_finished);
    pthread_mutex_destroy(&jb.lock);
    if (jb.cancelled)
        return bgi_scene_fail(scene, BG_ERR_CANCELLED, "bg_render_cpu: cancelled by settings.progress after %d of "
                              "%d rows; each row is complete or untouched", jb.rows_done, image->height);
    bgi_render_rows_done(settings, 0, image->height);
    bgi_render_progress(settings, 1.0);
    return BG_OK;
}
