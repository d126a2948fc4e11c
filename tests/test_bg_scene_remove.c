/* Removing objects, lights, materials and textures, and the generation-counted handles behind it:
 * a removal takes effect at the next commit and gives exactly the committed state (and so the CPU
 * image) of a scene built without the removed items; an id of a removed item is refused by every
 * call that takes a handle, also after its slot is reused and after the slot's generations run out
 * (the slot retires); materials and textures still referenced are refused naming the referrer; a
 * commit that fails after a removal leaves the previous commit renderable. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_alloc.h"

#include "betelgeuse.h"
#include "betelgeuse/scene/scene_internal.h"
#include "scenes/scenes.h"
#include "util_removal.h"

enum { W = 64, H = 48 };

/* ---- helpers ---- */

/* The call returned want with a message containing text; clears the error, and checks that the
 * refused call left the scene committable. */
static void expect_refused(bg_scene *s, bg_status got, bg_status want, const char *text)
{
    assert_int_equal(got, want);
    assert_int_equal(bg_scene_error(s), want);
    const char *msg = bg_scene_error_message(s);
    if (!strstr(msg, text))
        fail_msg("message \"%s\" does not contain \"%s\"", msg, text);
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bg_scene_error(s), BG_OK);
}

static unsigned char *cpu_image(bg_scene *s)
{
    unsigned char *px = malloc((size_t)W * H * 4);
    assert_non_null(px);
    bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
    bg_render_settings set = bg_render_settings_init();
    set.threads = 2;
    assert_int_equal(bg_render_cpu(s, &set, &img), BG_OK);
    return px;
}

static bool same_image(const unsigned char *a, const unsigned char *b)
{
    return memcmp(a, b, (size_t)W * H * 4) == 0;
}

static bg_scene *scene_with_material(uint32_t *out_material)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &m, out_material), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

static uint32_t add_sphere(bg_scene *s, double x, uint32_t material)
{
    uint32_t id;
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(x, 0, 0), 0.5, material, &id), BG_OK);
    return id;
}

/* ---- removal and the committed state ---- */

/* Removing the doomed items gives the image of the scene built without them, bit for bit, with
 * the object tree (9 spheres) and without it mattering (4). Until the commit the last committed
 * scene is what renders. */
static void check_removal_matches(int spheres)
{
    bg_scene *a = NULL, *b = NULL;
    assert_int_equal(bg_scene_create(NULL, &a), BG_OK);
    assert_int_equal(bg_scene_create(NULL, &b), BG_OK);
    util_doomed d;
    util_removal_scene(a, spheres, &d);
    util_removal_scene(b, spheres, NULL);
    unsigned char *before = cpu_image(a), *without = cpu_image(b);
    assert_false(same_image(before, without)); /* the doomed sphere and light show */

    /* Pending removals change nothing the renderers see. */
    assert_int_equal(bg_scene_remove_object(a, d.sphere), BG_OK);
    assert_int_equal(bg_scene_remove_light(a, d.light), BG_OK);
    assert_int_equal(bgi_scene_committed(a)->object_count, (uint32_t)spheres + 2);
    unsigned char *pending = cpu_image(a);
    assert_true(same_image(pending, before));
    assert_int_equal(bg_scene_remove_material(a, d.material), BG_OK);
    assert_int_equal(bg_scene_remove_texture(a, d.texture), BG_OK);
    assert_int_equal(bg_scene_commit(a), BG_OK);

    const bg_scene_state *sa = bgi_scene_committed(a), *sb = bgi_scene_committed(b);
    assert_int_equal(sa->object_count, sb->object_count);
    assert_int_equal(sa->material_count, sb->material_count);
    assert_int_equal(sa->texture_count, sb->texture_count);
    assert_int_equal(sa->light_count, sb->light_count);
    assert_int_equal(sa->tree_count, sb->tree_count);
    assert_int_equal(sa->always_count, sb->always_count);
    for (uint32_t i = 0; i < sa->object_count; i++) {
        assert_int_equal(sa->objects[i].material, sb->objects[i].material);
        assert_memory_equal(sa->objects[i].to_world, sb->objects[i].to_world, sizeof sa->objects[i].to_world);
    }
    /* The checker material now reads dense texture 1, as in the scene built without the doomed one. */
    for (uint32_t i = 0; i < sa->material_count; i++)
        assert_int_equal(sa->materials[i].base.reflectance.texture, sb->materials[i].base.reflectance.texture);
    unsigned char *after = cpu_image(a);
    assert_true(same_image(after, without));
    free(before);
    free(without);
    free(pending);
    free(after);
    bg_scene_destroy(a);
    bg_scene_destroy(b);
}

