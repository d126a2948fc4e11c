/* The shared scenes of examples/scenes: each builds, commits, has what its description promises
 * and is framed by its camera. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/scene/scene_internal.h"
#include "scenes/scenes.h"

static const bg_scene_state *build(scene_id id, const scene_params *p, bg_scene **out)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_status st = scenes_build_ex(id, p, s);
    if (st != BG_OK)
        fail_msg("%s: %s", scenes_name(id), bg_scene_error_message(s));
    assert_int_equal(bg_scene_error(s), BG_OK);
    assert_int_equal(bg_scene_commit_count(s), 1);
    *out = s;
    return bgi_scene_committed(s);
}

static int count_shape(const bg_scene_state *st, bg_shape shape)
{
    int n = 0;
    for (uint32_t i = 0; i < st->object_count; i++)
        n += st->objects[i].shape == shape;
    return n;
}

/* Every bounded object's centre lies inside the camera's view cone (with the aspect 1 of a
 * square image), so no object is off screen. */
static void assert_framed(const bg_scene_state *st, const char *name)
{
    const bg_camera_data *c = &st->camera;
    for (uint32_t i = 0; i < st->object_count; i++) {
        const bg_object_data *o = &st->objects[i];
        if (!o->bounded)
            continue;
        double d[3];
        for (int k = 0; k < 3; k++)
            d[k] = 0.5 * (o->bounds_min[k] + o->bounds_max[k]) - (&c->camera.position.x)[k];
        double z = d[0] * c->forward[0] + d[1] * c->forward[1] + d[2] * c->forward[2];
        double x = d[0] * c->right[0] + d[1] * c->right[1] + d[2] * c->right[2];
        double y = d[0] * c->up[0] + d[1] * c->up[1] + d[2] * c->up[2];
        if (!(z > 0 && fabs(x) < z * c->half_y && fabs(y) < z * c->half_y))
            fail_msg("%s: object %u is out of view (x %g, y %g, z %g)", name, i + 1, x, y, z);
    }
}

static void test_every_scene_builds(void **state)
{
    (void)state;
    for (int i = 0; i < SCENE_COUNT; i++) {
        bg_scene *s;
        const bg_scene_state *st = build((scene_id)i, NULL, &s);
        assert_non_null(st);
        assert_true(st->object_count >= 1);
        assert_true(st->light_count >= 1);
        assert_true(st->has_bounded_objects);
        assert_framed(st, scenes_name((scene_id)i));
        scene_id back;
        assert_true(scenes_find(scenes_name((scene_id)i), &back));
        assert_int_equal(back, i);
        bg_scene_destroy(s);
    }
    assert_null(scenes_name(SCENE_COUNT));
    scene_id x;
    assert_false(scenes_find("no_such_scene", &x));
    bg_scene *s;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_int_equal(scenes_build(SCENE_COUNT, s), BG_ERR_INVALID_ARGUMENT);
    scene_params bad = {.lights = 300};
    assert_int_equal(scenes_build_ex(SCENE_MANY_LIGHTS, &bad, s), BG_ERR_INVALID_ARGUMENT);
    bg_scene_destroy(s);
}

