/* The files a run reads, known by identity (device and inode), so that an output path naming one
 * of them, by whatever spelling (./, .., a symbolic or a hard link), is refused before anything is
 * written over it. */
#ifndef CLI_INPUTS_H
#define CLI_INPUTS_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

typedef struct cli_input {
    dev_t device;
    ino_t inode;
    char *path; /* as it was given, for the message */
} cli_input;

typedef struct cli_inputs {
    cli_input *items;
    size_t count, capacity;
    bool out_of_memory; /* an add failed: the list is incomplete and cannot vouch for an output */
} cli_inputs;

/* Adds the file at path; a path that names no file is skipped (writing there loses nothing). */
void cli_inputs_add(cli_inputs *in, const char *path);

/* cli_inputs_add in the shape of bg_scenefile_desc.inputs, with user the cli_inputs. */
void cli_inputs_on_read(const char *path, void *user);

/* True when path may be written; false with the reason (naming option, path and the input) when
 * it names an input. */
bool cli_inputs_allow(const cli_inputs *in, const char *option, const char *path, char *why, size_t why_size);

void cli_inputs_free(cli_inputs *in);

#endif
