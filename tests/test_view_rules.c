/* The viewer's pure rules (src/cli/view_resolution.c, view_camera.c): the moving resolution chosen
 * from a frame's time, and camera moves that never give a camera the scene refuses. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "cli/view_camera.h"
#include "cli/view_resolution.h"

/* A frame at 1/3 size that took 18 ms: the full frame would take 162 ms, 1/2 size 40.5 ms. */
static void resolution_follows_the_pixels(void **state)
{
    (void)state;
    assert_int_equal(view_resolution_next(3, 18.0, 33.0), 3);
    assert_int_equal(view_resolution_next(3, 18.0, 50.0), 3);  /* 40.5 > 0.8 x 50: not finer yet */
    assert_int_equal(view_resolution_next(1, 162.0, 50.0), 2); /* 40.5 <= 50 */
    assert_int_equal(view_resolution_next(1, 10.0, 33.0), 1);
    assert_int_equal(view_resolution_next(4, 1.0, 33.0), 1);   /* 16 ms full: back to full size */
    assert_int_equal(view_resolution_next(1, 1000.0, 33.0), 4); /* too slow for any: the coarsest */
    assert_int_equal(view_resolution_side(640, 3), 214);
    assert_int_equal(view_resolution_side(1, 4), 1);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(resolution_follows_the_pixels),
        cmocka_unit_test(orbit_stops_short_of_the_poles),
        cmocka_unit_test(frame_keeps_the_direction),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