static void test_paper_scenes(void **state)
{
    (void)state;
    bg_scene *s;
    const bg_scene_state *st = build(SCENE_PAPER_EARTH, NULL, &s);
    assert_int_equal(st->object_count, 1);
    assert_int_equal(st->objects[0].shape, BG_SHAPE_SPHERE);
    assert_int_equal(st->light_count, 2);
    for (uint32_t i = 0; i < st->light_count; i++)
        assert_int_equal(st->lights[i].type, BG_LIGHT_POINT);
    assert_int_equal(st->texture_count, 1);
    assert_int_equal(st->textures[0].width, 256);
    assert_int_equal(st->textures[0].height, 128);
    assert_int_equal(st->materials[st->objects[0].material].base.reflectance.texture, 1);
    bg_scene_destroy(s);

    st = build(SCENE_PAPER_EARTH_SHADOW, NULL, &s);
    assert_int_equal(count_shape(st, BG_SHAPE_SPHERE), 1);
    assert_int_equal(count_shape(st, BG_SHAPE_PLANE), 1);
    assert_int_equal(st->light_count, 2);
    /* The plane is behind the sphere and faces the camera; every light is in front of the plane. */
    const bg_object_data *plane = st->objects[0].shape == BG_SHAPE_PLANE ? &st->objects[0] : &st->objects[1];
    const bg_object_data *sphere = st->objects[0].shape == BG_SHAPE_SPHERE ? &st->objects[0] : &st->objects[1];
    double n[3] = {plane->to_world[0][1], plane->to_world[1][1], plane->to_world[2][1]};
    double p0[3] = {plane->to_world[0][3], plane->to_world[1][3], plane->to_world[2][3]};
    const double *cam = &st->camera.camera.position.x;
    double side_cam = 0, side_sphere = 0;
    for (int k = 0; k < 3; k++) {
        side_cam += (cam[k] - p0[k]) * n[k];
        side_sphere += (sphere->to_world[k][3] - p0[k]) * n[k];
    }
    assert_true(side_cam > 0 && side_sphere > 1.0); /* sphere clear of the plane */
    for (uint32_t i = 0; i < st->light_count; i++) {
        const double *l = &st->lights[i].position.x;
        double side = 0;
        for (int k = 0; k < 3; k++)
            side += (l[k] - p0[k]) * n[k];
        assert_true(side > side_sphere);
    }
    bg_scene_destroy(s);
}

static void test_mirror_and_glass(void **state)
{
    (void)state;
    bg_scene *s;
    const bg_scene_state *st = build(SCENE_MIRROR, NULL, &s);
    int mirrors = 0, diffuse = 0;
    for (uint32_t i = 0; i < st->object_count; i++) {
        const bg_material *m = &st->materials[st->objects[i].material];
        if (st->objects[i].shape != BG_SHAPE_SPHERE)
            continue;
        if (m->base.roughness.value == 0 && m->base.reflectance.r >= 0.8)
            mirrors++;
        else if (m->base.roughness.value == 1)
            diffuse++;
    }
    assert_int_equal(mirrors, 1);
    assert_true(diffuse >= 3);
    assert_int_equal(count_shape(st, BG_SHAPE_PLANE), 1);
    bg_scene_destroy(s);

    st = build(SCENE_GLASS, NULL, &s);
    int glass = 0;
    mirrors = 0;
    bool checker = false;
    for (uint32_t i = 0; i < st->object_count; i++) {
        const bg_material *m = &st->materials[st->objects[i].material];
        if (m->transparency.value == 1 && m->ior == 1.5)
            glass++;
        else if (m->base.roughness.value == 0)
            mirrors++;
        if (st->objects[i].shape == BG_SHAPE_PLANE && m->base.reflectance.texture != 0)
            checker = true;
    }
    assert_int_equal(glass, 1);
    assert_int_equal(mirrors, 1);
    assert_true(checker);
    bg_scene_destroy(s);
}

static void test_scaling_scenes(void **state)
{
    (void)state;
    const int spheres[] = {1, 2, 7, 16, 64, 100};
    for (size_t i = 0; i < sizeof spheres / sizeof spheres[0]; i++) {
        scene_params p = {.spheres = spheres[i]};
        bg_scene *s;
        const bg_scene_state *st = build(SCENE_MANY_SPHERES, &p, &s);
        assert_int_equal(count_shape(st, BG_SHAPE_SPHERE), spheres[i]);
        assert_framed(st, "many_spheres");
        /* Varied materials once there are enough spheres. */
        if (spheres[i] >= 6) {
            bool seen[64] = {false};
            int distinct = 0;
            for (uint32_t k = 0; k < st->object_count; k++)
                if (st->objects[k].shape == BG_SHAPE_SPHERE && !seen[st->objects[k].material]) {
                    seen[st->objects[k].material] = true;
                    distinct++;
                }
            assert_true(distinct >= 6);
        }
        bg_scene_destroy(s);
    }
    const int lights[] = {1, 3, 8, 16};
    for (size_t i = 0; i < sizeof lights / sizeof lights[0]; i++) {
        scene_params p = {.lights = lights[i]};
        bg_scene *s;
        const bg_scene_state *st = build(SCENE_MANY_LIGHTS, &p, &s);
        assert_int_equal(st->light_count, (uint32_t)lights[i]);
        double total = 0;
        for (uint32_t k = 0; k < st->light_count; k++)
            total += st->lights[k].intensity;
        assert_true(fabs(total - 2.0) < 1e-12);
        if (lights[i] >= 3)
            assert_false(st->lights[0].color[0] == st->lights[1].color[0] &&
                         st->lights[0].color[1] == st->lights[1].color[1]);
        bg_scene_destroy(s);
    }
}

