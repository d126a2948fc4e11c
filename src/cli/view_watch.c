/* Watching the scene's files (view_watch.h): a stat per file each time the viewer looks, a few
 * times a second while it waits, which costs microseconds; inotify would save them but not work on
 * every file system the scene may be on (NFS), nor on the other systems GLFW runs on. */
#include "view_watch.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static view_watched note(const char *path)
{
    view_watched f;
    memset(&f, 0, sizeof f);
    struct stat st;
    if (stat(path, &st) == 0) {
        f.exists = true;
        f.inode = st.st_ino;
        f.size = st.st_size;
        f.modified = st.st_mtim;
    }
    return f;
}

static bool same(const view_watched *a, const view_watched *b)
{
    return a->exists == b->exists && a->inode == b->inode && a->size == b->size &&
           a->modified.tv_sec == b->modified.tv_sec && a->modified.tv_nsec == b->modified.tv_nsec;
}

bool view_watch_set(view_watch *w, const cli_inputs *inputs)
{
    view_watched *files = calloc(inputs->count ? inputs->count : 1, sizeof *files);
    if (!files)
        return false;
    size_t n = 0;
    for (; n < inputs->count; n++) {
        files[n] = note(inputs->items[n].path);
        files[n].path = strdup(inputs->items[n].path);
        if (!files[n].path)
            break;
    }
    if (n < inputs->count) {
        for (size_t i = 0; i < n; i++)
            free(files[i].path);
        free(files);
        return false;
    }
    view_watch_free(w);
    w->files = files;
    w->count = n;
    return true;
}

bool view_watch_changed(view_watch *w)
{
    bool changed = false;
    for (size_t i = 0; i < w->count; i++) {
        view_watched now = note(w->files[i].path);
        now.path = w->files[i].path;
        if (!same(&now, &w->files[i]))
            changed = true;
        w->files[i] = now;
    }
    return changed;
}

void view_watch_free(view_watch *w)
{
    for (size_t i = 0; i < w->count; i++)
        free(w->files[i].path);
    free(w->files);
    w->files = NULL;
    w->count = 0;
}
