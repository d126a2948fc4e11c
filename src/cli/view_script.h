/* The viewer's --script (view_script.c): timed inputs for tests and benchmarks, one command a line,
 * driving the same input functions as the window's mouse and keys (view_input.h). The language is
 * in docs/command.md ("view --script"); '#' starts a comment. The script ends the session: after
 * its last line the viewer quits as on Esc. */
#ifndef CLI_VIEW_SCRIPT_H
#define CLI_VIEW_SCRIPT_H

#include <stdbool.h>
#include <stddef.h>

#include "view.h"

typedef struct view_script view_script;

/* Reads and checks the whole script from the file at path, or from text (named name in messages)
 * when text is not NULL; false with the reason naming the file and line ("run.txt:3: ..."). */
bool view_script_load(const char *path, const char *text, view_script **out, char *why, size_t why_size);

/* Runs the script's commands that are due at now. Returns the seconds the loop may wait for
 * events before calling again: 0 when a command wants the next frame first (a drag's steps),
 * -1 when the script waits on the viewer (wait-rest, wait-reload), not on the clock. A failed
 * expectation is printed (file, line, what was found) and sets v->exit_code to 1; the script goes on. */
double view_script_run(view_script *s, viewer *v, double now);

/* True after the last command ran. */
bool view_script_done(const view_script *s);

void view_script_free(view_script *s);

#endif
