/* Replays a corpus through a fuzz target without libFuzzer: every file named on the command line,
 * and every file under every folder named there (in name order, hidden files skipped), goes once
 * through LLVMFuzzerTestOneInput. Built with the project's own compiler and flags, and with ASan and
 * UBSan under SANITIZE=1, it makes the fuzz corpus a regression test that needs no clang.
 *
 *     replay_<target> [--in-process] FILE_OR_FOLDER...
 *
 * Each input runs in a child process of its own, so that one crashing input does not hide the
 * others: the run names every input that crashed, hung (BG_FUZZ_REPLAY_TIMEOUT seconds, default
 * 10) or leaked (LeakSanitizer reports at each child's exit), and exits 1 if any did, or if a name
 * could not be read or no input was found. --in-process runs them all in this process instead, to
 * step through one input in a debugger; the first crash then ends the run. */
#include "fuzz_target.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

typedef struct replay {
    bool in_process;
    unsigned timeout;
    size_t ran, failed, unreadable;
} replay;

/* The whole file in a buffer of exactly its size, so that the target's overreads past the input are
 * caught under AddressSanitizer as they are under libFuzzer. */
static bool read_input(const char *path, uint8_t **out, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    uint8_t *data = NULL;
    size_t n = 0, cap = 0;
    bool ok = true;
    for (;;) {
        if (n == cap) {
            size_t grown = cap ? 2 * cap : 4096;
            uint8_t *p = realloc(data, grown);
            if (!p) {
                ok = false;
                break;
            }
            data = p;
            cap = grown;
        }
        size_t got = fread(data + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            ok = !ferror(f);
            break;
        }
    }
    fclose(f);
    if (ok) {
        uint8_t *exact = malloc(n ? n : 1);
        ok = exact != NULL;
        if (ok && n)
            memcpy(exact, data, n);
        *out = exact;
        *size = n;
    }
    free(data);
    return ok;
}

static void run_in_child(replay *r, const char *path, const uint8_t *data, size_t size)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        fprintf(stderr, "replay: %s: cannot fork: %s\n", path, strerror(errno));
        r->failed++;
        return;
    }
    if (pid == 0) {
        /* SIGALRM's default action ends the child: a hang shows as that signal. */
        alarm(r->timeout);
        LLVMFuzzerTestOneInput(data, size);
        exit(0); /* exit, not _exit: LeakSanitizer checks for leaks at exit */
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) {
            fprintf(stderr, "replay: %s: waitpid: %s\n", path, strerror(errno));
            r->failed++;
            return;
        }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return;
    r->failed++;
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
        fprintf(stderr, "replay: FAILED %s: still running after %u s\n", path, r->timeout);
    else if (WIFSIGNALED(status))
        fprintf(stderr, "replay: FAILED %s: killed by signal %d (%s)\n", path, WTERMSIG(status),
                strsignal(WTERMSIG(status)));
    else
        fprintf(stderr, "replay: FAILED %s: exit status %d\n", path, WEXITSTATUS(status));
}

static void run_file(replay *r, const char *path)
{
    uint8_t *data = NULL;
    size_t size = 0;
    if (!read_input(path, &data, &size)) {
        fprintf(stderr, "replay: cannot read %s: %s\n", path, strerror(errno));
        r->unreadable++;
        return;
    }
    r->ran++;
    if (r->in_process)
        LLVMFuzzerTestOneInput(data, size);
    else
        run_in_child(r, path, data, size);
    free(data);
}

static int visible(const struct dirent *e)
{
    return e->d_name[0] != '.';
}

static void run_path(replay *r, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "replay: %s: %s\n", path, strerror(errno));
        r->unreadable++;
        return;
    }
    if (!S_ISDIR(st.st_mode)) {
        run_file(r, path);
        return;
    }
    struct dirent **names;
    int n = scandir(path, &names, visible, alphasort);
    if (n < 0) {
        fprintf(stderr, "replay: cannot list %s: %s\n", path, strerror(errno));
        r->unreadable++;
        return;
    }
    for (int i = 0; i < n; i++) {
        size_t len = strlen(path) + strlen(names[i]->d_name) + 2;
        char *child = malloc(len);
        if (child) {
            /* "dir/" given on the command line stays one slash: the names printed are paths to paste. */
            size_t pl = strlen(path);
            snprintf(child, len, "%s%s%s", path, pl && path[pl - 1] == '/' ? "" : "/", names[i]->d_name);
            run_path(r, child);
            free(child);
        } else {
            r->unreadable++;
        }
        free(names[i]);
    }
    free(names);
}

int main(int argc, char **argv)
{
    replay r = {false, 10, 0, 0, 0};
    const char *t = getenv("BG_FUZZ_REPLAY_TIMEOUT");
    if (t && atoi(t) > 0)
        r.timeout = (unsigned)atoi(t);
    const char *name = strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0];
    int first = 1;
    if (argc > 1 && strcmp(argv[1], "--in-process") == 0) {
        r.in_process = true;
        first = 2;
    }
    if (first >= argc) {
        fprintf(stderr, "usage: %s [--in-process] FILE_OR_FOLDER...\n", name);
        return 2;
    }
    LLVMFuzzerInitialize(&argc, &argv);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = first; i < argc; i++)
        run_path(&r, argv[i]);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    printf("%s: %zu inputs run in %.1f s, %zu failed%s\n", name, r.ran, seconds, r.failed,
           r.unreadable ? ", some names could not be read" : "");
    if (r.ran == 0)
        fprintf(stderr, "%s: no input found\n", name);
    return r.failed || r.unreadable || r.ran == 0 ? 1 : 0;
}
