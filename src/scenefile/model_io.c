/* assimp's file access routed through bgi_open_input: every file an importer opens (the model, an
 * OBJ's MTL, a glTF's buffers and images) must be a regular file, is opened without blocking, and is
 * named to the caller's input callback. assimp takes a file it cannot open for a missing one (an
 * OBJ without its MTL still loads), so a refusal for any other reason is kept here and turned into
 * the load's error afterwards: a FIFO named as an MTL must not hang the load nor pass unnoticed. */
#include "model_internal.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "betelgeuse/io/open_input.h"

static bgi_sf_model_io *io_of(struct aiFileIO *io)
{
    return (bgi_sf_model_io *)(void *)io->UserData;
}

static FILE *file_of(struct aiFile *file)
{
    return (FILE *)(void *)file->UserData;
}

static size_t read_proc(struct aiFile *file, char *buffer, size_t size, size_t count)
{
    return size && count ? fread(buffer, size, count, file_of(file)) : 0;
}

static size_t write_proc(struct aiFile *file, const char *buffer, size_t size, size_t count)
{
    (void)file, (void)buffer, (void)size, (void)count;
    return 0; /* the loader only reads */
}

static size_t tell_proc(struct aiFile *file)
{
    long at = ftell(file_of(file));
    return at < 0 ? 0 : (size_t)at;
}

static size_t size_proc(struct aiFile *file)
{
    struct stat st;
    return fstat(fileno(file_of(file)), &st) == 0 && st.st_size > 0 ? (size_t)st.st_size : 0;
}

/* assimp passes offsets as size_t; from the current position or the end a step back arrives as its
 * two's complement, so it is taken back to a signed offset. */
static enum aiReturn seek_proc(struct aiFile *file, size_t offset, enum aiOrigin origin)
{
    long off;
    if (offset <= LONG_MAX)
        off = (long)offset;
    else if (origin != aiOrigin_SET && SIZE_MAX - offset < (size_t)LONG_MAX)
        off = -(long)(SIZE_MAX - offset) - 1;
    else
        return aiReturn_FAILURE;
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    return fseek(file_of(file), off, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static void flush_proc(struct aiFile *file)
{
    (void)file;
}

static struct aiFile *open_proc(struct aiFileIO *io, const char *path, const char *mode)
{
    bgi_sf_model_io *m = io_of(io);
    if (!path || !mode || strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+'))
        return NULL;
    char why[256];
    FILE *f = bgi_open_input(path, why, sizeof why);
    if (!f) {
        if (errno != ENOENT && !m->refused[0])
            snprintf(m->refused, sizeof m->refused, "its file \"%.200s\" %s", path, why);
        return NULL;
    }
    struct aiFile *file = malloc(sizeof *file);
    if (!file) {
        fclose(f);
        return NULL;
    }
    bgi_sf_note_input(m->ctx, path);
    *file = (struct aiFile){read_proc, write_proc, tell_proc, size_proc, seek_proc, flush_proc, (aiUserData)(void *)f};
    return file;
}

static void close_proc(struct aiFileIO *io, struct aiFile *file)
{
    (void)io;
    if (file) {
        fclose(file_of(file));
        free(file);
    }
}

void bgi_sf_model_io_init(bgi_sf_model_io *m, bgi_sf_ctx *ctx)
{
    memset(m, 0, sizeof *m);
    m->ctx = ctx;
    m->io.OpenProc = open_proc;
    m->io.CloseProc = close_proc;
    m->io.UserData = (aiUserData)(void *)m;
}
