/* BENCH_CASES: which cases of a bench program run, so that one case can be timed again without the
 * rest of its program (e.g. `BENCH_CASES=many_spheres64 build/release/bench/bench_embree out`).
 *
 * The variable holds case names separated by commas; unset or empty, every case runs. A name picks
 * a case at every image size; "name@size" picks it at one size (many_spheres64@1024). Each program
 * says its names in its usage comment. A name that no case of the program matched is an error
 * (bench_select_check, which then lists the program's names), so that a typo does not pass as an
 * empty run. */
#ifndef BENCH_SELECT_H
#define BENCH_SELECT_H

#include <stdbool.h>
#include <stdio.h>

/* True when the case `name` at image side `size` (0: the case has no size) is to run. Every call
 * counts as a match for the names it accepts, whatever the caller then does. */
bool bench_selected(const char *name, int size);

/* True when BENCH_CASES names some cases (not every case runs). */
bool bench_select_active(void);

/* After a program has asked about all its cases: false, with the unknown names and the program's
 * `known` names (one string, for the message) on stderr, when a name of BENCH_CASES matched nothing. */
bool bench_select_check(const char *program, const char *known);

/* "BENCH_CASES=...: only these cases" for a table's header, nothing when every case runs. */
void bench_select_print(FILE *f);

#endif
