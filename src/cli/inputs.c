/* The run's inputs by identity (inputs.h). Comparing names would miss "./s.json", "d/../s.json"
 * and links; two paths name one file exactly when stat gives the same device and inode. */
#include "inputs.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void cli_inputs_add(cli_inputs *in, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return;
    for (size_t i = 0; i < in->count; i++)
        if (in->items[i].device == st.st_dev && in->items[i].inode == st.st_ino)
            return;
    if (in->count == in->capacity) {
        size_t capacity = in->capacity ? 2 * in->capacity : 8;
        cli_input *items = realloc(in->items, capacity * sizeof *items);
        if (!items) {
            in->out_of_memory = true;
            return;
        }
        in->items = items;
        in->capacity = capacity;
    }
    char *copy = strdup(path);
    if (!copy) {
        in->out_of_memory = true;
        return;
    }
    in->items[in->count++] = (cli_input){st.st_dev, st.st_ino, copy};
}

void cli_inputs_on_read(const char *path, void *user)
{
    cli_inputs_add(user, path);
}

bool cli_inputs_allow(const cli_inputs *in, const char *option, const char *path, char *why, size_t size)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return true; /* a file that is not there yet is no input */
    for (size_t i = 0; i < in->count; i++)
        if (in->items[i].device == st.st_dev && in->items[i].inode == st.st_ino) {
            snprintf(why, size, "%s %s: that is the input file %s, which the output would overwrite", option, path,
                     in->items[i].path);
            return false;
        }
    return true;
}

void cli_inputs_free(cli_inputs *in)
{
    for (size_t i = 0; i < in->count; i++)
        free(in->items[i].path);
    free(in->items);
    memset(in, 0, sizeof *in);
}
