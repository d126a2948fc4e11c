/* Says whether a headless backend gives a context here: exit 0, or 1 with MACS's reason on stdout.
 * tests/run_suites.sh asks it whether OSMesa is there before choosing the backend of every suite.
 * Usage: probe_headless osmesa|egl|device */
#include <stdio.h>
#include <string.h>

#include "macs.h"

int main(int argc, char **argv)
{
    static const struct { const char *name; macs_headless_backend backend; } names[] = {
        {"osmesa", MACS_HEADLESS_OSMESA}, {"egl", MACS_HEADLESS_EGL}, {"device", MACS_HEADLESS_EGL_DEVICE}};
    macs_headless_desc desc = {0};
    size_t i = 0;
    while (argc == 2 && i < sizeof names / sizeof names[0] && strcmp(argv[1], names[i].name) != 0)
        i++;
    if (argc != 2 || i == sizeof names / sizeof names[0]) {
        fprintf(stderr, "usage: probe_headless osmesa|egl|device\n");
        return 2;
    }
    desc.backend = names[i].backend;
    char message[1024];
    macs_headless *h = NULL;
    if (macs_headless_create(&desc, &h, message, sizeof message) != MACS_OK) {
        printf("%s\n", message);
        return 1;
    }
    macs_headless_destroy(h);
    return 0;
}
