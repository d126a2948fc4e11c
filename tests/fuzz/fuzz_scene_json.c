/* Fuzz target: JSON scene text through bg_scenefile_load_string into a fresh scene.
 *
 * Relative texture and mesh paths resolve against the folder of the shipped scenes, so that the
 * seeds (copies of the .json files of examples/scenes/json) load their PNG textures and the bunny,
 * and the fuzzer reaches the code after a successful load (materials on textures, meshes, the
 * commit) rather than stopping at "cannot open". The folder is BG_FUZZ_SCENE_DIR from the
 * environment, else the one the Makefile compiles in (FUZZ_SCENE_DIR, an absolute path), else the
 * current folder. */
#include "fuzz_target.h"

#include <betelgeuse_scenefile.h>

#include <stdlib.h>
#include <string.h>

#ifndef FUZZ_SCENE_DIR
#define FUZZ_SCENE_DIR NULL
#endif

static const char *scene_dir;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    bg_fuzz_detach_stdin();
    const char *env = getenv("BG_FUZZ_SCENE_DIR");
    scene_dir = env && *env ? env : FUZZ_SCENE_DIR;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > BG_FUZZ_MAX_INPUT)
        return 0;
    /* The loader takes a C string; a copy of exactly size + 1 bytes keeps an overread past the
     * text visible to AddressSanitizer. A zero byte inside the input ends the text early. */
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    if (size > 0)
        memcpy(text, data, size);
    text[size] = '\0';

    bg_scene *scene = NULL;
    if (bg_scene_create(NULL, &scene) == BG_OK) {
        bg_scenefile_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.base_dir = scene_dir;
        desc.name = "fuzz.json";
        bg_scenefile_result result;
        char message[512];
        /* Success and failure are both fine: only crashes, sanitizer reports and leaks count. */
        message[0] = '\0';
        bg_status st = bg_scenefile_load_string(text, &desc, scene, &result, message, sizeof message);
        bg_fuzz_report(st, message);
        bg_scene_destroy(scene);
    }
    free(text);
    return 0;
}
