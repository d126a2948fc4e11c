/* Frame counts and the benchmark table (view_report.h). */
#include "view_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view_resolution.h"

/* The benchmark's orbit: this many moving frames. */
enum { BENCHMARK_MOVES = 60 };

bool view_times_add(view_times *t, double ms, int divisor)
{
    if (t->count == t->capacity) {
        int capacity = t->capacity ? 2 * t->capacity : 64;
        double *ms_grown = realloc(t->ms, (size_t)capacity * sizeof *ms_grown);
        if (!ms_grown)
            return false;
        t->ms = ms_grown;
        int *div_grown = realloc(t->divisors, (size_t)capacity * sizeof *div_grown);
        if (!div_grown)
            return false;
        t->divisors = div_grown;
        t->capacity = capacity;
    }
    t->ms[t->count] = ms;
    t->divisors[t->count] = divisor;
    t->count++;
    return true;
}

void view_times_free(view_times *t)
{
    free(t->ms);
    free(t->divisors);
    memset(t, 0, sizeof *t);
}

void view_report_frames(const viewer *v)
{
    printf("frames drawn: %ld moving, %ld at rest; frames drawn at rest after %d samples: %ld\n", v->frames_moving,
           v->frames_rest, v->samples, v->frames_rest_after_n);
    printf("reloads: %d, failed: %d\n", v->reloads, v->reload_errors);
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The nearest-rank percentile of n sorted values. */
static double percentile(const double *sorted, int n, double p)
{
    int rank = (int)ceil(p / 100.0 * n);
    return sorted[rank < 1 ? 0 : rank - 1];
}

void view_report_benchmark(const viewer *v)
{
    const view_times *t = &v->moving_times;
    printf("scene        %s, %dx%d, %d samples at rest, frame-time target %g ms\n", v->options->scene, v->width,
           v->height, v->samples, v->options->frame_ms > 0 ? v->options->frame_ms : 33.0);
    if (t->count > 0) {
        double *sorted = malloc((size_t)t->count * sizeof *sorted);
        if (sorted) {
            memcpy(sorted, t->ms, (size_t)t->count * sizeof *sorted);
            qsort(sorted, (size_t)t->count, sizeof *sorted, by_value);
            printf("moving       %d frames: p50 %.1f ms, p90 %.1f ms, p99 %.1f ms\n", t->count,
                   percentile(sorted, t->count, 50), percentile(sorted, t->count, 90),
                   percentile(sorted, t->count, 99));
            free(sorted);
        }
        int at[VIEW_MAX_DIVISOR + 1] = {0};
        for (int i = 0; i < t->count; i++)
            at[t->divisors[i]]++;
        printf("scale        ");
        for (int d = 1; d <= VIEW_MAX_DIVISOR; d++)
            printf("1/%d: %d frames%s", d, at[d], d < VIEW_MAX_DIVISOR ? ", " : "");
        int last = t->divisors[t->count - 1];
        printf("; last 1/%d (%dx%d)\n", last, view_resolution_side(v->width, last), view_resolution_side(v->height, last));
    }
    if (v->rest_reached > 0)
        printf("at rest      %d samples in %.2f s\n", v->samples, v->rest_reached - v->rest_started);
    else
        printf("at rest      %d samples not reached\n", v->samples);
}

void view_benchmark_script(char *text, size_t size, int width, int height)
{
    snprintf(text, size, "drag left %d %d %d %d %d\nwait-rest\nquit\n", width / 5, height / 2, width - width / 5,
             height / 2, BENCHMARK_MOVES);
}
