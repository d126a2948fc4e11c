/* The viewer's pure rules (src/cli/view_resolution.c, view_camera.c): the moving resolution chosen
 * from a frame's time, and camera moves that never give a camera the scene refuses. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "cli/view_camera.h"
#include "cli/view_resolution.h"

/* A frame at 1/3 size that took 18 ms: the full frame would take 162 ms, 1/2 size 40.5 ms. */
static void resolution_follows_the_pixels(void **state)
{
    (void)state;
    /* Nothing measured before: every other divisor is estimated by its pixels. */
    view_resolution r[6];
    memset(r, 0, sizeof r);
    assert_int_equal(view_resolution_next(&r[0], 3, 18.0, 33.0), 3);
    assert_int_equal(view_resolution_next(&r[1], 3, 18.0, 50.0), 3);  /* 40.5 > 0.8 x 50: not finer yet */
    assert_int_equal(view_resolution_next(&r[2], 1, 162.0, 50.0), 2); /* 40.5 <= 50 */
    assert_int_equal(view_resolution_next(&r[3], 1, 10.0, 33.0), 1);
    assert_int_equal(view_resolution_next(&r[4], 4, 1.0, 33.0), 1);   /* 16 ms full: back to full size */
    assert_int_equal(view_resolution_next(&r[5], 1, 1000.0, 33.0), 4); /* too slow for any: the coarsest */
    assert_int_equal(view_resolution_side(640, 3), 214);
    assert_int_equal(view_resolution_side(1, 4), 1);
}

/* A frame's fixed cost makes a half-size frame take more than a quarter of a full one: from 10.4 ms
 * at half size the pixel rule guesses 41.6 ms for the full frame, over the target, though it takes
 * 21.9 (paper_earth_shadow at 640x480 on llvmpipe). The rule measures it after VIEW_PROBE_FRAMES
 * frames, and keeps the full size once it has. A probe that is too slow goes back. */
static void resolution_probes_a_finer_one(void **state)
{
    (void)state;
    view_resolution r;
    memset(&r, 0, sizeof r);
    int d = view_resolution_next(&r, 1, 89.9, 33.0); /* the first moving frame, slow */
    assert_int_equal(d, 2);
    for (int i = 1; i < VIEW_PROBE_FRAMES; i++)
        assert_int_equal(d = view_resolution_next(&r, d, 10.4, 33.0), 2);
    assert_int_equal(d = view_resolution_next(&r, d, 10.4, 33.0), 1); /* the probe */
    assert_int_equal(d = view_resolution_next(&r, d, 21.9, 33.0), 1); /* measured: within the target */
    assert_int_equal(d = view_resolution_next(&r, d, 23.0, 33.0), 1);

    memset(&r, 0, sizeof r);
    d = view_resolution_next(&r, 1, 60.0, 33.0);
    assert_int_equal(d, 2);
    for (int i = 0; i < VIEW_PROBE_FRAMES; i++)
        d = view_resolution_next(&r, d, 15.0, 33.0);
    assert_int_equal(d, 1);                                           /* the probe */
    assert_int_equal(d = view_resolution_next(&r, d, 58.0, 33.0), 2); /* too slow: back */
}

/* Orbiting far past the pole stops short of it; the camera stays one the scene takes. */
static void orbit_stops_short_of_the_poles(void **state)
{
    (void)state;
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    bg_camera c = bg_camera_init();
    for (int i = 0; i < 50; i++) {
        view_camera_orbit(&c, 37, -400, 480);
        assert_int_equal(bg_scene_set_camera(scene, &c), BG_OK);
    }
    view_camera_pan(&c, 30, -20, 480);
    view_camera_dolly(&c, 500);
    assert_int_equal(bg_scene_set_camera(scene, &c), BG_OK);
    bg_scene_destroy(scene);
}

/* F: the bounds' centre is looked at, from the direction the camera had. */
static void frame_keeps_the_direction(void **state)
{
    (void)state;
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0, 0, 10);
    c.look_at = bg_vec3_make(0, 0, 0);
    bg_scenefile_summary s = {0};
    s.bounded = true;
    s.bounds_min = bg_vec3_make(4, -1, -1);
    s.bounds_max = bg_vec3_make(6, 1, 1);
    assert_true(view_camera_frame(&c, &s, 4.0 / 3.0));
    assert_true(fabs(c.look_at.x - 5) < 1e-12 && fabs(c.look_at.y) < 1e-12);
    assert_true(fabs(c.position.x - 5) < 1e-12 && c.position.z > 1);
    s.bounded = false;
    assert_false(view_camera_frame(&c, &s, 1.0));
}

/* An orthographic camera: the wheel narrows the view (moving a parallel view would change nothing
 * it shows), a pan moves by the view's own height per window height, and F fits the bounds into
 * the half-sides with the view plane in front of them. */
static void orthographic_view_zooms_pans_and_frames(void **state)
{
    (void)state;
    bg_camera c = bg_camera_init();
    c.position = bg_vec3_make(0, 0, 10);
    c.look_at = bg_vec3_make(0, 0, 0);
    c.projection = BG_PROJECTION_ORTHOGRAPHIC;
    c.half_height = 2.0;
    view_camera_dolly(&c, 1);
    assert_true(fabs(c.half_height - 1.8) < 1e-12);
    assert_true(c.position.z == 10.0);
    view_camera_pan(&c, 0, 240, 480); /* half the window up: the view moves by its half-height */
    assert_true(fabs(c.position.y - 1.8) < 1e-12 && fabs(c.look_at.y - 1.8) < 1e-12);
    bg_scenefile_summary s = {0};
    s.bounded = true;
    s.bounds_min = bg_vec3_make(-3, -4, 0);
    s.bounds_max = bg_vec3_make(3, 4, 0); /* radius 5 */
    assert_true(view_camera_frame(&c, &s, 0.5));
    assert_true(fabs(c.half_height - 1.05 * 5 / 0.5) < 1e-12);
    assert_true(fabs(c.position.z - 10.0) < 1e-9 && fabs(c.look_at.z) < 1e-12);
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    view_camera_dolly(&c, -100000);
    assert_int_equal(bg_scene_set_camera(scene, &c), BG_OK);
    view_camera_dolly(&c, 100000);
    assert_int_equal(bg_scene_set_camera(scene, &c), BG_OK);
    bg_scene_destroy(scene);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(resolution_follows_the_pixels),
        cmocka_unit_test(resolution_probes_a_finer_one),
        cmocka_unit_test(orbit_stops_short_of_the_poles),
        cmocka_unit_test(frame_keeps_the_direction),
        cmocka_unit_test(orthographic_view_zooms_pans_and_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
