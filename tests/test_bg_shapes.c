/* Each prototype's intersection, normal and UV against hand-computed values (docs/shading.md
 * sections 2-4), including grazing rays, rays starting inside, rays parallel to a face, and
 * transformed instances. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/cpu/cpu_internal.h"

#define EPS 1e-12

static void near(double got, double want, double tol)
{
    if (!(fabs(got - want) <= tol))
        fail_msg("got %.17g, want %.17g (tol %g)", got, want, tol);
}

static void near3(const double got[3], double x, double y, double z, double tol)
{
    near(got[0], x, tol);
    near(got[1], y, tol);
    near(got[2], z, tol);
}

static bg_cpu_span proto(bg_shape shape, double ox, double oy, double oz, double dx, double dy, double dz)
{
    const double o[3] = {ox, oy, oz}, d[3] = {dx, dy, dz};
    bg_cpu_span s;
    bgi_cpu_intersect_prototype(shape, o, d, &s);
    return s;
}

static void test_sphere_head_on(void **state)
{
    (void)state;
    bg_cpu_span s = proto(BG_SHAPE_SPHERE, 0, 0, 5, 0, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[0], 4.0, EPS);
    near(s.t[1], 6.0, EPS);
    near3(s.normal[0], 0, 0, 1, EPS);
    near3(s.normal[1], 0, 0, -1, EPS);
}

static void test_sphere_unnormalised_direction(void **state)
{
    (void)state;
    /* t stays the parameter of the unnormalised ray: o + t d with |d| = 2 */
    bg_cpu_span s = proto(BG_SHAPE_SPHERE, 0, 0, 5, 0, 0, -2);
    assert_int_equal(s.count, 2);
    near(s.t[0], 2.0, EPS);
    near(s.t[1], 3.0, EPS);
}

static void test_sphere_inside_and_graze(void **state)
{
    (void)state;
    bg_cpu_span s = proto(BG_SHAPE_SPHERE, 0, 0, 0, 1, 0, 0);
    assert_int_equal(s.count, 2);
    near(s.t[0], -1.0, EPS);
    near(s.t[1], 1.0, EPS);
    /* tangent: x = 1 touches at z = 0 */
    s = proto(BG_SHAPE_SPHERE, 1, 0, 5, 0, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[0], 5.0, 1e-6);
    near(s.t[1], 5.0, 1e-6);
    s = proto(BG_SHAPE_SPHERE, 1.0 + 1e-9, 0, 5, 0, 0, -1);
    assert_int_equal(s.count, 0);
    /* far away and nearly tangent: the stable discriminant still finds the chord
     * 2 sqrt(1 - 0.6^2) = 1.6 around t = 1e6 */
    s = proto(BG_SHAPE_SPHERE, 0.6, 0, 1e6, 0, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[1] - s.t[0], 1.6, 1e-9);
}

static void test_box(void **state)
{
    (void)state;
    bg_cpu_span s = proto(BG_SHAPE_BOX, 0, 0, 5, 0, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[0], 4.0, EPS);
    near(s.t[1], 6.0, EPS);
    near3(s.normal[0], 0, 0, 1, 0);
    near3(s.normal[1], 0, 0, -1, 0);
    /* inside */
    s = proto(BG_SHAPE_BOX, 0.5, 0, 0, -1, 0, 0);
    assert_int_equal(s.count, 2);
    near(s.t[0], -0.5, EPS);
    near(s.t[1], 1.5, EPS);
    near3(s.normal[1], -1, 0, 0, 0);
    /* parallel to the top face and in its plane: still inside the y slab */
    s = proto(BG_SHAPE_BOX, 0, 1, 5, 0, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[0], 4.0, EPS);
    /* parallel just above it: miss */
    s = proto(BG_SHAPE_BOX, 0, 1.0 + 1e-12, 5, 0, 0, -1);
    assert_int_equal(s.count, 0);
    /* diagonal through the edge region: enters through x = -1 at t = 1 (o = (-2, -0.5, 0), d = (1, 1, 0)) */
    s = proto(BG_SHAPE_BOX, -2, -0.5, 0, 1, 1, 0);
    assert_int_equal(s.count, 2);
    near(s.t[0], 1.0, EPS);
    near(s.t[1], 1.5, EPS);
    near3(s.normal[0], -1, 0, 0, 0);
    near3(s.normal[1], 0, 1, 0, 0);
    /* a tiny but non-zero component must not overflow or miss */
    s = proto(BG_SHAPE_BOX, 0, 0, 5, 1e-310, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[0], 4.0, EPS);
}

