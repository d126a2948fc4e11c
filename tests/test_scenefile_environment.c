/* "settings.environment" of a JSON scene: a Radiance .hdr (stb_image) or a PNG around the scene.
 * The shipped environment.json loads and renders its sky where rays meet nothing, the same on the
 * CPU and the GPU; a truncated .hdr, a file of another kind and a missing one are refused with the
 * file and the reason; bad keys are refused by path. The shipped window_room.json is lit by its sky
 * through the window only, and its path integrator lights the ceiling the sun cannot reach. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse_scenefile.h"
#include "util_gl.h"
#include "util_gpu.h"

#define SCENES "examples/scenes/json"

enum { W = 40, H = 30 };

static bg_status load_text(const char *text, bg_scene **out, char *message, size_t size)
{
    assert_int_equal(bg_scene_create(NULL, out), BG_OK);
    bg_scenefile_desc d;
    memset(&d, 0, sizeof d);
    d.base_dir = SCENES;
    bg_scenefile_result r;
    return bg_scenefile_load_string(text, &d, *out, &r, message, size);
}

/* The shipped scene: its sky is seen above the horizon (bluish, brighter than the black background),
 * and the GPU's image follows the CPU's. */
static void shipped_environment_scene_renders_its_sky(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_scenefile_result r;
    char message[1024];
    if (bg_scenefile_load(SCENES "/environment.json", NULL, s, &r, message, sizeof message) != BG_OK)
        fail_msg("%s", message);
    bg_render_settings set = r.settings;
    set.samples = 4;
    set.frame_width = W;
    set.frame_height = H;
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    const unsigned char *top = cpu; /* the top-left pixel looks at the sky */
    print_message("top-left pixel %d %d %d\n", top[0], top[1], top[2]);
    assert_true(top[2] > 150 && top[2] > top[0]);
    unsigned char *gpu = util_gpu_plan_image(s, &set, BG_PLAN_FUSED, W, H, "environment.json");
    bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
    static const gpu_threshold row = {SCENE_COUNT, 24.0, 0.5, 35.0, 0.01};
    util_expect_near_row(cpu, &gi, &row, "environment.json, fused");
    free(gpu);
    free(cpu);
    bg_scene_destroy(s);
}

static void expect_refused(const char *text, bg_status status, const char *part1, const char *part2)
{
    bg_scene *s = NULL;
    char message[1024];
    bg_status st = load_text(text, &s, message, sizeof message);
    print_message("%s\n", message);
    assert_int_equal(st, status);
    assert_non_null(strstr(message, part1));
    if (part2)
        assert_non_null(strstr(message, part2));
    bg_scene_destroy(s);
}

static void write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, size, f), size);
    fclose(f);
}

/* Broken files: each refused with the file's path and the reason. */
static void bad_files_are_refused(void **state)
{
    (void)state;
    char dir[] = "/tmp/bg_env_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char truncated[64], text[64], json[512];
    snprintf(truncated, sizeof truncated, "%s/cut.hdr", dir);
    snprintf(text, sizeof text, "%s/notes.hdr", dir);
    /* A header that promises 64 x 32 pixels and two pixels of data. */
    static const char cut[] = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32 +X 64\n\x80\x80\x80\x81\x80\x80\x80\x81";
    write_file(truncated, cut, sizeof cut - 1);
    write_file(text, "just some text\n", 15);
    snprintf(json, sizeof json, "{\"settings\": {\"environment\": {\"file\": \"%s\"}}}", truncated);
    expect_refused(json, BG_ERR_IO, truncated, "not a readable Radiance HDR image");
    snprintf(json, sizeof json, "{\"settings\": {\"environment\": {\"file\": \"%s\"}}}", text);
    expect_refused(json, BG_ERR_IO, text, "neither a Radiance HDR");
    snprintf(json, sizeof json, "{\"settings\": {\"environment\": {\"file\": \"%s/missing.hdr\"}}}", dir);
    expect_refused(json, BG_ERR_IO, "missing.hdr", "cannot open: No such file or directory");
    /* Not regular files: refused by kind, at once (a FIFO without a writer would block a plain open). */
    snprintf(json, sizeof json, "{\"settings\": {\"environment\": {\"file\": \"%s\"}}}", dir);
    expect_refused(json, BG_ERR_IO, dir, "is a directory");
    char fifo[64];
    snprintf(fifo, sizeof fifo, "%s/sky.hdr", dir);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    snprintf(json, sizeof json, "{\"settings\": {\"environment\": {\"file\": \"%s\"}}}", fifo);
    expect_refused(json, BG_ERR_IO, fifo, "a FIFO");
    unlink(fifo);
    unlink(truncated);
    unlink(text);
    rmdir(dir);
}

