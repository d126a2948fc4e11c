/* Opening an input file (a texture, a scene, a model, a tile) so that no path can block or mislead
 * the reader: only regular files are read. A FIFO would block fopen until a writer comes, a
 * directory reads as a file of absurd size, and /dev/zero never ends.
 *
 * Header-only on purpose: libbetelgeuse, libbetelgeuse_scenefile and the command each compile their
 * own copy, so that no library has to export an internal helper to another. */
#ifndef BG_OPEN_INPUT_H
#define BG_OPEN_INPUT_H

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a file that is not regular is, in words. */
static inline const char *bgi_input_kind(mode_t mode)
{
    if (S_ISDIR(mode))
        return "is a directory";
    if (S_ISFIFO(mode))
        return "is not a regular file (a FIFO)";
    if (S_ISCHR(mode))
        return "is not a regular file (a character device)";
    if (S_ISBLK(mode))
        return "is not a regular file (a block device)";
    if (S_ISSOCK(mode))
        return "is not a regular file (a socket)";
    return "is not a regular file";
}

/* path opened for binary reading, or NULL with the reason in why ("cannot open: ...", "is a
 * directory", "is not a regular file (a FIFO)"). The open is non-blocking, so that a FIFO returns at
 * once and fstat can refuse it; a regular file is switched back to blocking reads. errno is ENOENT
 * when the file is missing, so that a caller probing for optional files can tell that case apart. */
static inline FILE *bgi_open_input(const char *path, char *why, size_t why_size)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        snprintf(why, why_size, "cannot open: %s", strerror(e));
        errno = e;
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        snprintf(why, why_size, "cannot read: %s", strerror(e));
        close(fd);
        errno = e;
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(why, why_size, "%s", bgi_input_kind(st.st_mode));
        close(fd);
        errno = S_ISDIR(st.st_mode) ? EISDIR : EINVAL;
        return NULL;
    }
    int flags = fcntl(fd, F_GETFL);
    FILE *f = flags >= 0 && fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) == 0 ? fdopen(fd, "rb") : NULL;
    if (!f) {
        int e = errno;
        snprintf(why, why_size, "cannot open: %s", strerror(e));
        close(fd);
        errno = e;
    }
    return f;
}

#endif