static void test_plane_and_rectangle(void **state)
{
    (void)state;
    bg_cpu_span s = proto(BG_SHAPE_PLANE, 3, 2, 1, 0, -1, 0);
    assert_int_equal(s.count, 1);
    near(s.t[0], 2.0, EPS);
    near3(s.normal[0], 0, 1, 0, 0);
    /* parallel: no hit, no division */
    s = proto(BG_SHAPE_PLANE, 0, 1, 0, 1, 0, 0);
    assert_int_equal(s.count, 0);
    s = proto(BG_SHAPE_PLANE, 0, 1, 0, 1, 1e-14, 0);
    assert_int_equal(s.count, 0);
    /* from below */
    s = proto(BG_SHAPE_PLANE, 0, -1, 0, 0, 0.5, 0);
    assert_int_equal(s.count, 1);
    near(s.t[0], 2.0, EPS);
    s = proto(BG_SHAPE_RECTANGLE, 0.5, 1, -0.5, 0, -1, 0);
    assert_int_equal(s.count, 1);
    near(s.t[0], 1.0, EPS);
    s = proto(BG_SHAPE_RECTANGLE, 1.5, 1, 0, 0, -1, 0);
    assert_int_equal(s.count, 0);
}

static void test_cylinder(void **state)
{
    (void)state;
    bg_cpu_span s = proto(BG_SHAPE_CYLINDER, 0, 0, 5, 0, 0, -1);
    assert_int_equal(s.count, 2);
    near(s.t[0], 4.0, EPS);
    near(s.t[1], 6.0, EPS);
    near3(s.normal[0], 0, 0, 1, EPS);
    near3(s.normal[1], 0, 0, -1, EPS);
    /* down the axis: both caps */
    s = proto(BG_SHAPE_CYLINDER, 0, 5, 0, 0, -1, 0);
    assert_int_equal(s.count, 2);
    near(s.t[0], 4.0, EPS);
    near(s.t[1], 6.0, EPS);
    near3(s.normal[0], 0, 1, 0, 0);
    near3(s.normal[1], 0, -1, 0, 0);
    /* parallel to the axis outside the side */
    s = proto(BG_SHAPE_CYLINDER, 2, 5, 0, 0, -1, 0);
    assert_int_equal(s.count, 0);
    /* through the top cap, out of the side: o = (0, 2.5, 0), d = (1, -2, 0) */
    s = proto(BG_SHAPE_CYLINDER, 0, 2.5, 0, 1, -2, 0);
    assert_int_equal(s.count, 2);
    near(s.t[0], 0.75, EPS);
    near(s.t[1], 1.0, EPS);
    near3(s.normal[0], 0, 1, 0, 0);
    near3(s.normal[1], 1, 0, 0, EPS);
    /* passing above the top cap */
    s = proto(BG_SHAPE_CYLINDER, -5, 1.5, 0, 1, 0, 0);
    assert_int_equal(s.count, 0);
}