static void bad_keys_are_refused(void **state)
{
    (void)state;
    expect_refused("{\"settings\": {\"environment\": {\"intensity\": 2}}}", BG_ERR_INVALID_ARGUMENT,
                   "settings.environment", "\"file\" is required");
    expect_refused("{\"settings\": {\"environment\": {\"file\": \"sky.hdr\", \"sampling\": \"random\"}}}",
                   BG_ERR_INVALID_ARGUMENT, "settings.environment.sampling", NULL);
    expect_refused("{\"settings\": {\"environment\": {\"file\": \"sky.hdr\", \"intensity\": -1}}}",
                   BG_ERR_INVALID_ARGUMENT, "settings.environment.intensity", NULL);
    expect_refused("{\"settings\": {\"environment\": {\"file\": \"sky.hdr\", \"lite\": true}}}",
                   BG_ERR_INVALID_ARGUMENT, "lite", NULL);
}

/* A PNG environment loads too (decoded from sRGB), and both sampling rules are accepted. */
static void png_environment_loads(void **state)
{
    (void)state;
    const char *texts[] = {
        "{\"settings\": {\"environment\": {\"file\": \"checker_grey.png\", \"light\": true}}, \"objects\": [{\"plane\": {}}]}",
        "{\"settings\": {\"environment\": {\"file\": \"sky.hdr\", \"light\": true, \"sampling\": \"uniform\"}}, "
        "\"objects\": [{\"plane\": {}}]}"};
    for (int i = 0; i < 2; i++) {
        bg_scene *s = NULL;
        char message[1024];
        if (load_text(texts[i], &s, message, sizeof message) != BG_OK)
            fail_msg("%s: %s", texts[i], message);
        bg_render_settings set = bg_render_settings_init();
        unsigned char *cpu = util_cpu_reference(s, &set, 8, 6);
        free(cpu);
        bg_scene_destroy(s);
    }
}

/* The file's text with add inserted at the start of its "objects" array; malloc'ed. */
static char *scene_text_with(const char *path, const char *add)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char text[16384];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    assert_true(n > 0 && n < sizeof text - 1);
    text[n] = '\0';
    const char *key = "\"objects\": [";
    char *at = strstr(text, key);
    assert_non_null(at);
    size_t head = (size_t)(at - text) + strlen(key);
    char *out = malloc(n + strlen(add) + 1);
    assert_non_null(out);
    memcpy(out, text, head);
    strcpy(out + head, add);
    strcat(out, text + head);
    return out;
}

/* The linear radiance of the scene's frame at W x H, 16 samples, on the CPU; malloc'ed RGBA floats. */
static float *room_radiance(bg_scene *s, const bg_scenefile_result *r, bg_integrator integrator)
{
    bg_render_settings set = r->settings;
    set.integrator = integrator;
    set.samples = 16;
    set.frame_width = W;
    set.frame_height = H;
    float *px = malloc(sizeof(float) * 4 * W * H);
    assert_non_null(px);
    bg_image im = {W, H, BG_PIXEL_RGBA32F, 0, px};
    if (bg_render_cpu(s, &set, &im) != BG_OK)
        fail_msg("%s", bg_scene_error_message(s));
    return px;
}

