/* What a viewer session measured (view_report.c): the frame counts a --script run prints, and the
 * --benchmark table (frame-time percentiles while moving, the resolution chosen, the time to N
 * samples at rest). */
#ifndef CLI_VIEW_REPORT_H
#define CLI_VIEW_REPORT_H

#include <stdbool.h>

#include "view.h"

/* Keeps one moving frame's time and divisor; false when out of memory (the frame is not kept). */
bool view_times_add(view_times *t, double ms, int divisor);
void view_times_free(view_times *t);

/* The counts, on stdout. */
void view_report_frames(const viewer *v);

/* The --benchmark table, on stdout. */
void view_report_benchmark(const viewer *v);

/* The script --benchmark runs: an orbit across the frame of width x height, one pointer move a
 * frame for moving frames, then the rest to N samples. */
void view_benchmark_script(char *text, size_t size, int width, int height);

#endif
