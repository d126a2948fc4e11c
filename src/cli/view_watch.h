/* The files a scene was read from, watched for edits (view_watch.c): every path the scene-file
 * library reported reading, with what stat said of it when it was read. An editor that saves by
 * writing a new file and renaming it changes the inode, one that writes in place the time or size;
 * either counts as a change. */
#ifndef CLI_VIEW_WATCH_H
#define CLI_VIEW_WATCH_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>
#include <time.h>

#include "inputs.h"

typedef struct view_watched {
    char *path;
    bool exists;
    ino_t inode;
    off_t size;
    struct timespec modified;
} view_watched;

typedef struct view_watch {
    view_watched *files;
    size_t count;
} view_watch;

/* Replaces the watched files with the paths of inputs, as they are now; false when out of memory
 * (the old list is kept). */
bool view_watch_set(view_watch *w, const cli_inputs *inputs);

/* True when any watched file differs from when it was noted; notes each as it is now, so that one
 * edit is reported once. */
bool view_watch_changed(view_watch *w);

void view_watch_free(view_watch *w);

#endif
