/* The progress bar of `betelgeuse render` on stderr: drawn only when stderr is a terminal (and not
 * --quiet), at most ten times a second, with the elapsed and the estimated remaining time. */
#ifndef CLI_PROGRESS_H
#define CLI_PROGRESS_H

#include <stdbool.h>

typedef struct cli_progress {
    bool shown;        /* stderr is a terminal and the bar is wanted */
    double start;      /* seconds, monotonic */
    double last_drawn; /* when the bar was last drawn */
    double fraction;   /* the last fraction reported */
    int tile, tiles;   /* the part being rendered, for the label (tiles 1: none) */
} cli_progress;

/* Starts the clock; the bar is shown when wanted and stderr is a terminal. */
void cli_progress_start(cli_progress *p, bool wanted);
/* Reports the fraction done of the whole job (0 .. 1); redraws when due. */
void cli_progress_update(cli_progress *p, double fraction);
/* Draws the final state and ends the line (nothing when the bar is not shown). */
void cli_progress_finish(cli_progress *p, bool done);
/* Seconds on a monotonic clock. */
double cli_now(void);

#endif
