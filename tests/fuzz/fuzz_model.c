/* Fuzz target: one model file format through bg_scenefile_load_model, compiled once per format with
 * -DFUZZ_EXTENSION=".ply" (or ".obj", ".stl").
 *
 * The loader takes a path and assimp picks its reader by the file's extension, so each input is
 * written to a file with that extension and loaded from there. The file lives in a private folder
 * (mkdtemp) under /dev/shm where that exists, so that the writes stay in memory, else under /tmp. The
 * folder is made once per process and the file is removed after every input, so that nothing one
 * input leaves on disk reaches the next; the folder goes at exit.
 *
 * A process that ends without running atexit (a crash report, a libFuzzer timeout, leak or memory
 * limit, a kill) leaves its folder behind, and libFuzzer's -fork mode ends a process at every
 * finding. So the folder's name holds the process id, bg-fuzz-<pid>-XXXXXX, and each target sweeps
 * away, as it starts, the folders of processes that are gone. */
#include "fuzz_target.h"

#include <betelgeuse_scenefile.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifndef FUZZ_EXTENSION
#error "compile with -DFUZZ_EXTENSION='\".ply\"' (the model format's file extension)"
#endif

#define FOLDER_PREFIX "bg-fuzz-"

static char dir[128];
static char file[160];
/* The process that made the folder: the replay driver's per-input children share it and must not
 * remove it when they exit. */
static pid_t owner;
static int ready; /* 1 while the folder exists */

static void remove_files(void)
{
    if (!ready)
        return;
    unlink(file);
    if (getpid() == owner) {
        rmdir(dir);
        ready = 0;
    }
}

/* A left-behind folder holds at most the one input file: its plain entries go, then the folder. */
static void remove_folder(const char *path)
{
    DIR *d = opendir(path);
    if (!d)
        return;
    struct dirent *e;
    char entry[512];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        if (snprintf(entry, sizeof entry, "%s/%s", path, e->d_name) < (int)sizeof entry)
            unlink(entry);
    }
    closedir(d);
    rmdir(path);
}

/* A folder is stale when its process is gone (kill(pid, 0) says no such process) and it has not
 * changed for a minute. The age guards a live target whose id means another process here (a
 * different pid namespace sharing /dev/shm): a running target rewrites its file for every input,
 * and libFuzzer's -timeout stops an input long before a minute. Folders of other users are left
 * alone; the sticky /dev/shm and /tmp would refuse their removal anyway. */
static void sweep(const char *base)
{
    DIR *d = opendir(base);
    if (!d)
        return;
    time_t now = time(NULL);
    struct dirent *e;
    char path[512];
    while ((e = readdir(d)) != NULL) {
        long pid;
        char dash;
        size_t n = strlen(FOLDER_PREFIX);
        if (strncmp(e->d_name, FOLDER_PREFIX, n) != 0 || sscanf(e->d_name + n, "%ld%c", &pid, &dash) != 2 ||
            dash != '-' || pid <= 0 || (pid_t)pid == getpid())
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue;
        struct stat st;
        if (snprintf(path, sizeof path, "%s/%s", base, e->d_name) < (int)sizeof path && lstat(path, &st) == 0 && S_ISDIR(st.st_mode) && st.st_uid == getuid() && now - st.st_mtime >= 60)
            remove_folder(path);
    }
    closedir(d);
}

static void setup(void)
{
    if (ready)
        return;
    struct stat st;
    const char *base = stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) && access("/dev/shm", W_OK) == 0
                           ? "/dev/shm" : "/tmp";
    sweep(base);
    snprintf(dir, sizeof dir, "%s/" FOLDER_PREFIX "%ld-XXXXXX", base, (long)getpid());
    if (!mkdtemp(dir)) {
        /* Going on would pass every input untested. */
        fprintf(stderr, "fuzz_model: cannot make a folder %s: %s\n", dir, strerror(errno));
        abort();
    }
    snprintf(file, sizeof file, "%s/input%s", dir, FUZZ_EXTENSION);
    owner = getpid();
    ready = 1;
    atexit(remove_files);
}

static int write_file(const uint8_t *data, size_t size)
{
    int fd = open(file, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0)
        return -1;
    size_t done = 0;
    while (done < size) {
        ssize_t n = write(fd, data + done, size - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            close(fd);
            return -1;
        }
        done += (size_t)n;
    }
    return close(fd);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    bg_fuzz_detach_stdin();
    setup();
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    setup(); /* for a driver that does not call LLVMFuzzerInitialize */
    if (size > BG_FUZZ_MAX_INPUT)
        return 0;
    if (write_file(data, size) != 0) {
        /* A full /dev/shm or /tmp would otherwise pass every input untested. */
        fprintf(stderr, "fuzz_model: cannot write %s: %s\n", file, strerror(errno));
        abort();
    }
    bg_scene *scene = NULL;
    if (bg_scene_create(NULL, &scene) == BG_OK) {
        bg_scenefile_result result;
        char message[512];
        /* Success and failure are both fine: only crashes, sanitizer reports and leaks count. */
        message[0] = '\0';
        bg_status st = bg_scenefile_load_model(file, NULL, scene, &result, message, sizeof message);
        bg_fuzz_report(st, message);
        bg_scene_destroy(scene);
    }
    unlink(file);
    return 0;
}
