/* The `betelgeuse` command (docs/command.md): render, assemble, info and view, --help and --version. */
#include <stdio.h>
#include <string.h>

#include "betelgeuse.h"
#include "cli.h"
#include "numbers.h"
#include "output.h"
#include "view_input.h"

#ifndef BG_CLI_VERSION
#define BG_CLI_VERSION "unknown"
#endif

/* The library's limits as text, so that the help states the numbers the parser enforces. */
#define SIDE CLI_NUMBER_TEXT(BG_MAX_IMAGE_SIDE)

/* In pieces: C99 promises string literals of 4095 characters only. */
static const char *const help[] = {
    "usage: betelgeuse render SCENE -o OUT.png [options]\n"
    "       betelgeuse assemble TILE.png... -o OUT.png\n"
    "       betelgeuse info SCENE [--renderer gpu|cpu] [--backend egl|osmesa] [--integrator whitted|path]\n"
    "                       [model options]\n"
    "       betelgeuse view SCENE [--size WxH] [--samples N] [--integrator whitted|path] [--frame-ms MS]\n"
    "                       [model options] [--script FILE | --benchmark] [-v] [-q]\n"
    "       betelgeuse --help | --version\n"
    "\n"
    "SCENE is a JSON scene file (docs/scene_format.md) or a model file (OBJ, PLY, STL, glTF), which is\n"
    "rendered with its cameras and lights, or a camera framing it and a default light.\n"
    "\n"
    "render options:\n"
    "  -o, --output OUT.png   the image (8-bit RGBA; it records its place in the frame for assemble)\n"
    "  --size WxH             the frame's size, each side 1 .. " SIDE " (default: the scene file's image, else\n"
    "                         640x480)\n"
    "  --samples N            camera rays per pixel, 1 .. " CLI_NUMBER_TEXT(BG_MAX_SAMPLES) ", stratified,\n"
    "                         box-filtered (default: the file's, else 1)\n"
    "  --renderer gpu|cpu     the GPU renderer on a headless context (default) or the CPU reference\n"
    "  --backend egl|osmesa   the headless context for the GPU: EGL (a GPU device, else surfaceless) or\n"
    "                         OSMesa; default: EGL device, EGL surfaceless, then OSMesa\n"
    "  --crop X0,Y0,X1,Y1     render only this window of the frame (pixels 0 .. " SIDE ", X1 and Y1 exclusive)\n"
    "  --tile I/N             render only band I of N of the frame (or of the crop): rows\n"
    "                         [floor((I-1) H / N), floor(I H / N)); `assemble` joins the bands\n"
    "  --max-depth D          bounce levels, 0 .. " CLI_NUMBER_TEXT(BG_MAX_DEPTH) " (default: the file's, else 5)\n"
    "  --integrator whitted|path  the paper's ray tree, or a path tracer (global illumination, noisy\n"
    "                         until many samples; docs/shading.md 13); default: the file's, else whitted.\n"
    "                         The GPU renderer does not draw path yet: use --renderer cpu\n"
    "  --linear               write linear values instead of sRGB\n"
    "  --float OUT.pfm        also write the linear radiance as a PFM (renders the frame a second time)\n"
    "  -q, --quiet            print nothing but errors (no progress bar, no warnings)\n"
    "  --timings              print each phase's wall time to stderr: scene load, context, render (with\n"
    "                         the programs it compiled), the frame rendered again with its programs\n"
    "                         cached (for this report only), PNG encode and write, putting in place\n"
    "  --strict               any warning while loading the scene (a missing model texture, a\n"
    "                         skipped PLY header line) is fatal: exit 2 (render, info and view)\n"
    "\n",
    "view options (a window; the GPU renderer on its OpenGL 2.1 context, through GLFW):\n"
    "  --size WxH, --samples N, --max-depth D, --integrator, -q and the model options as for render;\n"
    "                         the samples at rest default to the file's when more than 1, else 64\n"
    "  --frame-ms MS          the frame time to hold while the camera moves, 1 .. 10000 (default 33):\n"
    "                         moving frames are rendered at 1/1, 1/2, 1/3 or 1/4 of each side\n"
    "  --script FILE          timed inputs (wait, drag, scroll, key, screenshot, wait-rest, wait-reload,\n"
    "                         expect-compiled, expect-gl, expect-error, touch, write, quit; docs/command.md);\n"
    "                         the viewer quits after its last line and prints its frame counts\n"
    "  --benchmark            a scripted orbit, then the rest to N samples: frame-time percentiles, the\n"
    "                         resolution chosen, the time to N samples\n"
    "  -v, --verbose          the GL version, each reload and the frame counts on exit\n"
    "The scene file and every file it reads are watched: an edit reloads the scene; a bad one keeps the\n"
    "last image and shows the error in the title and on stderr.\n"
    "\n",
    "model options (render, info and view):\n"
    "  --up y|z|-y|-z         the model file's up axis, turned to +y (default y, glTF's); a Z-up file\n"
    "                         lies on its side without --up z\n"
    "  --smooth [ANGLE]       compute normals where the file has none, smooth across edges whose face\n"
    "                         normals differ by at most ANGLE degrees, 0 .. 180, creased at sharper ones\n"
    "                         (default 180: fully smooth); without it such a file stays flat-faceted\n"
    "  --camera N|auto        the file's camera N, counted from 1 (default 1), or auto: a camera\n"
    "                         framing the model even when the file has cameras\n"
    "  --look-from X,Y,Z      the camera's position, replacing the chosen camera's\n"
    "  --look-at X,Y,Z        the point it looks at\n"
    "  --fov DEG              its vertical field of view, between 0 and 180 (a framing camera keeps\n"
    "                         the model in view at it)\n"
    "  --aperture R           its lens radius, >= 0, for depth of field (0: a pinhole, everything sharp);\n"
    "                         the blur converges as samples add up (--samples, or the viewer at rest)\n"
    "  --focus-distance D     the distance ahead of the camera that stays sharp, >= 0 (0: the distance\n"
    "                         to the point it looks at)\n"
    "--up, --smooth and --camera apply to model files; --look-from, --look-at, --fov, --aperture and\n"
    "--focus-distance to JSON scenes too. `info` says which camera was used and how many the file has.\n"
    "\n"
    "A progress bar with the elapsed and remaining time goes to stderr when it is a terminal; Ctrl-C\n"
    "cancels the render and writes nothing. Pixels are the same whatever the crop or tile.\n"
    "\n"
    "Outputs are written beside their target under a temporary name and renamed into place only when\n"
    "every output of the run is complete: a failed write leaves existing files as they were. An output\n"
    "that names an input (the scene, a model, a texture, a tile), or -o and --float naming one file,\n"
    "is refused.\n"
    "\n"
    "exit codes: 0 done; 1 the render or a write failed (or was cancelled); 2 bad usage, or a bad\n"
    "scene, model or tile file (the message names the file, the field and the reason).\n"
    "\n"
    "view's mouse and keys:\n",
};

