/* POV-Ray 3.7 export of the paper's two scenes, and timing of POV-Ray rendering them, so the
 * benchmark can put a classic CPU ray tracer next to our GPU path and CPU reference.
 *
 * The .pov file is written from the scene's committed state (the scene is built with
 * scenes_build), so it carries the very numbers our renderers use. Geometry, camera, lights,
 * texture placement and background are exact; Schlick's BRDF has no POV-Ray counterpart and is
 * replaced by a fitted diffuse term (the file's comments say where). The goal is equal work and a
 * visually matching image, not identical pixels.
 *
 * Nothing here prints: every failure returns false with a message in the caller's buffer (which
 * may be NULL or of size 0 when the caller does not want it). */
#ifndef POV_EXPORT_H
#define POV_EXPORT_H

#include <stdbool.h>
#include <stddef.h>

#include "scenes/scenes.h"

/* True when an executable named povray is found on PATH. */
bool pov_available(void);

/* Writes dir/<scene name>.pov, and dir/<scene name>_tex<N>.png for every texture it uses, for
 * SCENE_PAPER_EARTH or SCENE_PAPER_EARTH_SHADOW; the .pov's path goes to pov_path. False with a
 * message for other scenes, a missing directory, a too small buffer or an I/O failure. */
bool pov_write_scene(scene_id id, const char *dir, char *pov_path, size_t pov_path_size,
                     char *message, size_t message_size);

/* Runs povray as a separate process on the .pov file at width x height (1 .. 16384), antialiasing
 * off, `threads` render threads (1 .. 512, POV-Ray's Work_Threads), writing an sRGB PNG to
 * out_png; *ms receives the process's wall time (start-up, parsing and tracing) in milliseconds.
 * POV-Ray runs in the .pov file's directory (so its texture files resolve) with its console output
 * in <pov_path without .pov>.log. False with a message (the log's last line when POV-Ray says why)
 * if povray is missing, cannot start, is killed or exits non-zero. */
bool pov_render(const char *pov_path, int width, int height, int threads, const char *out_png,
                double *ms, char *message, size_t message_size);

#endif
