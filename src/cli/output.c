/* Outputs replaced all at once (output.h). rename() within one folder swaps a file in a single
 * step, so a reader sees the old file or the new one, never a part; the temporary is therefore
 * made in the target's own folder, on the same filesystem. */
/* realpath is an X/Open interface, which the build's _POSIX_C_SOURCE alone does not declare. */
#define _XOPEN_SOURCE 700

#include "output.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a plain create gives a new file; mkstemp makes its file 0600, which a shared render folder
 * would not expect. */
static mode_t create_mode = 0644;

static bool fail(char *why, size_t size, const char *format, const char *path, const char *detail)
{
    snprintf(why, size, format, path, detail);
    return false;
}

void cli_output_init(void)
{
    mode_t mask = umask(0);
    umask(mask);
    create_mode = 0666 & ~mask;
}

/* The length of path's folder part, the last '/' included; 0 for a bare name. */
static size_t folder_length(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? (size_t)(slash - path) + 1 : 0;
}

/* What the symbolic link at link points to, as a path from here: a relative destination is
 * relative to the link's own folder. NULL when it cannot be read. */
static char *link_destination(const char *link, size_t length)
{
    char *dest = malloc(length + 1);
    ssize_t n = dest ? readlink(link, dest, length + 1) : -1;
    if (n < 0 || (size_t)n > length) {
        free(dest);
        return NULL;
    }
    dest[n] = '\0';
    size_t folder = folder_length(link);
    if (dest[0] == '/' || folder == 0)
        return dest;
    char *joined = malloc(folder + (size_t)n + 1);
    if (joined) {
        memcpy(joined, link, folder);
        memcpy(joined + folder, dest, (size_t)n + 1);
    }
    free(dest);
    return joined;
}

/* Where the output goes. Writing used to go through a symbolic link into its file (creating it if
 * missing); renaming onto the link would replace the link instead, so links are followed here, as
 * open() follows them, up to its usual limit of hops. NULL with errno set on failure (ELOOP). */
static char *resolve_target(const char *path)
{
    char *at = strdup(path);
    for (int hops = 0; at && hops < 40; hops++) {
        struct stat st;
        if (lstat(at, &st) != 0 || !S_ISLNK(st.st_mode))
            return at;
        char *next = link_destination(at, (size_t)st.st_size);
        if (!next)
            return at;
        free(at);
        at = next;
    }
    free(at);
    errno = ELOOP;
    return NULL;
}

/* "FOLDER/.NAME.XXXXXX" for mkstemp: hidden, and named after its target so that one left behind
 * by a killed process can be told apart. A long name is cut so that the suffix still fits. */
static char *temp_template(const char *target)
{
    size_t folder = folder_length(target);
    size_t base = strlen(target + folder);
    if (base > 200)
        base = 200;
    char *t = malloc(folder + 1 + base + sizeof ".XXXXXX");
    if (!t)
        return NULL;
    memcpy(t, target, folder);
    t[folder] = '.';
    memcpy(t + folder + 1, target + folder, base);
    memcpy(t + folder + 1 + base, ".XXXXXX", sizeof ".XXXXXX");
    return t;
}

/* A device or a FIFO (/dev/null, a pipe to another program) cannot be replaced, only written. */
static bool open_directly(cli_output *out, char *why, size_t size)
{
    out->file = fopen(out->target, "wb");
    if (!out->file)
        return fail(why, size, "%s: cannot open: %s", out->name, strerror(errno));
    return true;
}

/* The new file gets mode: a replaced file's own (a render folder's 0600 outputs stay private),
 * else what a plain create would give. */
static bool open_temporary(cli_output *out, mode_t mode, char *why, size_t size)
{
    out->temp = temp_template(out->target);
    if (!out->temp)
        return fail(why, size, "%s: %s", out->name, "out of memory");
    int fd = mkstemp(out->temp);
    if (fd < 0) {
        int err = errno;
        free(out->temp);
        out->temp = NULL;
        return fail(why, size, "%s: cannot create: %s", out->name, strerror(err));
    }
    if (fchmod(fd, mode) != 0 || !(out->file = fdopen(fd, "wb"))) {
        int err = errno;
        close(fd);
        return fail(why, size, "%s: cannot create: %s", out->name, strerror(err));
    }
    return true;
}

bool cli_output_open(cli_output *out, const char *path, char *why, size_t size)
{
    memset(out, 0, sizeof *out);
    out->name = path;
    const char *base = path + folder_length(path);
    if (*base == '\0' || strcmp(base, ".") == 0 || strcmp(base, "..") == 0)
        return fail(why, size, "%s: %s", path, "names a folder, not a file");
    out->target = resolve_target(path);
    if (!out->target)
        return fail(why, size, "%s: cannot create: %s", path, strerror(errno));
    struct stat st;
    bool exists = stat(out->target, &st) == 0, ok;
    if (exists && S_ISDIR(st.st_mode))
        ok = fail(why, size, "%s: %s", path, "is a directory");
    else if (exists && !S_ISREG(st.st_mode))
        ok = open_directly(out, why, size);
    else
        ok = open_temporary(out, exists ? st.st_mode & 07777 : create_mode, why, size);
    if (!ok)
        cli_output_discard(out);
    return ok;
}

bool cli_output_finish(cli_output *out, char *why, size_t size)
{
    /* A full disk may show only when the data reaches it: flush and sync before calling it done. */
    bool ok = fflush(out->file) == 0 && !ferror(out->file) && (!out->temp || fsync(fileno(out->file)) == 0);
    int err = errno;
    if (fclose(out->file) != 0 && ok) {
        ok = false;
        err = errno;
    }
    out->file = NULL;
    if (!ok)
        return fail(why, size, "%s: cannot write: %s", out->name, strerror(err));
    return true;
}

bool cli_outputs_commit(cli_output *outs, size_t count, char *why, size_t size)
{
    for (size_t i = 0; i < count; i++) {
        if (!outs[i].temp)
            continue;
        if (rename(outs[i].temp, outs[i].target) != 0)
            return fail(why, size, "%s: cannot put in place: %s", outs[i].name, strerror(errno));
        free(outs[i].temp);
        outs[i].temp = NULL;
    }
    return true;
}

void cli_output_discard(cli_output *out)
{
    if (out->file)
        fclose(out->file);
    if (out->temp)
        unlink(out->temp);
    free(out->temp);
    free(out->target);
    memset(out, 0, sizeof *out);
}

/* The real path of path's folder, with the base name after it; NULL when the folder is missing. */
static char *real_place(const char *path)
{
    char *target = resolve_target(path);
    if (!target)
        return NULL;
    size_t folder = folder_length(target);
    char *dir = folder ? strndup(target, folder) : strdup(".");
    char *real = dir ? realpath(dir, NULL) : NULL;
    const char *base = target + folder;
    char *place = real ? malloc(strlen(real) + 1 + strlen(base) + 1) : NULL;
    if (place)
        sprintf(place, "%s/%s", real, base);
    free(real);
    free(dir);
    free(target);
    return place;
}

bool cli_output_same_file(const char *a, const char *b)
{
    /* A device such as /dev/null takes both outputs with nothing replaced: only a file can be lost. */
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino && S_ISREG(sa.st_mode);
    char *pa = real_place(a), *pb = real_place(b);
    bool same = pa && pb && strcmp(pa, pb) == 0;
    free(pa);
    free(pb);
    return same;
}