static void removal_matches_a_scene_built_without(void **state)
{
    (void)state;
    check_removal_matches(4);
    check_removal_matches(9);
}

/* A removed object or light that is added again lands where the scene built that way has it. */
static void remove_then_add_renders_like_a_fresh_build(void **state)
{
    (void)state;
    uint32_t m, n;
    bg_scene *a = scene_with_material(&m), *b = scene_with_material(&n);
    uint32_t a1 = add_sphere(a, -1, m), a2 = add_sphere(a, 0, m);
    add_sphere(a, 1, m);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0, 3, 3);
    uint32_t la;
    assert_int_equal(bg_scene_add_light(a, &l, &la), BG_OK);
    assert_int_equal(bg_scene_commit(a), BG_OK);
    assert_int_equal(bg_scene_remove_object(a, a2), BG_OK);
    assert_int_equal(bg_scene_remove_object(a, a1), BG_OK);
    uint32_t r1 = add_sphere(a, -0.5, m); /* reuses a1's slot (last freed first): dense index 0 */
    assert_int_equal(r1 & 0xFFFFFFu, a1 & 0xFFFFFFu);
    assert_int_equal(bg_scene_commit(a), BG_OK);

    add_sphere(b, -0.5, n);
    add_sphere(b, 1, n);
    uint32_t lb;
    assert_int_equal(bg_scene_add_light(b, &l, &lb), BG_OK);
    assert_int_equal(bg_scene_commit(b), BG_OK);
    unsigned char *ia = cpu_image(a), *ib = cpu_image(b);
    assert_true(same_image(ia, ib));
    free(ia);
    free(ib);
    bg_scene_destroy(a);
    bg_scene_destroy(b);
}

/* ---- handles ---- */