static void test_uv_maps(void **state)
{
    (void)state;
    double uv[2], dpdu[3];
    const double front[3] = {0, 0, 1};
    bgi_cpu_uv_map(BG_UV_SPHERICAL, front, uv, dpdu);
    near(uv[0], 0.5, EPS);
    near(uv[1], 0.5, EPS);
    near3(dpdu, 1, 0, 0, EPS);
    const double east[3] = {1, 0, 0};
    bgi_cpu_uv_map(BG_UV_SPHERICAL, east, uv, dpdu);
    near(uv[0], 0.75, EPS);
    const double lat45[3] = {0, sqrt(0.5), sqrt(0.5)};
    bgi_cpu_uv_map(BG_UV_SPHERICAL, lat45, uv, dpdu);
    near(uv[1], 0.75, EPS);
    /* the seam: just east of -z is u = 1, just west is u = 0 */
    const double seam_e[3] = {1e-12, 0, -1}, seam_w[3] = {-1e-12, 0, -1};
    bgi_cpu_uv_map(BG_UV_SPHERICAL, seam_e, uv, dpdu);
    near(uv[0], 1.0, 1e-9);
    bgi_cpu_uv_map(BG_UV_SPHERICAL, seam_w, uv, dpdu);
    near(uv[0], 0.0, 1e-9);
    /* pole: guarded atan2(0, 0) */
    const double pole[3] = {0, 1, 0};
    bgi_cpu_uv_map(BG_UV_SPHERICAL, pole, uv, dpdu);
    near(uv[0], 0.5, 0);
    near(uv[1], 1.0, EPS);
    near3(dpdu, 0, 0, 0, 0);

    const double pp[3] = {0.5, 0, -0.5};
    bgi_cpu_uv_map(BG_UV_PLANAR, pp, uv, dpdu);
    near(uv[0], 0.75, EPS);
    near(uv[1], 0.75, EPS);
    near3(dpdu, 1, 0, 0, 0);

    const double bx[3] = {-1, 0.5, 0.2};
    bgi_cpu_uv_map(BG_UV_BOX, bx, uv, dpdu);
    near(uv[0], 0.6, EPS);
    near(uv[1], 0.75, EPS);
    near3(dpdu, 0, 0, 1, 0);
    const double bz[3] = {0.5, -0.5, -1};
    bgi_cpu_uv_map(BG_UV_BOX, bz, uv, dpdu);
    near(uv[0], 0.25, EPS);
    near(uv[1], 0.25, EPS);
    near3(dpdu, -1, 0, 0, 0);

    const double side[3] = {1, 0.5, 0};
    bgi_cpu_uv_map(BG_UV_CYLINDRICAL, side, uv, dpdu);
    near(uv[0], 0.75, EPS);
    near(uv[1], 0.75, EPS);
    near3(dpdu, 0, 0, -1, EPS);
    const double cap[3] = {0.5, 1, -0.5};
    bgi_cpu_uv_map(BG_UV_CYLINDRICAL, cap, uv, dpdu);
    near(uv[0], 0.75, EPS);
    near(uv[1], 0.75, EPS);
    const double cap_low[3] = {0.5, -1, -0.5};
    bgi_cpu_uv_map(BG_UV_CYLINDRICAL, cap_low, uv, dpdu);
    near(uv[1], 0.25, EPS);
}

/* A committed one-object scene; the test reads its object data. */
static bg_scene *one_object(const bg_object_desc *desc)
{
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat = 0, obj = 0;
    assert_int_equal(bg_scene_add_material(scene, &m, &mat), BG_OK);
    bg_object_desc d = *desc;
    d.material = mat;
    assert_int_equal(bg_scene_add_object(scene, &d, &obj), BG_OK);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    return scene;
}

static bool hit_object(const bg_scene *scene, const double o[3], const double d[3], bool far_root, bg_cpu_hit *hit)
{
    const bg_scene_state *st = bgi_scene_committed(scene);
    assert_non_null(st);
    bg_cpu_candidate c;
    if (!bgi_cpu_intersect_object(&st->objects[0], o, d, far_root, 1e300, &c))
        return false;
    bgi_cpu_hit_attributes(&st->objects[0], 0, o, d, &c, hit);
    return true;
}

static void test_transformed_sphere(void **state)
{
    (void)state;
    bg_object_desc desc = bg_object_desc_init(BG_SHAPE_SPHERE, 1);
    desc.transform = bg_mat4_mul(bg_mat4_translate(1, 2, 3), bg_mat4_scale(2, 2, 2));
    desc.uv_scale[0] = 2.0;
    bg_scene *scene = one_object(&desc);
    const double o[3] = {1, 2, 10}, d[3] = {0, 0, -1};
    bg_cpu_hit hit;
    assert_true(hit_object(scene, o, d, false, &hit));
    near(hit.t, 5.0, EPS);
    near3(hit.position, 1, 2, 5, EPS);
    near3(hit.normal, 0, 0, 1, EPS);
    near3(hit.tangent, 1, 0, 0, EPS);
    assert_true(hit.entering);
    near(hit.uv[0], 1.0, EPS); /* 0.5 x uv_scale 2 */
    near(hit.uv[1], 0.5, EPS);
    /* the far root: the exit point, normal flipped to face the ray, leaving */
    assert_true(hit_object(scene, o, d, true, &hit));
    near(hit.t, 9.0, EPS);
    near3(hit.normal, 0, 0, 1, EPS);
    assert_false(hit.entering);
    /* starting inside takes the exit root */
    const double inside[3] = {1, 2, 3};
    assert_true(hit_object(scene, inside, d, false, &hit));
    near(hit.t, 2.0, EPS);
    assert_false(hit.entering);
    /* a ray that starts on the far side going away misses */
    const double away[3] = {1, 2, -10};
    assert_false(hit_object(scene, away, d, false, &hit));
    bg_scene_destroy(scene);
}

