/* Test helper: a MACS context whose GL loader is wrapped so that texture and renderbuffer
 * allocations report GL_OUT_OF_MEMORY through the next glGetError, as a full GPU would. A real huge
 * allocation is unreliable under llvmpipe, ASan and valgrind; this is not. One such context at a
 * time (the wrapper's state is the test program's). */
#ifndef UTIL_OOM_H
#define UTIL_OOM_H

#include "macs.h"

/* Creates the wrapped context on a headless context; fails the test on error. */
macs_context *util_oom_context(macs_headless *headless);
/* From now on the next count allocations fail (count < 0: every one); resets util_oom_injected. */
void util_oom_start(int count);
/* Stops failing allocations and drops a failure not yet reported; keeps util_oom_injected. */
void util_oom_stop(void);
/* How many allocations were made to fail since the last util_oom_start. */
int util_oom_injected(void);

#endif
