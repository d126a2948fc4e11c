/* Betelgeuse GPU smoke subset, run on every backend and driver (OSMesa and EGL surfaceless,
 * llvmpipe and softpipe): the paper's two scenes at 96x96 against the CPU reference, within the
 * thresholds test_bg_gpu_scenes uses (gpu_thresholds.h), with finite float output. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "gpu_thresholds.h"
#include "scenes/image_metrics.h"
#include "scenes/scenes.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 96, H = 96 };

static void check_scene(macs_headless *h, scene_id id)
{
    const char *name = scenes_name(id);
    macs_context *ctx = util_context(h, NULL);
    bg_renderer *r = util_renderer(ctx);
    bg_scene *s = util_scene(id);

    static unsigned char cpu[W * H * 4], gpu[W * H * 4];
    static float gpuf[W * H * 4];
    bg_image ci = {W, H, BG_PIXEL_RGBA8, 0, cpu}, gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
    bg_image fi = {W, H, BG_PIXEL_RGBA32F, 0, gpuf};
    bg_render_settings set = bg_render_settings_init();
    assert_int_equal(bg_render_cpu(s, &set, &ci), BG_OK);
    bg_status st = bg_render_gpu(r, s, &set, &gi);
    if (st != BG_OK)
        fail_msg("%s: %s: %s", name, bg_status_string(st), bg_renderer_error_message(r));

    image_metrics m;
    assert_true(image_metrics_compare(&ci, &gi, GPU_SILHOUETTE_THRESHOLD, &m));
    char line[512], why[256];
    macs_gl_info info;
    macs_context_get_gl_info(ctx, &info);
    print_message("%-19s %s: %s\n", name, info.renderer ? info.renderer : "?",
                  image_metrics_format(&m, line, sizeof line));
    if (!gpu_threshold_check(gpu_threshold_of(id), &m, why, sizeof why))
        fail_msg("%s: %s", name, why);

    assert_int_equal(bg_render_gpu(r, s, &set, &fi), BG_OK);
    size_t bad = image_metrics_count_nonfinite(&fi);
    if (bad != 0)
        fail_msg("%s: %zu non-finite values in the RGBA32F output", name, bad);

    bg_scene_destroy(s);
    bg_renderer_destroy(r);
    macs_context_destroy(ctx);
}

static void paper_earth(void **state)
{
    check_scene(*state, SCENE_PAPER_EARTH);
}

static void paper_earth_shadow(void **state)
{
    check_scene(*state, SCENE_PAPER_EARTH_SHADOW);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(paper_earth),
        cmocka_unit_test(paper_earth_shadow),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