static void test_transformed_box(void **state)
{
    (void)state;
    /* scale x by 3, rotate +90 degrees about y (x -> -z), move to z = -5: spans z in [-8, -2] */
    bg_object_desc desc = bg_object_desc_init(BG_SHAPE_BOX, 1);
    desc.transform = bg_mat4_mul(bg_mat4_translate(0, 0, -5),
                                 bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 90.0), bg_mat4_scale(3, 1, 1)));
    bg_scene *scene = one_object(&desc);
    const double o[3] = {0, 0, 0}, d[3] = {0, 0, -1};
    bg_cpu_hit hit;
    assert_true(hit_object(scene, o, d, false, &hit));
    near(hit.t, 2.0, 1e-12);
    near3(hit.normal, 0, 0, 1, 1e-12);
    /* the prototype's -x face at its centre: u = (1 + z) / 2 = 0.5, v = 0.5; dP/du = +z -> world +x */
    near(hit.uv[0], 0.5, 1e-12);
    near(hit.uv[1], 0.5, 1e-12);
    near3(hit.tangent, 1, 0, 0, 1e-12);
    assert_true(hit_object(scene, o, d, true, &hit));
    near(hit.t, 8.0, 1e-12);
    bg_scene_destroy(scene);
}

static void test_transformed_plane_both_sides(void **state)
{
    (void)state;
    bg_scene *scene = NULL;
    assert_int_equal(bg_scene_create(NULL, &scene), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat = 0, obj = 0;
    assert_int_equal(bg_scene_add_material(scene, &m, &mat), BG_OK);
    assert_int_equal(bg_scene_add_plane(scene, bg_vec3_make(0, 0, -4), bg_vec3_make(0, 0, 1), mat, &obj), BG_OK);
    assert_int_equal(bg_scene_commit(scene), BG_OK);
    bg_cpu_hit hit;
    const double o[3] = {0, 0, 0}, d[3] = {0, 0, -1};
    assert_true(hit_object(scene, o, d, false, &hit));
    near(hit.t, 4.0, EPS);
    near3(hit.normal, 0, 0, 1, EPS);
    assert_true(hit.entering);
    const double back[3] = {0, 0, -8}, up[3] = {0, 0, 1};
    assert_true(hit_object(scene, back, up, false, &hit));
    near(hit.t, 4.0, EPS);
    near3(hit.normal, 0, 0, -1, EPS); /* flipped to face the ray */
    assert_false(hit.entering);
    /* grazing: parallel to the plane */
    const double side[3] = {1, 0, 0};
    assert_false(hit_object(scene, o, side, false, &hit));
    bg_scene_destroy(scene);
}

static void test_transformed_cylinder_and_rectangle(void **state)
{
    (void)state;
    /* a cylinder lying along x (rotate -90 about z: y -> x), radius 0.5, half-length 2 */
    bg_object_desc desc = bg_object_desc_init(BG_SHAPE_CYLINDER, 1);
    desc.transform = bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 0, 1), -90.0), bg_mat4_scale(0.5, 2, 0.5));
    bg_scene *scene = one_object(&desc);
    bg_cpu_hit hit;
    const double o[3] = {10, 0, 0}, d[3] = {-1, 0, 0};
    assert_true(hit_object(scene, o, d, false, &hit));
    near(hit.t, 8.0, 1e-12);
    near3(hit.normal, 1, 0, 0, 1e-12);
    const double o2[3] = {1, 0, 5}, d2[3] = {0, 0, -1};
    assert_true(hit_object(scene, o2, d2, false, &hit));
    near(hit.t, 4.5, 1e-12);
    near3(hit.normal, 0, 0, 1, 1e-12);
    bg_scene_destroy(scene);

    /* a rectangle standing up facing +z (rotate +90 about x: +y -> +z), 2 x 2 */
    desc = bg_object_desc_init(BG_SHAPE_RECTANGLE, 1);
    desc.transform = bg_mat4_mul(bg_mat4_translate(0, 0, -1), bg_mat4_rotate(bg_vec3_make(1, 0, 0), 90.0));
    scene = one_object(&desc);
    const double o3[3] = {0.5, 0.5, 3}, d3[3] = {0, 0, -1};
    assert_true(hit_object(scene, o3, d3, false, &hit));
    near(hit.t, 4.0, 1e-12);
    near3(hit.normal, 0, 0, 1, 1e-12);
    /* prototype point (0.5, 0, -0.5): u = 0.75, v = 0.75 */
    near(hit.uv[0], 0.75, 1e-12);
    near(hit.uv[1], 0.75, 1e-12);
    const double o4[3] = {1.5, 0, 3};
    assert_false(hit_object(scene, o4, d3, false, &hit));
    bg_scene_destroy(scene);
}

