/* Test helpers for the GPU renderer suites: a renderer on a MACS context, and shared scenes. */
#ifndef UTIL_GPU_H
#define UTIL_GPU_H

#include "gpu_thresholds.h"

#include "betelgeuse.h"
#include "scenes/scenes.h"

/* A headless context, a MACS context on it and a renderer on that. */
typedef struct util_gpu {
    macs_headless *headless;
    macs_context *ctx;
    bg_renderer *renderer;
} util_gpu;

/* A renderer with default settings on ctx, with no stored error; fails the test on error. */
bg_renderer *util_renderer(macs_context *ctx);
/* Opens the whole stack (caps may be NULL); fails the test on error. */
void util_gpu_open(util_gpu *g, const macs_limits *caps);
/* Destroys what util_gpu_open made. */
void util_gpu_close(util_gpu *g);
/* A new scene built as the shared scene id and committed; fails the test on error. */
bg_scene *util_scene(scene_id id);

/* A committed tube of 40000 overlapping sphere boxes around the view axis, the spheres all beside
 * it: a ray down the axis enters every box and hits nothing, 80000 steps, more than llvmpipe's loop
 * limit leaves a pixel, so the tree plan hands those pixels to the CPU reference. */
bg_scene *util_tube_scene(void);

/* The same for meshes: a committed stack of 40000 triangles facing the camera, each triangle's box
 * around the view axis but the triangle beside it, under one light: the pixels near the axis walk
 * every node of the mesh's tree, and every plan hands them to the CPU reference. */
bg_scene *util_triangle_stack_scene(void);

/* The default settings with the paper's multipass plan forced: for the suites that check that
 * plan's passes, G-buffer, splits and skips (BG_PLAN_AUTO picks the fused plan where it can). */
bg_render_settings util_multipass_settings(void);

/* Under a limit profile (MACS_TEST_PROFILE), a render the renderer refuses with BG_ERR_LIMIT is a
 * profile the renderer cannot work within: skips the calling test, printing label, the profile and
 * message (which names the limit). Does nothing for any other status, or without a profile. */
void util_skip_if_profile_refuses(bg_status st, const char *message, const char *label);

/* The renderer's GPU entry points as the suites call them: the same, except that under a limit
 * profile a BG_ERR_LIMIT refusal skips the calling test by name (util_skip_if_profile_refuses)
 * instead of returning, so that a test the profile's hardware could not run is counted as skipped,
 * never as passed or failed. Without MACS_TEST_PROFILE they return exactly what the library does.
 * The suites get them through the macros below; util_gpu.c calls the library's own, and so does a
 * test whose point is the refusal, by putting the name in parentheses: (bg_render_gpu)(r, s, set, img). */
bg_status util_profiled_render_gpu(bg_renderer *r, bg_scene *s, const bg_render_settings *set, bg_image *img);
bg_status util_profiled_render_gpu_to_texture(bg_renderer *r, bg_scene *s, const bg_render_settings *set,
                                              macs_texture *target);
bg_status util_profiled_render_gpu_accumulate(bg_renderer *r, bg_scene *s, const bg_render_settings *set,
                                              bg_accumulation *acc, int first, int count);
#ifndef UTIL_GPU_LIBRARY_CALLS
#define bg_render_gpu(r, s, set, img) util_profiled_render_gpu(r, s, set, img)
#define bg_render_gpu_to_texture(r, s, set, target) util_profiled_render_gpu_to_texture(r, s, set, target)
#define bg_render_gpu_accumulate(r, s, set, acc, first, count) \
    util_profiled_render_gpu_accumulate(r, s, set, acc, first, count)
#endif

/* The default settings with the given plan and samples, and 2 CPU threads for the reference. */
bg_render_settings util_plan_settings(bg_gpu_plan plan, int samples);
/* Fails the test with what, the status and r's message unless st is BG_OK. */
void util_expect_render_ok(bg_renderer *r, bg_status st, const char *what);

