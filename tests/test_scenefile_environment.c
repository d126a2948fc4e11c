/* "settings.environment" of a JSON scene: a Radiance .hdr (stb_image) or a PNG around the scene.
 * The shipped environment.json loads and renders its sky where rays meet nothing, the same on the
 * CPU and the GPU; a truncated .hdr, a file of another kind and a missing one are refused with the
 * file and the reason; bad keys are refused by path. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shipped_environment_scene_renders_its_sky),
        cmocka_unit_test(bad_files_are_refused),
        cmocka_unit_test(bad_keys_are_refused),
        cmocka_unit_test(png_environment_loads),
    };
    return cmocka_run_group_tests_name("scenefile_environment", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