/* The mean of R, G and B over rows [y0, y1). */
static double mean_rows(const float *px, int y0, int y1)
{
    double sum = 0;
    for (int y = y0; y < y1; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                sum += px[4 * (y * W + x) + c];
    return sum / (3.0 * W * (y1 - y0));
}

/* window_room.json: a room of rectangles whose seams overlap, closed but for a window in its far wall,
 * with no light, no ambient and no emission: its only light is the sky through the window. With a pane
 * over the window every pixel is exactly 0 under either integrator; open, the sun and the sky light
 * it. The top rows see the ceiling, which the sun (35 degrees up, through a window below it) cannot
 * reach and which sees only the ground of the sky (radiance about 0.1) through the window, in about
 * 0.1 sr at a grazing angle: Whitted's ceiling is near 0.001. Under path it gets the light the sunlit
 * floor and walls reflect: the sun puts about 5 W through the window onto 120 m^2 of walls of albedo
 * about 0.7, some 0.02 in radiance after a few bounces. The test asks for 4 times Whitted's, with room
 * for those estimates being off several-fold, and for more light in the whole frame (the bounces only
 * add; the light sampled at the first hit is the same, 13.2). */
static void window_room_is_lit_through_its_window(void **state)
{
    (void)state;
    static const char path[] = SCENES "/window_room.json";
    char message[1024];
    bg_scenefile_result r;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (bg_scenefile_load(path, NULL, s, &r, message, sizeof message) != BG_OK)
        fail_msg("%s", message);
    assert_int_equal(r.settings.integrator, BG_INTEGRATOR_PATH);
    assert_false(r.settings.path_ambient);
    assert_true(r.ambient[0] == 0 && r.ambient[1] == 0 && r.ambient[2] == 0);
    assert_int_equal(r.summary.lights, 0);
    float *path_px = room_radiance(s, &r, BG_INTEGRATOR_PATH);
    float *whitted_px = room_radiance(s, &r, BG_INTEGRATOR_WHITTED);
    bg_scene_destroy(s);

    /* The pane: the window's opening, x in [-1.6, 0.4] and y in [0.9, 2.2] at z = -5, and 0.1 more
       on each side. */
    char *closed = scene_text_with(path, "{\"rectangle\": {}, \"transform\": [{\"scale\": [1.1, 1, 0.75]}, "
                                         "{\"rotate\": {\"axis\": [1, 0, 0], \"degrees\": 90}}, "
                                         "{\"translate\": [-0.6, 1.55, -5]}]},\n");
    bg_scenefile_desc d;
    memset(&d, 0, sizeof d);
    d.base_dir = SCENES;
    d.name = "window_room.json with a pane";
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    if (bg_scenefile_load_string(closed, &d, s, &r, message, sizeof message) != BG_OK)
        fail_msg("%s", message);
    free(closed);
    for (int i = 0; i < 2; i++) {
        bg_integrator integrator = i ? BG_INTEGRATOR_PATH : BG_INTEGRATOR_WHITTED;
        float *px = room_radiance(s, &r, integrator);
        for (int k = 0; k < W * H; k++)
            if (px[4 * k] != 0 || px[4 * k + 1] != 0 || px[4 * k + 2] != 0)
                fail_msg("the closed room (%s) has light at pixel (%d, %d): %g %g %g", i ? "path" : "whitted", k % W,
                         k / W, px[4 * k], px[4 * k + 1], px[4 * k + 2]);
        free(px);
    }
    bg_scene_destroy(s);

    double path_all = mean_rows(path_px, 0, H), whitted_all = mean_rows(whitted_px, 0, H);
    double path_top = mean_rows(path_px, 0, H / 8), whitted_top = mean_rows(whitted_px, 0, H / 8);
    print_message("window_room: mean radiance %.4f path, %.4f whitted; the ceiling's (top %d rows) %.4f path, "
                  "%.5f whitted\n", path_all, whitted_all, H / 8, path_top, whitted_top);
    assert_true(whitted_all > 0);
    if (!(path_all > whitted_all && path_top > 4 * whitted_top))
        fail_msg("the path integrator adds too little light: whole frame %.4f (whitted %.4f), ceiling %.4f "
                 "(whitted %.5f)", path_all, whitted_all, path_top, whitted_top);
    free(path_px);
    free(whitted_px);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shipped_environment_scene_renders_its_sky),
        cmocka_unit_test(bad_files_are_refused),
        cmocka_unit_test(bad_keys_are_refused),
        cmocka_unit_test(png_environment_loads),
        cmocka_unit_test(window_room_is_lit_through_its_window),
    };
    return cmocka_run_group_tests_name("scenefile_environment", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
