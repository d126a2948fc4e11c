/* Test helpers for the GPU threshold tables (util_thresholds.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/scene/scene_internal.h"
#include "util_gpu.h"
#include "util_thresholds.h"

void util_thresholds_catch_half_pixel_offset(const gpu_threshold table[SCENE_COUNT], int width, int height,
                                             const char *what)
{
    unsigned char *a = malloc((size_t)width * height * 4), *b = malloc((size_t)width * height * 4);
    assert_non_null(a);
    assert_non_null(b);
    for (int id = 0; id < SCENE_COUNT; id++) {
        assert_int_equal(table[id].scene, id);
        bg_scene *s = util_scene((scene_id)id);
        bg_render_settings set = bg_render_settings_init();
        bg_image ai = {width, height, BG_PIXEL_RGBA8, 0, a}, bi = {width, height, BG_PIXEL_RGBA8, 0, b};
        assert_int_equal(bg_render_cpu(s, &set, &ai), BG_OK);
        const bg_camera_data *cd = &bgi_scene_committed(s)->camera;
        bg_camera cam = cd->camera;
        double dx = cam.look_at.x - cam.position.x, dy = cam.look_at.y - cam.position.y,
               dz = cam.look_at.z - cam.position.z;
        double shift = sqrt(dx * dx + dy * dy + dz * dz) * cd->half_y * 2.0 / height * 0.5;
        cam.look_at.x += cd->right[0] * shift;
        cam.look_at.y += cd->right[1] * shift;
        cam.look_at.z += cd->right[2] * shift;
        assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        assert_int_equal(bg_render_cpu(s, &set, &bi), BG_OK);
        image_metrics m;
        char why[256], line[512];
        assert_true(image_metrics_compare(&ai, &bi, GPU_SILHOUETTE_THRESHOLD, &m));
        if (gpu_threshold_check(&table[id], &m, why, sizeof why))
            fail_msg("%s: a half-pixel offset passes %s: %s", scenes_name((scene_id)id), what,
                     image_metrics_format(&m, line, sizeof line));
        bg_scene_destroy(s);
    }
    free(a);
    free(b);
}
