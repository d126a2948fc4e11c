/* Wall time per frame phase, for bg_render_settings.gpu_timing. Both plans time their phases here, so
 * bg_render_stats.phase_ms means the same for each. */
#include <time.h>

#include "shared.h"

double bgi_gpu_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* A phase's time is only its own once the GPU has drained its work, so timing waits at both ends. */
void bgi_gpu_phase_start(bg_renderer *r, bool timing, double *clock)
{
    if (!timing)
        return;
    macs_context_finish(r->ctx);
    *clock = bgi_gpu_now_ms();
}

void bgi_gpu_phase_end(bg_renderer *r, bool timing, double *clock, bg_phase phase)
{
    if (!timing)
        return;
    macs_context_finish(r->ctx);
    double t = bgi_gpu_now_ms();
    r->stats.phase_ms[phase] += t - *clock;
    *clock = t;
}