static void stale_ids_refused_by_every_call(void **state)
{
    (void)state;
    static const unsigned char c0[3] = {0, 0, 0}, c1[3] = {255, 255, 255};
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    uint32_t t, m0, m1, o1, o2, l1, l2;
    assert_int_equal(scenes_add_checker_texture(s, c0, c1, &t), BG_OK);
    bg_material plain = bg_material_init(), textured = plain;
    textured.base.reflectance.texture = t;
    assert_int_equal(bg_scene_add_material(s, &plain, &m0), BG_OK);
    assert_int_equal(bg_scene_add_material(s, &textured, &m1), BG_OK);
    o1 = add_sphere(s, 0, m0);
    o2 = add_sphere(s, 2, m0);
    bg_light l = bg_light_init();
    assert_int_equal(bg_scene_add_light(s, &l, &l1), BG_OK);
    assert_int_equal(bg_scene_add_light(s, &l, &l2), BG_OK);
    /* A scene that never removed anything hands out 1, 2, 3 per kind. */
    assert_int_equal(t, 1);
    assert_int_equal(m1, 2);
    assert_int_equal(o2, 2);
    assert_int_equal(l2, 2);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    assert_int_equal(bg_scene_remove_object(s, o1), BG_OK);
    assert_int_equal(bg_scene_remove_light(s, l1), BG_OK);
    assert_int_equal(bg_scene_remove_material(s, m1), BG_OK);
    assert_int_equal(bg_scene_remove_texture(s, t), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    bg_mat4 move = bg_mat4_translate(0, 1, 0);
    uint32_t id;
    expect_refused(s, bg_scene_set_transform(s, o1, &move), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_set_transform: object = 1 was removed");
    expect_refused(s, bg_scene_remove_object(s, o1), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_remove_object: object = 1 was removed");
    expect_refused(s, bg_scene_set_light(s, l1, &l), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_set_light: light = 1 was removed");
    expect_refused(s, bg_scene_remove_light(s, l1), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_remove_light: light = 1 was removed");
    expect_refused(s, bg_scene_set_material(s, m1, &plain), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_set_material: material = 2 was removed");
    expect_refused(s, bg_scene_remove_material(s, m1), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_remove_material: material = 2 was removed");
    bg_object_desc desc = bg_object_desc_init(BG_SHAPE_BOX, m1);
    expect_refused(s, bg_scene_add_object(s, &desc, &id), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_add_object: material = 2 was removed");
    expect_refused(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1, m1, &id), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_add_sphere: material = 2 was removed");
    expect_refused(s, bg_scene_add_plane(s, bg_vec3_make(0, 0, 0), bg_vec3_make(0, 1, 0), m1, &id),
                   BG_ERR_INVALID_ARGUMENT, "bg_scene_add_plane: material = 2 was removed");
    expect_refused(s, bg_scene_add_material(s, &textured, &id), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_add_material: base.reflectance.texture = 1 was removed");
    bg_material coat = plain;
    coat.coat.isotropy.texture = t; /* an unused coat's references are checked too */
    expect_refused(s, bg_scene_set_material(s, m0, &coat), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_set_material: material 1: coat.isotropy.texture = 1 was removed");
    expect_refused(s, bg_scene_remove_texture(s, t), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_remove_texture: texture = 1 was removed");

    /* The slot is reused under a new id; the old one still names the removed object only. */
    uint32_t o3 = add_sphere(s, 4, m0);
    assert_int_equal(o3, 0x01000001u);
    assert_true(o3 != o1);
    expect_refused(s, bg_scene_set_transform(s, o1, &move), BG_ERR_INVALID_ARGUMENT, "object = 1 was removed");
    assert_int_equal(bg_scene_set_transform(s, o3, &move), BG_OK);
    assert_int_equal(bg_scene_remove_object(s, o3), BG_OK);
    expect_refused(s, bg_scene_set_transform(s, o3, &move), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_set_transform: object = 0x01000001 was removed");
    /* Ids never handed out: a later generation, a slot past the end, slot bits 0. */
    expect_refused(s, bg_scene_set_transform(s, 0x02000001u, &move), BG_ERR_INVALID_ARGUMENT,
                   "object = 0x02000001 is not an object of this scene (1 in use)");
    expect_refused(s, bg_scene_set_transform(s, 3, &move), BG_ERR_INVALID_ARGUMENT, "object = 3 is not an object");
    expect_refused(s, bg_scene_set_transform(s, 0x01000000u, &move), BG_ERR_INVALID_ARGUMENT,
                   "object = 0x01000000 is not an object");
    expect_refused(s, bg_scene_remove_object(s, 0), BG_ERR_INVALID_ARGUMENT, "object = 0 is not an object");
    assert_int_equal(bgi_scene_committed(s)->object_count, 1);
    assert_true(bgi_scene_committed(s)->objects[0].to_world[0][3] == 2.0); /* o2, untouched */
    bg_scene_destroy(s);
}

static void freed_slots_are_reused_last_freed_first(void **state)
{
    (void)state;
    uint32_t m;
    bg_scene *s = scene_with_material(&m);
    uint32_t a = add_sphere(s, 0, m), b = add_sphere(s, 1, m), c = add_sphere(s, 2, m);
    assert_int_equal(bg_scene_remove_object(s, b), BG_OK);
    uint32_t b2 = add_sphere(s, 5, m);
    assert_int_equal(b2, 0x01000002u);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    /* Dense in slot order: the reused slot sits between a and c. */
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_int_equal(st->object_count, 3);
    assert_true(st->objects[1].to_world[0][3] == 5.0);
    assert_int_equal(bg_scene_remove_object(s, a), BG_OK);
    assert_int_equal(bg_scene_remove_object(s, c), BG_OK);
    assert_int_equal(add_sphere(s, 7, m), 0x01000003u);
    assert_int_equal(add_sphere(s, 8, m), 0x01000001u);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_true(st->objects[0].to_world[0][3] == 8.0 && st->objects[2].to_world[0][3] == 7.0);
    bg_scene_destroy(s);
}

/* 300 add/remove rounds on one slot: generations 0 .. 255, then the slot retires and a new slot
 * takes over; no id repeats and every old id stays refused. */
static void exhausted_slots_retire(void **state)
{
    (void)state;
    enum { ROUNDS = 300 };
    uint32_t m;
    bg_scene *s = scene_with_material(&m);
    uint32_t ids[ROUNDS];
    for (int i = 0; i < ROUNDS; i++) {
        ids[i] = add_sphere(s, 0, m);
        for (int k = 0; k < i; k++)
            assert_true(ids[k] != ids[i]);
        assert_int_equal(bg_scene_remove_object(s, ids[i]), BG_OK);
    }
    for (uint32_t g = 0; g < 256; g++)
        assert_int_equal(ids[g], 1u | (g << 24));
    assert_int_equal(ids[256], 2u);
    assert_int_equal(ids[299], 2u | (43u << 24));
    bg_mat4 move = bg_mat4_translate(0, 1, 0);
    for (int i = 0; i < ROUNDS; i++) {
        assert_int_equal(bg_scene_set_transform(s, ids[i], &move), BG_ERR_INVALID_ARGUMENT);
        assert_non_null(strstr(bg_scene_error_message(s), "was removed"));
        bg_scene_clear_error(s);
    }
    /* The retired slot stays retired: the next objects take slot 1's next generation, then slot 2. */
    assert_int_equal(add_sphere(s, 0, m), 2u | (44u << 24));
    assert_int_equal(add_sphere(s, 1, m), 3u);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bgi_scene_committed(s)->object_count, 2);
    bg_scene_destroy(s);
}

static void removing_twice_fails(void **state)
{
    (void)state;
    static const unsigned char c0[3] = {0, 0, 0}, c1[3] = {255, 255, 255};
    uint32_t m, o, l, t, m2;
    bg_scene *s = scene_with_material(&m);
    o = add_sphere(s, 0, m);
    bg_light light = bg_light_init();
    assert_int_equal(bg_scene_add_light(s, &light, &l), BG_OK);
    assert_int_equal(scenes_add_checker_texture(s, c0, c1, &t), BG_OK);
    bg_material mat = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &mat, &m2), BG_OK);
    assert_int_equal(bg_scene_remove_object(s, o), BG_OK);
    expect_refused(s, bg_scene_remove_object(s, o), BG_ERR_INVALID_ARGUMENT, "object = 1 was removed");
    assert_int_equal(bg_scene_remove_light(s, l), BG_OK);
    expect_refused(s, bg_scene_remove_light(s, l), BG_ERR_INVALID_ARGUMENT, "light = 1 was removed");
    assert_int_equal(bg_scene_remove_texture(s, t), BG_OK);
    expect_refused(s, bg_scene_remove_texture(s, t), BG_ERR_INVALID_ARGUMENT, "texture = 1 was removed");
    assert_int_equal(bg_scene_remove_material(s, m2), BG_OK);
    expect_refused(s, bg_scene_remove_material(s, m2), BG_ERR_INVALID_ARGUMENT, "material = 2 was removed");
    assert_int_equal(bg_scene_remove_object(NULL, 1), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_scene_remove_light(NULL, 1), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_scene_remove_material(NULL, 1), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(bg_scene_remove_texture(NULL, 1), BG_ERR_INVALID_ARGUMENT);
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_int_equal(st->object_count + st->light_count + st->texture_count, 0);
    assert_int_equal(st->material_count, 1);
    bg_scene_destroy(s);
}

/* Materials and textures are referenced by handle, so they are refused while referenced (the
 * message names the referrer) and removable once nothing uses them. */
static void referenced_materials_and_textures_refused(void **state)
{
    (void)state;
    static const unsigned char c0[3] = {0, 0, 0}, c1[3] = {255, 255, 255};
    uint32_t m0;
    bg_scene *s = scene_with_material(&m0);
    uint32_t t1, t2, m1, m2;
    assert_int_equal(scenes_add_checker_texture(s, c0, c1, &t1), BG_OK);
    assert_int_equal(scenes_add_checker_texture(s, c1, c0, &t2), BG_OK);
    bg_material mat = bg_material_init();
    mat.coat.roughness.texture = t2; /* has_coat is false: still a reference */
    assert_int_equal(bg_scene_add_material(s, &mat, &m1), BG_OK);
    bg_material mat2 = bg_material_init();
    mat2.emission.texture = t1;
    assert_int_equal(bg_scene_add_material(s, &mat2, &m2), BG_OK);
    add_sphere(s, 0, m0);
    uint32_t o = add_sphere(s, 1, m2);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    expect_refused(s, bg_scene_remove_material(s, m2), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_remove_material: material 3 is used by object 2");
    expect_refused(s, bg_scene_remove_texture(s, t2), BG_ERR_INVALID_ARGUMENT,
                   "bg_scene_remove_texture: texture 2 is used by material 2 (coat.roughness.texture)");
    expect_refused(s, bg_scene_remove_texture(s, t1), BG_ERR_INVALID_ARGUMENT,
                   "texture 1 is used by material 3 (emission.texture)");
    /* Dropping the references makes them removable. */
    bg_material untextured = bg_material_init();
    assert_int_equal(bg_scene_set_material(s, m1, &untextured), BG_OK);
    assert_int_equal(bg_scene_remove_texture(s, t2), BG_OK);
    assert_int_equal(bg_scene_remove_object(s, o), BG_OK);
    assert_int_equal(bg_scene_remove_material(s, m2), BG_OK);
    assert_int_equal(bg_scene_remove_texture(s, t1), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_int_equal(st->material_count, 2);
    assert_int_equal(st->texture_count, 0);
    assert_int_equal(st->object_count, 1);
    bg_scene_destroy(s);
}

/* ---- a failing commit after removals ---- */

/* Removals, then a commit that runs out of memory: the previous commit still renders, the removed
 * texture's texels included (they are freed only by a commit that drops them); the next commit
 * applies everything. */
static void failed_commit_keeps_the_previous_one(void **state)
{
    (void)state;
    static const unsigned char c0[3] = {200, 30, 30}, c1[3] = {30, 30, 200};
    util_alloc_counter a = UTIL_ALLOC_COUNTER;
    bg_scene_desc desc = {0};
    desc.allocator.alloc = util_counted_alloc;
    desc.allocator.realloc = util_counted_realloc;
    desc.allocator.free = util_counted_free;
    desc.allocator.user = &a;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(&desc, &s), BG_OK);
    uint32_t t, textured, plain;
    assert_int_equal(scenes_add_checker_texture(s, c0, c1, &t), BG_OK);
    bg_material m = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &m, &plain), BG_OK);
    m.base.reflectance.texture = t;
    assert_int_equal(bg_scene_add_material(s, &m, &textured), BG_OK);
    uint32_t front = add_sphere(s, -0.6, textured);
    add_sphere(s, 0.6, plain);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0, 2, 4);
    uint32_t light;
    assert_int_equal(bg_scene_add_light(s, &l, &light), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    unsigned char *before = cpu_image(s);

    assert_int_equal(bg_scene_remove_object(s, front), BG_OK);
    assert_int_equal(bg_scene_remove_material(s, textured), BG_OK);
    assert_int_equal(bg_scene_remove_texture(s, t), BG_OK);
    assert_int_equal(bg_scene_remove_light(s, light), BG_OK);
    for (int i = 0; i < 40; i++) /* more than the committed arrays hold */
        add_sphere(s, 3 + i, plain);
    a.fail_after = a.allocs;
    assert_int_equal(bg_scene_commit(s), BG_ERR_OUT_OF_MEMORY);
    a.fail_after = -1;
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_int_equal(st->object_count, 2);
    assert_int_equal(st->texture_count, 1);
    assert_int_equal(st->light_count, 1);
    assert_int_equal(st->commit_count, 1);
    unsigned char *after_failure = cpu_image(s);
    assert_true(same_image(before, after_failure));

    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(st->object_count, 41);
    assert_int_equal(st->texture_count, 0);
    assert_int_equal(st->light_count, 0);
    unsigned char *applied = cpu_image(s);
    assert_false(same_image(before, applied));
    free(before);
    free(after_failure);
    free(applied);
    bg_scene_destroy(s);
    assert_int_equal(a.allocs, a.frees);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(removal_matches_a_scene_built_without),
        cmocka_unit_test(remove_then_add_renders_like_a_fresh_build),
        cmocka_unit_test(stale_ids_refused_by_every_call),
        cmocka_unit_test(freed_slots_are_reused_last_freed_first),
        cmocka_unit_test(exhausted_slots_retire),
        cmocka_unit_test(removing_twice_fails),
        cmocka_unit_test(referenced_materials_and_textures_refused),
        cmocka_unit_test(failed_commit_keeps_the_previous_one),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
