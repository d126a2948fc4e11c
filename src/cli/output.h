/* The command's output files, replaced all at once or not at all: each is written to a temporary
 * file beside its target, and the temporaries are renamed onto the targets only when every output
 * of the run has been written. A failed or cancelled run removes its temporaries and leaves the
 * files that were there before as they were. */
#ifndef CLI_OUTPUT_H
#define CLI_OUTPUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

typedef struct cli_output {
    const char *name; /* the path as the user gave it, for messages */
    char *target;     /* where the file goes: name, or what a symbolic link at name points to */
    char *temp;       /* the temporary beside target; NULL when writing to target directly */
    FILE *file;       /* open between cli_output_open and cli_output_finish */
} cli_output;

/* Notes the process's umask, which a temporary's permissions follow. Call it before any thread
 * starts: reading the umask means setting it for a moment. */
void cli_output_init(void);

/* Creates the temporary for the file at path (a special file that exists, such as /dev/null, is
 * written directly instead). False with the reason; *out is then empty, nothing to discard. */
bool cli_output_open(cli_output *out, const char *path, char *why, size_t why_size);

/* Flushes the written data to disk and closes the file; false with the reason when any write
 * failed (a full disk, a file-size limit). */
bool cli_output_finish(cli_output *out, char *why, size_t why_size);

/* Renames each finished temporary onto its target, in order; false with the reason at the first
 * that fails (the outputs before it are then in place, the rest discarded). */
bool cli_outputs_commit(cli_output *outs, size_t count, char *why, size_t why_size);

/* Closes and removes what is left of an output (nothing after a commit); safe on an empty one. */
void cli_output_discard(cli_output *out);

/* Whether two output paths name one file, so that one output would replace the other: the same
 * folder (after resolving links) and the same base name, or, when both exist, the same regular
 * file (a device such as /dev/null may take both). Outputs need not exist yet. */
bool cli_output_same_file(const char *a, const char *b);

#endif
