/* Render settings shared by both renderers: the defaults and one validation. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render_settings.h"

bg_render_settings bg_render_settings_init(void)
{
    bg_render_settings s;
    memset(&s, 0, sizeof s);
    s.max_depth = 5;
    s.min_weight = 1.0 / 512.0;
    s.encoding = BG_ENCODING_SRGB;
    return s;
}

bg_status bgi_render_settings_check(const bg_render_settings *s, const char *where, char *message, size_t size)
{
    const double *b = s->background;
    if (!isfinite(b[0]) || !isfinite(b[1]) || !isfinite(b[2]) || b[0] < 0.0 || b[1] < 0.0 || b[2] < 0.0)
        snprintf(message, size, "%s: settings.background must be finite and >= 0", where);
    else if (s->max_depth < 0 || s->max_depth > BG_MAX_DEPTH)
        snprintf(message, size, "%s: settings.max_depth %d is not in 0..%d", where, s->max_depth, BG_MAX_DEPTH);
    else if (!isfinite(s->min_weight) || s->min_weight < 0.0)
        snprintf(message, size, "%s: settings.min_weight must be finite and >= 0", where);
    else if (s->integrator != BG_INTEGRATOR_WHITTED && s->integrator != BG_INTEGRATOR_PATH)
        snprintf(message, size, "%s: settings.integrator %d is unknown", where, (int)s->integrator);
    else if (s->encoding != BG_ENCODING_SRGB && s->encoding != BG_ENCODING_LINEAR)
        snprintf(message, size, "%s: settings.encoding %d is unknown", where, (int)s->encoding);
    else if (s->threads < 0 || s->threads > BG_MAX_THREADS)
        snprintf(message, size, "%s: settings.threads %d is not in 0..%d", where, s->threads, BG_MAX_THREADS);
    else if (!isfinite(s->dmax) || s->dmax < 0.0)
        snprintf(message, size, "%s: settings.dmax must be finite and >= 0 (0 = automatic)", where);
    else if (s->gpu_disable_skips & ~(unsigned)BG_SKIP_ALL)
        snprintf(message, size, "%s: settings.gpu_disable_skips has unknown bits 0x%x", where,
                 s->gpu_disable_skips & ~(unsigned)BG_SKIP_ALL);
    else if (s->gpu_plan != BG_PLAN_AUTO && s->gpu_plan != BG_PLAN_FUSED && s->gpu_plan != BG_PLAN_MULTIPASS &&
             s->gpu_plan != BG_PLAN_FUSED_TREE)
        snprintf(message, size, "%s: settings.gpu_plan %d is unknown", where, (int)s->gpu_plan);
    else if (s->primary != BG_PRIMARY_AUTO && s->primary != BG_PRIMARY_WALK && s->primary != BG_PRIMARY_RASTER)
        snprintf(message, size, "%s: settings.primary %d is unknown", where, (int)s->primary);
    else if (!isfinite(s->gpu_memory_budget) || (s->gpu_memory_budget != 0.0 && s->gpu_memory_budget < 1048576.0))
        snprintf(message, size, "%s: settings.gpu_memory_budget = %g must be 0 (1 GiB) or a finite number of bytes "
                 ">= 1 MiB", where, s->gpu_memory_budget);
    else
        return BG_OK;
    return BG_ERR_INVALID_ARGUMENT;
}