static void test_segment_blocked(void **state)
{
    (void)state;
    bg_object_desc desc = bg_object_desc_init(BG_SHAPE_SPHERE, 1);
    bg_scene *scene = one_object(&desc);
    const bg_scene_state *st = bgi_scene_committed(scene);
    const double o[3] = {0, 0, 5}, l[3] = {0, 0, -1};
    assert_true(bgi_cpu_segment_blocked(&st->objects[0], o, l, 10.0));
    assert_false(bgi_cpu_segment_blocked(&st->objects[0], o, l, 3.5)); /* ends before the sphere */
    const double up[3] = {0, 0, 1};
    assert_false(bgi_cpu_segment_blocked(&st->objects[0], o, up, 1e300)); /* behind the start */
    bg_scene_destroy(scene);
}

/* The segment is open at its light end by BG_SHADOW_END_REL of its length (docs/shading.md 2.8): a
 * light lying on a surface is not shadowed by that surface, whichever side of t_max rounding puts
 * the root, and the tolerance scales with the segment. Without the rule the ends just past the
 * root below would count as blocked. */
static void test_segment_open_at_light(void **state)
{
    (void)state;
    const double near_end = 1.0 + BG_SHADOW_END_REL / 4.0, before = 1.0 + BG_SHADOW_END_REL * 4.0;
    const double scales[3] = {1e-6, 1.0, 1e6};
    for (int k = 0; k < 3; k++) {
        double a = scales[k];
        bg_object_desc desc = bg_object_desc_init(BG_SHAPE_SPHERE, 1);
        desc.transform = bg_mat4_scale(a, a, a);
        bg_scene *scene = one_object(&desc);
        const bg_scene_state *st = bgi_scene_committed(scene);
        const double o[3] = {0, 0, 5 * a}, l[3] = {0, 0, -1};
        /* The sphere's near root is 4a. */
        assert_false(bgi_cpu_segment_blocked(&st->objects[0], o, l, 4 * a * near_end));
        assert_false(bgi_cpu_segment_blocked(&st->objects[0], o, l, 4 * a));
        assert_true(bgi_cpu_segment_blocked(&st->objects[0], o, l, 4 * a * before));
        bg_scene_destroy(scene);

        desc = bg_object_desc_init(BG_SHAPE_PLANE, 1);
        desc.transform = bg_mat4_scale(a, a, a);
        scene = one_object(&desc);
        st = bgi_scene_committed(scene);
        /* From 3a above the plane, obliquely: the root is at 5a. */
        const double p[3] = {0, 3 * a, 0}, m[3] = {0.8, -0.6, 0};
        assert_false(bgi_cpu_segment_blocked(&st->objects[0], p, m, 5 * a * near_end));
        assert_true(bgi_cpu_segment_blocked(&st->objects[0], p, m, 5 * a * before));
        bg_scene_destroy(scene);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_head_on),
        cmocka_unit_test(test_sphere_unnormalised_direction),
        cmocka_unit_test(test_sphere_inside_and_graze),
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_plane_and_rectangle),
        cmocka_unit_test(test_cylinder),
        cmocka_unit_test(test_uv_maps),
        cmocka_unit_test(test_transformed_sphere),
        cmocka_unit_test(test_transformed_box),
        cmocka_unit_test(test_transformed_plane_both_sides),
        cmocka_unit_test(test_transformed_cylinder_and_rectangle),
        cmocka_unit_test(test_segment_blocked),
        cmocka_unit_test(test_segment_open_at_light),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
