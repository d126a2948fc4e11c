/* The progress bar (progress.h). */
#include "progress.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

enum { BAR_WIDTH = 32 };

double cli_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void cli_progress_start(cli_progress *p, bool wanted)
{
    p->shown = wanted && isatty(2);
    p->start = cli_now();
    p->last_drawn = -1.0;
    p->fraction = 0.0;
    p->tile = 0;
    p->tiles = 1;
}

/* "m:ss" or "h:mm:ss". */
static void clock_text(double seconds, char *out, size_t size)
{
    /* Clamped to 10^6 hours: an estimate from a tiny fraction can be anything. */
    long s = seconds > 0.0 ? (long)(seconds < 3.6e9 ? seconds + 0.5 : 3.6e9) : 0;
    if (s >= 3600)
        snprintf(out, size, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    else
        snprintf(out, size, "%ld:%02ld", s / 60, s % 60);
}

static void draw(cli_progress *p, double now)
{
    double f = p->fraction < 0.0 ? 0.0 : p->fraction > 1.0 ? 1.0 : p->fraction;
    int filled = (int)(f * BAR_WIDTH + 0.5);
    char bar[BAR_WIDTH + 1];
    for (int i = 0; i < BAR_WIDTH; i++)
        bar[i] = i < filled ? '#' : '.';
    bar[BAR_WIDTH] = '\0';
    double elapsed = now - p->start;
    char spent[32], left[32] = "?";
    clock_text(elapsed, spent, sizeof spent);
    if (f > 0.0)
        clock_text(elapsed * (1.0 - f) / f, left, sizeof left);
    fprintf(stderr, "\r[%s] %5.1f%%  elapsed %s  left %s ", bar, 100.0 * f, spent, left);
    fflush(stderr);
    p->last_drawn = now;
}

void cli_progress_update(cli_progress *p, double fraction)
{
    if (fraction > p->fraction)
        p->fraction = fraction;
    if (!p->shown)
        return;
    double now = cli_now();
    if (p->last_drawn < 0.0 || now - p->last_drawn >= 0.1)
        draw(p, now);
}

void cli_progress_finish(cli_progress *p, bool done)
{
    if (!p->shown)
        return;
    if (done)
        p->fraction = 1.0;
    draw(p, cli_now());
    fputc('\n', stderr);
}
