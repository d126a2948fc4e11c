/* Cameras at the edges of their ranges. A thin lens focused 1e20 ahead renders on the GPU as on the
 * CPU (the direction through the lens overflowed in float: a black frame). The orthographic camera
 * (bg_camera.projection, docs/shading.md 1.5): parallel rays from the view's rectangle. On the CPU reference two equal spheres at different depths are drawn the same size
 * (they are not under the perspective camera); every GPU plan draws the shared scenes through it as
 * the CPU does, within the scenes' usual bounds, and a window of the frame is the frame's pixels;
 * a lens, a zero or huge half_height and an unknown projection are refused by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"
#include "util_gpu.h"

enum { W = 96, H = 72 };

static bg_camera orthographic_camera(double half_height)
{
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(2.0, 3.0, 9.0);
    c.look_at = bg_vec3_make(0.0, 0.5, 0.0);
    c.projection = BG_PROJECTION_ORTHOGRAPHIC;
    c.half_height = half_height;
    return c;
}

/* Lit pixels in columns [x0, x1) of an RGBA8 image (any channel above 8). */
static int lit_in_columns(const unsigned char *px, int x0, int x1)
{
    int n = 0;
    for (int y = 0; y < H; y++)
        for (int x = x0; x < x1; x++) {
            const unsigned char *p = px + ((size_t)y * W + (size_t)x) * 4;
            n += p[0] > 8 || p[1] > 8 || p[2] > 8;
        }
    return n;
}

/* Two unit spheres, one 6 units behind the other and beside it, seen along -z: parallel rays draw
 * them the same size (to a pixel's rounding), the perspective camera the nearer one larger. */
static void parallel_rays_keep_sizes_at_every_depth(void **state)
{
    (void)state;
    int left[2], right[2];
    for (int projection = 0; projection < 2; projection++) {
        bg_scene *s = NULL;
        assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
        bg_material m = bg_material_init();
        m.ambient = (bg_color_param){1, 1, 1, 0};
        uint32_t mat, a, b, l;
        assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(-1.6, 0, 0), 1.0, mat, &a), BG_OK);
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(1.6, 0, -6), 1.0, mat, &b), BG_OK);
        bg_light light = bg_light_init();
        light.position = bg_vec3_make(0, 5, 10);
        assert_int_equal(bg_scene_add_light(s, &light, &l), BG_OK);
        bg_camera c = bg_camera_init();
        c.position = bg_vec3_make(0, 0, 8);
        c.look_at = bg_vec3_make(0, 0, 0);
        c.fov_y_degrees = 30.0;
        if (projection) {
            c.projection = BG_PROJECTION_ORTHOGRAPHIC;
            c.half_height = 2.0;
        }
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        bg_render_settings set = bg_render_settings_init();
        unsigned char *px = util_cpu_reference(s, &set, W, H);
        left[projection] = lit_in_columns(px, 0, W / 2);
        right[projection] = lit_in_columns(px, W / 2, W);
        free(px);
        bg_scene_destroy(s);
    }
    print_message("perspective: near %d, far %d pixels; orthographic: near %d, far %d pixels\n", left[0], right[0],
                  left[1], right[1]);
    assert_true(left[0] > 2 * right[0]);
    /* A disc of radius r pixels covers about pi r^2: the two differ by rounding along the rim only. */
    assert_true(abs(left[1] - right[1]) <= left[1] / 20);
    assert_true(left[1] > 400);
}

/* Every shared scene through the orthographic camera: each plan against the CPU reference, within
 * the scene's row of the shared table. */
static void every_plan_follows_the_cpu(void **state)
{
    (void)state;
    static const scene_id scenes[] = {SCENE_PAPER_EARTH_SHADOW, SCENE_GLASS, SCENE_MANY_SPHERES, SCENE_ALL_PRIMITIVES};
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_FUSED_TREE, BG_PLAN_MULTIPASS};
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        bg_scene *s = util_scene(scenes[i]);
        bg_camera c = orthographic_camera(3.0);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        bg_render_settings set = bg_render_settings_init();
        unsigned char *cpu = util_cpu_reference(s, &set, W, H);
        for (size_t p = 0; p < sizeof plans / sizeof plans[0]; p++) {
            char label[96];
            snprintf(label, sizeof label, "%s, orthographic, plan %d", scenes_name(scenes[i]), (int)plans[p]);
            unsigned char *gpu = util_gpu_plan_image(s, &set, plans[p], W, H, label);
            bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
            util_expect_near(cpu, &gi, scenes[i], label);
            free(gpu);
        }
        free(cpu);
        bg_scene_destroy(s);
    }
}

