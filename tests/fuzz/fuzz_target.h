/* The entry points every fuzz target defines, in libFuzzer's form. libFuzzer calls them; so does
 * tests/fuzz/replay_main.c, which runs each file of a corpus through a target, so that the same
 * target code runs both under clang's fuzzer and, without clang, as a regression test in make check. */
#ifndef BG_FUZZ_TARGET_H
#define BG_FUZZ_TARGET_H

#include <betelgeuse.h>

#include <stddef.h>
#include <stdint.h>

/* Called once before the first input, in the process that will run them (the replay driver calls
 * it before it forks its per-input children). Returns 0. */
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* Runs one input; returns 0 (libFuzzer reserves other values). A bug shows as a crash, a sanitizer
 * report or a leak, never as a return value. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Inputs larger than this are skipped: the loaders' cost grows with the input, and large inputs
 * slow the fuzzer down without reaching code that small ones do not. */
#define BG_FUZZ_MAX_INPUT ((size_t)1 << 20)

/* Standard input as /dev/null: a scene or model may name "/dev/stdin" as a texture or material
 * file, and a read from a terminal would stall the run until libFuzzer's timeout. */
void bg_fuzz_detach_stdin(void);

/* With BG_FUZZ_VERBOSE=1 in the environment, the loader's status and message for each input go to
 * stderr: to see how far a new seed gets, e.g. that a scene loads rather than stops at a typo.
 * Silent otherwise, as the fuzzer wants its targets. */
void bg_fuzz_report(bg_status status, const char *message);

#endif
