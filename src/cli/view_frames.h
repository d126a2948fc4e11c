/* The viewer's frames on the GPU (view_frames.c): what the window shows is always a MACS texture the
 * renderer wrote, never an image that went through the host. Moving, a frame is one sample at a
 * reduced size; at rest, the full-size frame gathers samples until it holds the N the viewer wants.
 *
 * At rest each step adds one sample of the pattern of N to a bg_accumulation on the GPU and resolves
 * the mean into the full texture, nothing read back; after N samples the frame is render's
 * --samples N bit for bit (the library's promise, docs/gpu_pipeline.md "Accumulation"). */
#ifndef CLI_VIEW_FRAMES_H
#define CLI_VIEW_FRAMES_H

#include <stdbool.h>

#include "betelgeuse.h"
#include "macs.h"

typedef struct view_frames {
    macs_context *context;
    bg_renderer *renderer;
    macs_texture *full;    /* the full-size frame, RGBA8 in the settings' encoding */
    macs_texture *reduced; /* the last moving frame's, at its reduced size */
    macs_texture *shown;   /* the one of the two the window shows (NULL: nothing yet) */
    bg_accumulation *sum;  /* the full frame's samples so far */
    int sum_width, sum_height;
    int samples;           /* samples the full frame holds (0: none, it restarts) */
} view_frames;

/* One moving frame: a single sample at width x height into the reduced texture, which it shows.
 * BG_OK or the renderer's failure (its message in bg_renderer_error_message). */
bg_status view_frames_moving(view_frames *f, bg_scene *scene, const bg_render_settings *settings, int width,
                             int height);

/* One step towards settings->samples at rest at the settings' frame size: adds samples to the full
 * frame and shows it (f->samples says how many it holds). */
bg_status view_frames_rest(view_frames *f, bg_scene *scene, const bg_render_settings *settings);

/* Forgets the samples gathered: the camera or the scene changed. */
void view_frames_restart(view_frames *f);

/* The shown frame read back into a new RGBA8 image with rows top first (pixels malloc'ed); false
 * when nothing is shown yet or out of memory. */
bool view_frames_read(view_frames *f, bg_image *image);

void view_frames_free(view_frames *f);

#endif
