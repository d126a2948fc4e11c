/* The `betelgeuse` command: its subcommands and exit codes (docs/command.md). */
#ifndef CLI_H
#define CLI_H

#include "betelgeuse.h"

/* Exit codes: 0 done, 1 the render (or a write) failed, 2 bad usage or a bad scene or input file. */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAILED = 1, CLI_EXIT_USAGE = 2 };

/* Each takes the arguments after its own name. */
int cli_render(int argc, char **argv);
int cli_assemble(int argc, char **argv);
int cli_info(int argc, char **argv);
int cli_view(int argc, char **argv);

/* The GPU plan in words, as info and the viewer's title name it (render.c). */
const char *cli_plan_name(bg_gpu_plan plan);

#endif