/* The help, and the viewer's controls from the table its input mapping keeps. */
static void print_help(void)
{
    for (size_t i = 0; i < sizeof help / sizeof help[0]; i++)
        fputs(help[i], stdout);
    fputs(view_input_help, stdout);
}

int main(int argc, char **argv)
{
    cli_output_init();
    if (argc < 2) {
        for (size_t i = 0; i < sizeof help / sizeof help[0]; i++)
            fputs(help[i], stderr);
        fputs(view_input_help, stderr);
        return CLI_EXIT_USAGE;
    }
    const char *command = argv[1];
    if (strcmp(command, "--help") == 0 || strcmp(command, "-h") == 0 || strcmp(command, "help") == 0) {
        print_help();
        return CLI_EXIT_OK;
    }
    if (strcmp(command, "--version") == 0) {
        printf("betelgeuse %s\n", BG_CLI_VERSION);
        return CLI_EXIT_OK;
    }
    for (int i = 2; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            print_help();
            return CLI_EXIT_OK;
        }
    if (strcmp(command, "render") == 0)
        return cli_render(argc - 2, argv + 2);
    if (strcmp(command, "assemble") == 0)
        return cli_assemble(argc - 2, argv + 2);
    if (strcmp(command, "info") == 0)
        return cli_info(argc - 2, argv + 2);
    if (strcmp(command, "view") == 0)
        return cli_view(argc - 2, argv + 2);
    fprintf(stderr, "betelgeuse: unknown command '%s' (render, assemble, info, view; see betelgeuse --help)\n", command);
    return CLI_EXIT_USAGE;
}
