/* Test helper: the removal scene (util_removal.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "scenes/scenes.h"
#include "util_removal.h"

static uint32_t material(bg_scene *s, double r, double g, double b, double roughness, uint32_t texture)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    m.base.reflectance.texture = texture;
    m.base.roughness.value = roughness;
    uint32_t id;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_OK);
    return id;
}

static uint32_t light(bg_scene *s, double x, double y, double z, double intensity)
{
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(x, y, z);
    l.intensity = intensity;
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    return id;
}

void util_removal_scene(bg_scene *s, int spheres, util_doomed *doomed)
{
    static const unsigned char dark[3] = {40, 60, 90}, light_[3] = {230, 220, 200};
    static const unsigned char red[3] = {200, 20, 20}, green[3] = {20, 200, 20};
    if (doomed) {
        assert_int_equal(scenes_add_checker_texture(s, red, green, &doomed->texture), BG_OK);
        doomed->material = material(s, 1, 1, 1, 1, doomed->texture);
        doomed->light = light(s, -5, 3, 7, 0.5);
    }
    uint32_t checker;
    assert_int_equal(scenes_add_checker_texture(s, dark, light_, &checker), BG_OK);
    uint32_t mats[4] = {material(s, 0.8, 0.2, 0.15, 1, 0), material(s, 0.9, 0.9, 0.9, 0, 0),
                        material(s, 1, 1, 1, 1, checker), material(s, 0.2, 0.5, 0.8, 0.3, 0)};
    uint32_t wall = material(s, 0.85, 0.85, 0.85, 1, 0);
    const int side = 3, rows = (spheres + side - 1) / side;
    uint32_t id;
    for (int i = 0; i < spheres; i++) {
        double x = (i % side - 1) * 1.3, y = ((rows - 1) / 2.0 - i / side) * 1.3;
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(x, y, 0), 0.55, mats[i % 4], &id), BG_OK);
        if (i == 0 && doomed)
            assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0.4, 0.3, 1.6), 0.45, doomed->material,
                                                 &doomed->sphere), BG_OK);
    }
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, 0, -1.5), bg_vec3_make(0, 0, 1), wall, &id), BG_OK);
    light(s, 4, 4, 8, 0.8);
    double ambient[3] = {0.3, 0.3, 0.3};
    assert_int_equal(bg_scene_set_ambient(s, ambient), BG_OK);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(0.5, 0.8, 4.0 + 1.6 * rows);
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
}

void util_removal_remove(bg_scene *s, const util_doomed *doomed)
{
    assert_int_equal(bg_scene_remove_object(s, doomed->sphere), BG_OK);
    assert_int_equal(bg_scene_remove_material(s, doomed->material), BG_OK);
    assert_int_equal(bg_scene_remove_texture(s, doomed->texture), BG_OK);
    assert_int_equal(bg_scene_remove_light(s, doomed->light), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
}