static void test_all_primitives_and_textured(void **state)
{
    (void)state;
    bg_scene *s;
    const bg_scene_state *st = build(SCENE_ALL_PRIMITIVES, NULL, &s);
    for (int k = 0; k < BG_SHAPE_COUNT_; k++)
        assert_int_equal(count_shape(st, (bg_shape)k), 1);
    int rotated = 0;
    for (uint32_t i = 0; i < st->object_count; i++)
        rotated += st->objects[i].to_world[0][1] != 0 || st->objects[i].to_world[1][0] != 0;
    assert_true(rotated >= 2);
    bg_scene_destroy(s);

    st = build(SCENE_TEXTURED_ANISO, NULL, &s);
    bool spot = false, sun = false, coat = false, aniso = false, textured_scalar = false;
    for (uint32_t i = 0; i < st->light_count; i++) {
        spot |= st->lights[i].type == BG_LIGHT_POINT && st->lights[i].spot_cutoff_degrees < 90;
        sun |= st->lights[i].type == BG_LIGHT_DIRECTIONAL;
    }
    for (uint32_t i = 0; i < st->material_count; i++) {
        coat |= st->materials[i].has_coat;
        aniso |= st->materials[i].base.isotropy.value < 0.5;
        textured_scalar |= st->materials[i].base.roughness.texture != 0;
    }
    assert_true(spot && sun && coat && aniso && textured_scalar);
    assert_true(st->texture_count >= 3);
    bg_scene_destroy(s);
}

static void test_earth_texture(void **state)
{
    (void)state;
    enum { W = 256, H = 128 };
    unsigned char *a = malloc(W * H * 4), *b = malloc(W * H * 4);
    scenes_earth_pixels(W, H, a);
    scenes_earth_pixels(W, H, b);
    assert_memory_equal(a, b, W * H * 4); /* deterministic */
    int ocean = 0, land = 0, ice = 0;
    for (int i = 0; i < W * H; i++) {
        const unsigned char *p = a + 4 * i;
        assert_int_equal(p[3], 255);
        if (p[0] > 200 && p[1] > 200 && p[2] > 200)
            ice++;
        else if (p[2] > p[1] && p[2] > p[0])
            ocean++;
        else
            land++;
    }
    /* Both kinds of surface in earnest, and ice only near the poles (top and bottom rows). */
    assert_true(ocean > W * H / 5 && land > W * H / 8 && ice > W * 4);
    for (int x = 0; x < W; x++) {
        const unsigned char *top = a + 4 * x, *mid = a + 4 * ((H / 2) * W + x);
        assert_true(top[0] > 200);
        assert_false(mid[0] > 200 && mid[1] > 200 && mid[2] > 200);
    }
    free(a);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_scene_builds),
        cmocka_unit_test(test_paper_scenes),
        cmocka_unit_test(test_mirror_and_glass),
        cmocka_unit_test(test_scaling_scenes),
        cmocka_unit_test(test_all_primitives_and_textured),
        cmocka_unit_test(test_earth_texture),
    };
    return cmocka_run_group_tests_name("bg_scenes", tests, NULL, NULL);
}