/* Renders s with bg_render_gpu (skipping as util_skip_if_profile_refuses says); on failure fails the
 * test with label, the status, the renderer's
 * message and the message of ctx (the MACS context r renders with). */
void util_render_gpu(bg_renderer *r, macs_context *ctx, bg_scene *s, const bg_render_settings *set, bg_image *img,
                     const char *label);

/* A new committed many_spheres scene of n spheres (fails the test if it cannot be built). */
bg_scene *util_many_spheres(int n);

/* The CPU reference of a scene at width x height, RGBA8, malloc'd (free it). */
unsigned char *util_cpu_reference(bg_scene *s, const bg_render_settings *set, int width, int height);
/* The same on the GPU with the given plan, on a renderer of its own over util_fx's context; fails the
 * test on an error or when another plan ran. */
unsigned char *util_gpu_plan_image(bg_scene *s, const bg_render_settings *set, bg_gpu_plan plan, int width,
                                   int height, const char *label);
/* The multipass plan forced on the scene fails with BG_ERR_LIMIT, its message naming `named`, and
 * leaves the image untouched. */
void util_expect_multipass_refuses(bg_scene *s, const bg_render_settings *set, const char *named);
/* Fails the test unless the multipass plan refuses s (BG_ERR_LIMIT) with a message naming the
 * environment, which it does not draw. */
void util_expect_multipass_refuses_environment(bg_scene *s, const bg_render_settings *set);
/* Fails the test unless the GPU image is within the threshold row of id against the CPU image
 * (gpu_thresholds.h); prints the comparison under label. */
void util_expect_near(const unsigned char *cpu, const bg_image *gpu, scene_id id, const char *label);
/* The same against a row of a suite's own (a scene the shared table has no row for). */
void util_expect_near_row(const unsigned char *cpu, const bg_image *gpu, const gpu_threshold *row, const char *label);
/* util_expect_near against the CPU reference of the same scene and settings. */
void util_expect_within(bg_scene *s, const bg_render_settings *set, const bg_image *gpu, scene_id id,
                        const char *label);

/* The suite-wide fixture of the GPU suites: util_gpu_group_setup opens it with default caps
 * (util_gpu_open), util_gpu_group_teardown closes it; pass both to cmocka_run_group_tests, or call
 * them from a suite's own group functions (setup first, teardown last). */
extern util_gpu util_fx;
int util_gpu_group_setup(void **state);
int util_gpu_group_teardown(void **state);

/* Applies X(test, id) to every shared scene, in scene_id order: X names a test function per scene
 * (paper_earth, ...) and the scene's id. For suites that run one test per shared scene. */
#define UTIL_EACH_SCENE(X)                          \
    X(paper_earth, SCENE_PAPER_EARTH)               \
    X(paper_earth_shadow, SCENE_PAPER_EARTH_SHADOW) \
    X(mirror, SCENE_MIRROR)                         \
    X(glass, SCENE_GLASS)                           \
    X(many_spheres, SCENE_MANY_SPHERES)             \
    X(many_lights, SCENE_MANY_LIGHTS)               \
    X(all_primitives, SCENE_ALL_PRIMITIVES)         \
    X(textured_aniso, SCENE_TEXTURED_ANISO)

/* For UTIL_EACH_SCENE: UTIL_EACH_SCENE(UTIL_SCENE_TEST) defines each scene's test as a call of the
 * suite's own static void check_scene(scene_id id), declared before it; UTIL_EACH_SCENE(UTIL_SCENE_UNIT_TEST)
 * lists those tests in a CMUnitTest array. */
#define UTIL_SCENE_TEST(fn, id)     \
    static void fn(void **state)    \
    {                               \
        (void)state;                \
        check_scene(id);            \
    }
#define UTIL_SCENE_UNIT_TEST(fn, id) cmocka_unit_test(fn),

#endif