/* A window of the orthographic frame renders the frame's own pixels there (the rays of a window are
 * the frame's: each pixel's place on the view rectangle comes from its frame coordinates). */
static void a_window_is_the_frames_pixels(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_ALL_PRIMITIVES);
    bg_camera c = orthographic_camera(2.5);
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    bg_render_settings set = bg_render_settings_init();
    unsigned char *full = util_gpu_plan_image(s, &set, BG_PLAN_MULTIPASS, W, H, "full frame");
    enum { X0 = 20, Y0 = 10, WW = 40, WH = 30 };
    set.frame_width = W;
    set.frame_height = H;
    set.window_x = X0;
    set.window_y = Y0;
    unsigned char *win = util_gpu_plan_image(s, &set, BG_PLAN_MULTIPASS, WW, WH, "window");
    /* The same program over the same frame coordinates: the bytes agree on any driver. */
    for (int y = 0; y < WH; y++)
        if (memcmp(win + (size_t)y * WW * 4, full + ((size_t)(Y0 + y) * W + X0) * 4, (size_t)WW * 4) != 0)
            fail_msg("window row %d differs from frame row %d", y, Y0 + y);
    free(win);
    free(full);
    bg_scene_destroy(s);
}

static void bad_orthographic_cameras_are_refused(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_camera c = orthographic_camera(2.0);
    c.aperture_radius = 0.1;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_ERR_INVALID_ARGUMENT);
    print_message("%s\n", bg_scene_error_message(s));
    assert_non_null(strstr(bg_scene_error_message(s), "depth of field needs a perspective camera"));
    static const double halves[] = {0.0, -1.0, 1e101};
    for (size_t i = 0; i < sizeof halves / sizeof halves[0]; i++) {
        c = orthographic_camera(halves[i]);
        bg_scene_clear_error(s);
        assert_int_equal(bg_scene_set_camera(s, &c), BG_ERR_INVALID_ARGUMENT);
        assert_non_null(strstr(bg_scene_error_message(s), "half_height"));
    }
    c = orthographic_camera(2.0);
    c.projection = (bg_projection)7;
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_set_camera(s, &c), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "projection = 7"));
    /* A perspective camera ignores half_height, whatever it holds. */
    c = bg_camera_init();
    c.half_height = 0.0;
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    bg_scene_destroy(s);
}

/* Aperture 0.2 focused 1e20 ahead (effectively at infinity): every plan as the CPU, 4 samples. */
static void a_lens_focused_far_away_renders(void **state)
{
    (void)state;
    bg_scene *s = util_scene(SCENE_PAPER_EARTH_SHADOW);
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0.0, 1.0, 6.0);
    c.look_at = bg_vec3_make(0.0, 0.5, 0.0);
    c.aperture_radius = 0.2;
    c.focus_distance = 1e20;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    bg_render_settings set = bg_render_settings_init();
    set.samples = 4;
    unsigned char *cpu = util_cpu_reference(s, &set, W, H);
    long sum = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++)
        sum += cpu[i];
    assert_true(sum > (long)W * H * 4 * 10); /* the scene is there, not black */
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
    for (size_t p = 0; p < sizeof plans / sizeof plans[0]; p++) {
        char label[64];
        snprintf(label, sizeof label, "focus 1e20, plan %d", (int)plans[p]);
        unsigned char *gpu = util_gpu_plan_image(s, &set, plans[p], W, H, label);
        bg_image gi = {W, H, BG_PIXEL_RGBA8, 0, gpu};
        util_expect_near(cpu, &gi, SCENE_PAPER_EARTH_SHADOW, label);
        free(gpu);
    }
    free(cpu);
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_lens_focused_far_away_renders),
        cmocka_unit_test(parallel_rays_keep_sizes_at_every_depth),
        cmocka_unit_test(every_plan_follows_the_cpu),
        cmocka_unit_test(a_window_is_the_frames_pixels),
        cmocka_unit_test(bad_orthographic_cameras_are_refused),
    };
    return cmocka_run_group_tests(tests, util_gpu_group_setup, util_gpu_group_teardown);
}
