/* Test helpers for the GPU threshold tables (util_thresholds.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/common/encoding.h"
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

/* An RGBA32F image as bg_render_gpu's RGBA8 output encodes it (sRGB, opaque). */
static unsigned char *encoded(const float *px, int width, int height)
{
    size_t n = (size_t)width * (size_t)height;
    unsigned char *out = malloc(n * 4);
    assert_non_null(out);
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++)
            out[i * 4 + c] = bgi_encode_channel(px[i * 4 + c], BG_ENCODING_SRGB);
        out[i * 4 + 3] = 255;
    }
    return out;
}

void util_expect_gpu_twins(const float *a, const float *b, int width, int height, const gpu_threshold *row,
                           const char *label)
{
    if (memcmp(a, b, (size_t)width * (size_t)height * 4 * sizeof(float)) == 0)
        return;
    unsigned char *ea = encoded(a, width, height), *eb = encoded(b, width, height);
    bg_image ia = {width, height, BG_PIXEL_RGBA8, 0, ea}, ib = {width, height, BG_PIXEL_RGBA8, 0, eb};
    image_metrics m;
    char why[256], line[512];
    assert_true(image_metrics_compare(&ia, &ib, GPU_SILHOUETTE_THRESHOLD, &m));
    print_message("%s: not bit-equal; %s\n", label, image_metrics_format(&m, line, sizeof line));
    if (!gpu_threshold_check(row, &m, why, sizeof why))
        fail_msg("%s: two GPU programs of the same formulas differ beyond the error model: %s", label, why);
    free(ea);
    free(eb);
}
