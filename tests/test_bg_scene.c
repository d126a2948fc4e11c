/* The scene API: validation of every field, the sticky first error, nothing half-applied, commit
 * (inverses, bounds, resolved UV mapping, camera basis) and cheap re-commits. */
#include <float.h>
#include <math.h>
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

/* ---- helpers ---- */

typedef struct counts { uint32_t objects, materials, lights, textures; } counts;

/* A scene with one texture, two materials, a sphere, a plane and a light, committed. */
static bg_scene *small_scene(void)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    unsigned char px[4 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    bg_image img = {2, 2, BG_PIXEL_RGBA8, 0, px};
    uint32_t t, m, o, l;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &t), BG_OK);
    bg_material mat = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &mat, &m), BG_OK);
    mat.base.reflectance.texture = t;
    assert_int_equal(bg_scene_add_material(s, &mat, &m), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1, 1, &o), BG_OK);
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), 2, &o), BG_OK);
    bg_light light = bg_light_init();
    light.position = bg_vec3_make(3, 3, 3);
    assert_int_equal(bg_scene_add_light(s, &light, &l), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

static counts committed_counts(const bg_scene *s)
{
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_non_null(st);
    counts c = {st->object_count, st->material_count, st->light_count, st->texture_count};
    return c;
}

/* The call returned status, stored it with a message naming field, changed nothing, and the
 * scene still commits to the same counts. Clears the error afterwards. */
static void expect_rejected(bg_scene *s, bg_status got, bg_status want, const char *field)
{
    counts before = committed_counts(s);
    assert_int_equal(got, want);
    assert_int_equal(bg_scene_error(s), want);
    const char *msg = bg_scene_error_message(s);
    if (!strstr(msg, field))
        fail_msg("message \"%s\" does not name \"%s\"", msg, field);
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    counts after = committed_counts(s);
    assert_memory_equal(&before, &after, sizeof before);
    assert_int_equal(bg_scene_error(s), BG_OK);
}

static bg_status add_material(bg_scene *s, bg_material m)
{
    uint32_t id = 777;
    bg_status st = bg_scene_add_material(s, &m, &id);
    if (st != BG_OK)
        assert_int_equal(id, 777); /* no handle handed out on failure */
    return st;
}

static bg_status add_object(bg_scene *s, bg_object_desc d)
{
    uint32_t id;
    return bg_scene_add_object(s, &d, &id);
}

static bg_status add_light(bg_scene *s, bg_light l)
{
    uint32_t id;
    return bg_scene_add_light(s, &l, &id);
}

static bg_status set_camera(bg_scene *s, bg_camera c)
{
    return bg_scene_set_camera(s, &c);
}

/* ---- status and lifetime ---- */

static void test_status_strings(void **state)
{
    (void)state;
    assert_string_equal(bg_status_string(BG_OK), "ok");
    assert_string_equal(bg_status_string(BG_ERR_IO), "file input/output failed");
    assert_string_equal(bg_status_string(BG_ERR_THREAD), "a worker thread could not be started");
    assert_string_equal(bg_status_string((bg_status)99), "unknown status");
    assert_string_equal(bg_status_string((bg_status)-1), "unknown status");
}

static void test_not_committed_before_first_commit(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    assert_null(bgi_scene_committed(s));
    assert_int_equal(bg_scene_commit_count(s), 0);
    assert_int_equal(bg_scene_error(s), BG_OK);
    assert_string_equal(bg_scene_error_message(s), "");
    assert_int_equal(bg_scene_commit(s), BG_OK); /* an empty scene is a valid scene */
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_non_null(st);
    assert_int_equal(st->object_count, 0);
    assert_false(st->has_bounded_objects);
    assert_int_equal(bg_scene_commit_count(s), 1);
    assert_int_equal(st->commit_count, 1);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bg_scene_commit_count(s), 2);
    bg_scene_destroy(s);
    bg_scene_destroy(NULL);
    assert_int_equal(bg_scene_create(NULL, NULL), BG_ERR_INVALID_ARGUMENT);
}

static void test_pending_changes_invisible_until_commit(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    uint32_t o;
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(5, 0, 0), 1, 1, &o), BG_OK);
    assert_int_equal(o, 3);
    assert_int_equal(bgi_scene_committed(s)->object_count, 2);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bgi_scene_committed(s)->object_count, 3);
    bg_scene_destroy(s);
}

/* ---- allocator and logger ---- */

/* A scene whose every allocation goes through the counting hooks above. */
static bg_scene *counted_scene(util_alloc_counter *a)
{
    bg_scene_desc d = {0};
    d.allocator.alloc = util_counted_alloc;
    d.allocator.realloc = util_counted_realloc;
    d.allocator.free = util_counted_free;
    d.allocator.user = a;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(&d, &s), BG_OK);
    return s;
}

static void test_allocator_hooks(void **state)
{
    (void)state;
    util_alloc_counter a = UTIL_ALLOC_COUNTER;
    bg_scene_desc d = {0};
    d.allocator.alloc = util_counted_alloc;
    d.allocator.free = util_counted_free; /* no realloc: the library moves blocks itself */
    d.allocator.user = &a;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(&d, &s), BG_OK);
    bg_material m = bg_material_init();
    uint32_t id;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_OK);
    for (int i = 0; i < 20; i++)
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(i, 0, 0), 1, 1, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bgi_scene_committed(s)->object_count, 20);
    assert_true(bgi_scene_committed(s)->objects[19].to_world[0][3] == 19.0);
    assert_true(a.allocs > 3);
    bg_scene_destroy(s);
    assert_int_equal(a.allocs, a.frees);

    /* Half a set of hooks is a caller mistake. */
    bg_scene_desc bad = {0};
    bad.allocator.alloc = util_counted_alloc;
    s = (bg_scene *)&bad;
    assert_int_equal(bg_scene_create(&bad, &s), BG_ERR_INVALID_ARGUMENT);
    assert_null(s);

    /* Out of memory at create. */
    util_alloc_counter none = {0, 0, 0, 0, 0}; /* the very first allocation fails */
    d.allocator.user = &none;
    assert_int_equal(bg_scene_create(&d, &s), BG_ERR_OUT_OF_MEMORY);
    assert_null(s);
}

static void test_out_of_memory_leaves_scene_intact(void **state)
{
    (void)state;
    util_alloc_counter a = UTIL_ALLOC_COUNTER;
    bg_scene *s = counted_scene(&a);
    bg_material m = bg_material_init();
    uint32_t id;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_OK);
    for (int i = 0; i < 4; i++)
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(i, 0, 0), 1, 1, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    /* Grow the pending objects past the committed storage, then make commit's growth fail. */
    for (int i = 4; i < 32; i++) /* the pending array is now exactly full */
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(i, 0, 0), 1, 1, &id), BG_OK);
    a.fail_after = a.allocs;
    assert_int_equal(bg_scene_commit(s), BG_ERR_OUT_OF_MEMORY);
    assert_int_equal(bg_scene_error(s), BG_ERR_OUT_OF_MEMORY);
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_non_null(st);
    assert_int_equal(st->object_count, 4);
    assert_int_equal(st->commit_count, 1);
    for (uint32_t i = 0; i < 4; i++)
        assert_true(st->objects[i].to_world[0][3] == (double)i);
    /* Adding fails cleanly too. */
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1, 1, &id), BG_ERR_OUT_OF_MEMORY);
    a.fail_after = -1;
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bgi_scene_committed(s)->object_count, 32);
    bg_scene_destroy(s);
    assert_int_equal(a.allocs, a.frees);
}

typedef struct log_record { int calls; bg_log_level level; char last[512]; } log_record;

static void t_log(bg_log_level level, const char *message, void *user)
{
    log_record *r = user;
    r->calls++;
    r->level = level;
    strncpy(r->last, message, sizeof r->last - 1);
}

static void test_logger_and_sticky_error(void **state)
{
    (void)state;
    log_record rec = {0, BG_LOG_DEBUG, ""};
    bg_scene_desc d = {0};
    d.logger.func = t_log;
    d.logger.user = &rec;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(&d, &s), BG_OK);
    uint32_t id;
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), -1, 1, &id), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rec.calls, 1);
    assert_int_equal(rec.level, BG_LOG_ERROR);
    assert_non_null(strstr(rec.last, "bg_scene_add_sphere: radius = -1"));
    /* A second error is logged but the first one sticks; successes do not clear it. */
    bg_material bad = bg_material_init();
    bad.ior = 0;
    assert_int_equal(bg_scene_add_material(s, &bad, &id), BG_ERR_INVALID_ARGUMENT);
    assert_int_equal(rec.calls, 2);
    assert_non_null(strstr(rec.last, "ior"));
    bg_material good = bg_material_init();
    assert_int_equal(bg_scene_add_material(s, &good, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bg_scene_error(s), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "radius"));
    assert_null(strstr(bg_scene_error_message(s), "ior"));
    bg_scene_clear_error(s);
    assert_int_equal(bg_scene_error(s), BG_OK);
    assert_string_equal(bg_scene_error_message(s), "");
    assert_int_equal(bg_scene_add_material(s, &bad, &id), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "bg_scene_add_material: ior = 0"));
    bg_scene_destroy(s);
}

/* ---- validation ---- */

static void test_material_validation(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    bg_material m;
    uint32_t id;

    m = bg_material_init(); m.base.roughness.value = 1.5;
    bg_status st = add_material(s, m);
    expect_rejected(s, st, BG_ERR_INVALID_ARGUMENT, "bg_scene_add_material: base.roughness.value = 1.5 is outside [0, 1]");
    m = bg_material_init(); m.base.roughness.value = -0.01;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "base.roughness.value");
    m = bg_material_init(); m.base.isotropy.value = 1.01;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "base.isotropy.value");
    m = bg_material_init(); m.coat.isotropy.value = NAN;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "coat.isotropy.value");
    m = bg_material_init(); m.has_coat = true; m.coat.roughness.value = 2;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "coat.roughness.value");
    m = bg_material_init(); m.transparency.value = 1.5;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "transparency.value");
    m = bg_material_init(); m.transparency.value = INFINITY;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "transparency.value");
    m = bg_material_init(); m.base.reflectance.g = -0.5;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "base.reflectance");
    m = bg_material_init(); m.base.reflectance.b = NAN;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "base.reflectance");
    m = bg_material_init(); m.coat.reflectance.r = -1;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "coat.reflectance");
    m = bg_material_init(); m.ambient.r = -0.1;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "ambient");
    m = bg_material_init(); m.emission.g = INFINITY;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "emission");
    m = bg_material_init(); m.ior = 0;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "ior");
    m = bg_material_init(); m.ior = -1.5;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "ior");
    m = bg_material_init(); m.ior = NAN;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "ior");
    m = bg_material_init(); m.base.roughness.channel = 4;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "base.roughness.channel");
    m = bg_material_init(); m.transparency.channel = -1;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "transparency.channel");
    m = bg_material_init(); m.base.reflectance.texture = 2; /* one texture exists */
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "base.reflectance.texture = 2");
    m = bg_material_init(); m.emission.texture = 99;
    expect_rejected(s, add_material(s, m), BG_ERR_INVALID_ARGUMENT, "emission.texture");
    expect_rejected(s, bg_scene_add_material(s, NULL, &id), BG_ERR_INVALID_ARGUMENT, "material is NULL");
    m = bg_material_init();
    expect_rejected(s, bg_scene_add_material(s, &m, NULL), BG_ERR_INVALID_ARGUMENT, "out_material");

    /* The limits themselves are accepted. */
    m = bg_material_init();
    m.base.roughness.value = 0; m.base.isotropy.value = 0; m.transparency.value = 1;
    m.base.roughness.texture = 1; m.base.roughness.channel = 3;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_OK);
    assert_int_equal(id, 3);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    /* set_material: handles and values. */
    expect_rejected(s, bg_scene_set_material(s, 0, &m), BG_ERR_INVALID_ARGUMENT, "material = 0");
    expect_rejected(s, bg_scene_set_material(s, 4, &m), BG_ERR_INVALID_ARGUMENT, "material = 4");
    expect_rejected(s, bg_scene_set_material(s, 1, NULL), BG_ERR_INVALID_ARGUMENT, "values");
    bg_material bad = bg_material_init(); bad.base.isotropy.value = 3;
    expect_rejected(s, bg_scene_set_material(s, 2, &bad), BG_ERR_INVALID_ARGUMENT, "material 2: base.isotropy.value = 3");
    /* The rejected set left material 2 as it was (textured). */
    assert_int_equal(bgi_scene_committed(s)->materials[1].base.reflectance.texture, 1);
    bg_scene_destroy(s);
}

static void test_object_validation(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    uint32_t id;
    bg_object_desc d;

    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), -1, 1, &id), BG_ERR_INVALID_ARGUMENT,
                    "bg_scene_add_sphere: radius = -1");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 0, 1, &id), BG_ERR_INVALID_ARGUMENT, "radius = 0");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), NAN, 1, &id), BG_ERR_INVALID_ARGUMENT, "radius");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, INFINITY, 0), 1, 1, &id), BG_ERR_INVALID_ARGUMENT, "center");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1, 9, &id), BG_ERR_INVALID_ARGUMENT, "material = 9");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1, 1, NULL), BG_ERR_INVALID_ARGUMENT, "out_object");
    expect_rejected(s, bg_scene_add_plane(s, bg_vec3_make(0, 0, 0), bg_vec3_make(0, 0, 0), 1, &id),
                    BG_ERR_INVALID_ARGUMENT, "normal");
    expect_rejected(s, bg_scene_add_plane(s, bg_vec3_make(NAN, 0, 0), bg_vec3_make(0, 1, 0), 1, &id),
                    BG_ERR_INVALID_ARGUMENT, "point");

    d = bg_object_desc_init((bg_shape)17, 1);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "shape = 17");
    d = bg_object_desc_init((bg_shape)-1, 1);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "shape");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.uv_mapping = (bg_uv_mapping)42;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "uv_mapping = 42");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.uv_scale[1] = 0;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "uv_scale[1]");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.uv_scale[0] = -2;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "uv_scale[0]");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.uv_scale[0] = INFINITY;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "uv_scale[0]");
    d = bg_object_desc_init(BG_SHAPE_BOX, 0);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "material = 0");
    d = bg_object_desc_init(BG_SHAPE_BOX, 3);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "material = 3");
    d = bg_object_desc_init(BG_SHAPE_CYLINDER, 1); d.transform = bg_mat4_scale(1, 0, 1);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform is singular");
    d = bg_object_desc_init(BG_SHAPE_CYLINDER, 1); d.transform = bg_mat4_scale(1, 1, 1e-13);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform is singular");
    /* The same slab turned: rotation does not hide it. */
    d = bg_object_desc_init(BG_SHAPE_CYLINDER, 1);
    d.transform = bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 1, 1), 40), bg_mat4_scale(1, 1, 1e-13));
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform is singular");
    /* Two rows almost parallel: singular for its scale, even though every entry is large. */
    d = bg_object_desc_init(BG_SHAPE_BOX, 1);
    d.transform.m[1][0] = 1; d.transform.m[1][1] = 1e-14; d.transform.m[0][0] = 1; d.transform.m[0][1] = 0;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform is singular");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.transform.m[2][1] = NAN;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.transform.m[0][3] = INFINITY;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform");
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.transform.m[3][0] = 0.5;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform is not affine");
    expect_rejected(s, bg_scene_add_object(s, NULL, &id), BG_ERR_INVALID_ARGUMENT, "desc");

    /* Scale-aware: a tiny but well-shaped object is fine. */
    d = bg_object_desc_init(BG_SHAPE_BOX, 1); d.transform = bg_mat4_scale(1e-9, 2e-9, 1e-9);
    assert_int_equal(add_object(s, d), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    /* set_transform */
    bg_mat4 flat = bg_mat4_scale(0, 1, 1), ok = bg_mat4_translate(1, 2, 3);
    expect_rejected(s, bg_scene_set_transform(s, 0, &ok), BG_ERR_INVALID_ARGUMENT, "object = 0");
    expect_rejected(s, bg_scene_set_transform(s, 99, &ok), BG_ERR_INVALID_ARGUMENT, "object = 99");
    expect_rejected(s, bg_scene_set_transform(s, 1, &flat), BG_ERR_INVALID_ARGUMENT, "object 1: transform is singular");
    expect_rejected(s, bg_scene_set_transform(s, 1, NULL), BG_ERR_INVALID_ARGUMENT, "transform");
    assert_true(bgi_scene_committed(s)->objects[0].to_world[0][0] == 1.0);
    bg_scene_destroy(s);
}

static void mat_times(const double a[4][4], const double b[4][4], double r[4][4]);

/* What commit derives per object is checked at add, through the same function: the three adds that
 * once passed and then blocked every commit (an inverse that overflowed or underflowed) are refused
 * where they are made, naming the field, and the scene goes on committing. */
static void test_add_refuses_what_commit_would(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    uint32_t id;
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, -2e300), 1e300, 1, &id), BG_ERR_INVALID_ARGUMENT,
                    "bg_scene_add_sphere: radius = 1e+300 is outside [1e-100, 1e100]");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1e-300, 1, &id), BG_ERR_INVALID_ARGUMENT,
                    "bg_scene_add_sphere: radius = 1e-300 is outside");
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_SPHERE, 1);
    d.transform = bg_mat4_scale(1e200, 1e200, 1e200);
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT,
                    "bg_scene_add_object: transform has an overall scale (|L|_F / sqrt 3) outside [1e-100, 1e100]: it is 1e+200");
    expect_rejected(s, bg_scene_set_transform(s, 1, &d.transform), BG_ERR_INVALID_ARGUMENT,
                    "bg_scene_set_transform: object 1: transform has an overall scale");
    /* The inverse and the world box are checked as commit derives them. */
    d.transform = bg_mat4_mul(bg_mat4_translate(1e300, 0, 0), bg_mat4_scale(1e-10, 1e-10, 1e-10));
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform has an inverse beyond the double range");
    expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(DBL_MAX, 0, 0), 1, 1, &id), BG_ERR_INVALID_ARGUMENT,
                    "bg_scene_add_sphere: transform (from center and radius) puts the world box beyond the double range (axis 0");
    d.transform = bg_mat4_translate(0, -DBL_MAX, 0);
    d.shape = BG_SHAPE_BOX;
    expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform puts the world box beyond the double range (axis 1");
    /* An unbounded plane has no world box to overflow. */
    d.shape = BG_SHAPE_PLANE;
    assert_int_equal(add_object(s, d), BG_OK);
    /* A good add after the refused ones commits. */
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, -2), 1, 1, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_int_equal(bgi_scene_committed(s)->object_count, 4);
    bg_scene_destroy(s);
}

/* The accepted overall scale is [1e-100, 1e100], both ends included; within it the singularity
 * test ignores scale and the committed inverse is exact to rounding. */
static void test_object_scale_range(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    uint32_t id;
    const double inside[] = {1e100, 1e-100, 3e99, 2e-99};
    for (size_t i = 0; i < sizeof inside / sizeof inside[0]; i++) {
        double k = inside[i];
        bg_object_desc d = bg_object_desc_init(BG_SHAPE_BOX, 1);
        d.transform = bg_mat4_mul(bg_mat4_translate(k, 0, 0), bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 2, 3), 30),
                                                                          bg_mat4_scale(k, 0.5 * k, k)));
        if (i < 2)
            d.transform = bg_mat4_scale(k, k, k);
        assert_int_equal(add_object(s, d), BG_OK);
        assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), k, 1, &id), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
        const bg_scene_state *st = bgi_scene_committed(s);
        const bg_object_data *o = &st->objects[st->object_count - 2];
        double p[4][4];
        mat_times(o->to_world, o->to_object, p);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                assert_true(fabs(p[r][c] - (r == c)) < 1e-12);
        if (i < 2)
            assert_true(fabs(o->to_object[0][0] * k - 1) < 1e-15);
    }
    const double outside[] = {1.01e100, 0.99e-100, 1e101, 1e-101};
    for (size_t i = 0; i < sizeof outside / sizeof outside[0]; i++) {
        double k = outside[i];
        bg_object_desc d = bg_object_desc_init(BG_SHAPE_BOX, 1);
        d.transform = bg_mat4_scale(k, k, k);
        expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform has an overall scale");
        expect_rejected(s, bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), k, 1, &id), BG_ERR_INVALID_ARGUMENT, "radius");
    }
    /* Scale-free singularity at both ends: a slab 1e-14 of its size is singular, 1e-11 is not. */
    const double ends[] = {1e100, 2e-100}; /* s = 0.82 k for these slabs */
    for (size_t i = 0; i < 2; i++) {
        double k = ends[i];
        bg_object_desc d = bg_object_desc_init(BG_SHAPE_BOX, 1);
        d.transform = bg_mat4_scale(k, k, 1e-14 * k);
        expect_rejected(s, add_object(s, d), BG_ERR_INVALID_ARGUMENT, "transform is singular");
        d.transform = bg_mat4_scale(k, k, 1e-11 * k);
        assert_int_equal(add_object(s, d), BG_OK);
        assert_int_equal(bg_scene_commit(s), BG_OK);
    }
    bg_scene_destroy(s);
}

static void test_camera_validation(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    bg_camera c;
    c = bg_camera_init(); c.look_at = c.position;
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "look_at equals position");
    c = bg_camera_init(); c.up = bg_vec3_make(0, 0, 2);
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "up = (0, 0, 2) is parallel");
    c = bg_camera_init(); c.up = bg_vec3_make(0, 0, 0);
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "up");
    c = bg_camera_init(); c.fov_y_degrees = 0;
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "fov_y_degrees = 0");
    c = bg_camera_init(); c.fov_y_degrees = 180;
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "fov_y_degrees = 180");
    c = bg_camera_init(); c.fov_y_degrees = NAN;
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "fov_y_degrees");
    c = bg_camera_init(); c.position.x = INFINITY;
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "position");
    c = bg_camera_init(); c.look_at.z = NAN;
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "look_at");
    expect_rejected(s, bg_scene_set_camera(s, NULL), BG_ERR_INVALID_ARGUMENT, "camera");
    /* The camera is unchanged by the rejected calls. */
    assert_true(bgi_scene_committed(s)->camera.camera.position.z == 5.0);
    c = bg_camera_init(); c.position = bg_vec3_make(0, 0, 1.5e308); c.look_at = bg_vec3_make(0, 0, -1.5e308);
    expect_rejected(s, set_camera(s, c), BG_ERR_INVALID_ARGUMENT, "look_at - position overflows");
    /* Vectors whose length overflows a double, though each component is finite, are fine: the
     * check normalises them as the commit does. */
    c = bg_camera_init(); c.position = bg_vec3_make(1.5e308, 0, 1.5e308); c.up = bg_vec3_make(0, DBL_MAX, DBL_MAX);
    assert_int_equal(set_camera(s, c), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_camera_data *cd = &bgi_scene_committed(s)->camera;
    assert_true(fabs(cd->forward[0] + sqrt(0.5)) < 1e-15 && fabs(cd->forward[2] + sqrt(0.5)) < 1e-15);
    assert_true(cd->up[1] > 0.5);
    c = bg_camera_init(); c.fov_y_degrees = 179.5;
    assert_int_equal(set_camera(s, c), BG_OK);
    bg_scene_destroy(s);
}

static void test_light_validation(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    bg_light l;
    l = bg_light_init(); l.type = (bg_light_type)7;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "type = 7");
    l = bg_light_init(); l.attenuation[1] = -0.1;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "attenuation");
    l = bg_light_init(); l.attenuation[0] = 0;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "attenuation = (0, 0, 0)");
    l = bg_light_init(); l.attenuation[2] = NAN;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "attenuation");
    double bad_cutoffs[] = {0, -10, 90.5, 120, 179, 181, NAN};
    for (size_t i = 0; i < sizeof bad_cutoffs / sizeof bad_cutoffs[0]; i++) {
        l = bg_light_init(); l.spot_cutoff_degrees = bad_cutoffs[i];
        expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "spot_cutoff_degrees");
    }
    l = bg_light_init(); l.spot_exponent = -1;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "spot_exponent");
    l = bg_light_init(); l.color[1] = -0.2;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "color");
    l = bg_light_init(); l.intensity = NAN;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "intensity");
    l = bg_light_init(); l.intensity = -1;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "intensity");
    l = bg_light_init(); l.position.y = -INFINITY;
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "position");
    l = bg_light_init(); l.type = BG_LIGHT_DIRECTIONAL; l.direction = bg_vec3_make(0, 0, 0);
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "direction");
    l = bg_light_init(); l.spot_cutoff_degrees = 30; l.direction = bg_vec3_make(0, 0, 0);
    expect_rejected(s, add_light(s, l), BG_ERR_INVALID_ARGUMENT, "direction");
    uint32_t id;
    expect_rejected(s, bg_scene_add_light(s, NULL, &id), BG_ERR_INVALID_ARGUMENT, "light");
    l = bg_light_init();
    expect_rejected(s, bg_scene_set_light(s, 2, &l), BG_ERR_INVALID_ARGUMENT, "light = 2");
    l.attenuation[0] = 0;
    expect_rejected(s, bg_scene_set_light(s, 1, &l), BG_ERR_INVALID_ARGUMENT, "light 1: attenuation");
    double neg[3] = {0.1, -0.1, 0.1}, nan3[3] = {NAN, 0, 0};
    expect_rejected(s, bg_scene_set_ambient(s, neg), BG_ERR_INVALID_ARGUMENT, "bg_scene_set_ambient: rgb");
    expect_rejected(s, bg_scene_set_ambient(s, nan3), BG_ERR_INVALID_ARGUMENT, "rgb");
    expect_rejected(s, bg_scene_set_ambient(s, NULL), BG_ERR_INVALID_ARGUMENT, "rgb");
    /* Accepted edges: cutoff 90 and 180, a point light with a zero (unused) direction. */
    l = bg_light_init(); l.spot_cutoff_degrees = 90;
    assert_int_equal(add_light(s, l), BG_OK);
    l = bg_light_init(); l.direction = bg_vec3_make(0, 0, 0);
    assert_int_equal(add_light(s, l), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    assert_int_equal(st->light_count, 3);
    assert_true(st->lights[0].position.x == 3.0); /* rejected set_light changed nothing */
    assert_true(fabs(st->lights[2].direction.y + 1.0) < 1e-15);
    bg_scene_destroy(s);
}

static void test_texture_validation(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    float fpx[4 * 4] = {0};
    unsigned char px[8 * 4] = {0};
    uint32_t id;
    bg_image img;
#define IMG(w, h, f, stride, p) (img = (bg_image){w, h, f, stride, p}, &img)
    expect_rejected(s, bg_scene_add_texture(s, IMG(0, 1, BG_PIXEL_RGBA8, 0, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "width = 0");
    expect_rejected(s, bg_scene_add_texture(s, IMG(-3, 1, BG_PIXEL_RGBA8, 0, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "width = -3");
    expect_rejected(s, bg_scene_add_texture(s, IMG(16385, 1, BG_PIXEL_RGBA8, 0, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "width = 16385");
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 0, BG_PIXEL_RGBA8, 0, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "height = 0");
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 100000, BG_PIXEL_RGBA8, 0, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "height");
    expect_rejected(s, bg_scene_add_texture(s, IMG(2, 2, BG_PIXEL_RGBA8, 7, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "stride = 7");
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, BG_PIXEL_RGBA32F, 8, fpx), NULL, &id), BG_ERR_INVALID_ARGUMENT, "stride");
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, (bg_pixel_format)9, 0, px), NULL, &id), BG_ERR_INVALID_ARGUMENT, "format = 9");
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, BG_PIXEL_RGBA8, 0, NULL), NULL, &id), BG_ERR_INVALID_ARGUMENT, "pixels");
    expect_rejected(s, bg_scene_add_texture(s, NULL, NULL, &id), BG_ERR_INVALID_ARGUMENT, "image");
    bg_texture_desc d = {(bg_texture_wrap)5, BG_TEXTURE_SRGB, BG_FILTER_LINEAR};
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, BG_PIXEL_RGBA8, 0, px), &d, &id), BG_ERR_INVALID_ARGUMENT, "wrap = 5");
    d.wrap = BG_WRAP_CLAMP; d.encoding = (bg_texture_encoding)7;
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, BG_PIXEL_RGBA8, 0, px), &d, &id), BG_ERR_INVALID_ARGUMENT, "encoding = 7");
    d.encoding = BG_TEXTURE_SRGB; d.filter = (bg_texture_filter)3;
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, BG_PIXEL_RGBA8, 0, px), &d, &id), BG_ERR_INVALID_ARGUMENT, "desc.filter = 3");
    fpx[6] = NAN;
    expect_rejected(s, bg_scene_add_texture(s, IMG(2, 2, BG_PIXEL_RGBA32F, 0, fpx), NULL, &id), BG_ERR_INVALID_ARGUMENT, "pixel (1, 0) channel 2");
    fpx[6] = -1;
    expect_rejected(s, bg_scene_add_texture(s, IMG(2, 2, BG_PIXEL_RGBA32F, 0, fpx), NULL, &id), BG_ERR_INVALID_ARGUMENT, "pixel");
    expect_rejected(s, bg_scene_add_texture(s, IMG(1, 1, BG_PIXEL_RGBA8, 0, px), NULL, NULL), BG_ERR_INVALID_ARGUMENT, "out_texture");
#undef IMG
    bg_scene_destroy(s);
}

/* ---- commit ---- */

static void mat_times(const double a[4][4], const double b[4][4], double r[4][4])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            r[i][j] = 0;
            for (int k = 0; k < 4; k++)
                r[i][j] += a[i][k] * b[k][j];
        }
}

static void test_commit_inverse_and_normal_matrix(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_BOX, 1);
    d.transform = bg_mat4_mul(bg_mat4_translate(3, -2, 7),
                              bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 2, 3), 37),
                                          bg_mat4_scale(0.25, 4, 1.5)));
    assert_int_equal(add_object(s, d), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_object_data *o = &bgi_scene_committed(s)->objects[2];
    double p[4][4], q[4][4];
    mat_times(o->to_world, o->to_object, p);
    mat_times(o->to_object, o->to_world, q);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            assert_true(fabs(p[i][j] - (i == j)) < 1e-12);
            assert_true(fabs(q[i][j] - (i == j)) < 1e-12);
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            assert_true(o->normal_to_world[i][j] == o->to_object[j][i]);
    /* A normal stays perpendicular to a transformed tangent: prototype face x = 1 has normal
     * (1, 0, 0) and tangent (0, 1, 0). */
    double t[3], n[3];
    for (int i = 0; i < 3; i++) {
        t[i] = o->to_world[i][1];
        n[i] = o->normal_to_world[i][0];
    }
    assert_true(fabs(t[0] * n[0] + t[1] * n[1] + t[2] * n[2]) < 1e-12);
    bg_scene_destroy(s);
}

static void expect_box(const bg_object_data *o, double x0, double y0, double z0, double x1, double y1, double z1)
{
    const double want_lo[3] = {x0, y0, z0}, want_hi[3] = {x1, y1, z1};
    assert_true(o->bounded);
    for (int i = 0; i < 3; i++) {
        if (!(o->bounds_min[i] <= want_lo[i] && o->bounds_min[i] > want_lo[i] - 1e-9) ||
            !(o->bounds_max[i] >= want_hi[i] && o->bounds_max[i] < want_hi[i] + 1e-9))
            fail_msg("axis %d: [%.17g, %.17g], want [%.17g, %.17g]", i, o->bounds_min[i], o->bounds_max[i],
                     want_lo[i], want_hi[i]);
    }
}

static void test_commit_bounds(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat, id;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    bg_vec3 z = bg_vec3_make(0, 0, 1), y = bg_vec3_make(0, 1, 0);
    /* Sphere scaled (2, 1, 0.5), turned 90 degrees about z, moved to (1, 2, 3). */
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_SPHERE, mat);
    d.transform = bg_mat4_mul(bg_mat4_translate(1, 2, 3), bg_mat4_mul(bg_mat4_rotate(z, 90), bg_mat4_scale(2, 1, 0.5)));
    assert_int_equal(add_object(s, d), BG_OK);
    /* Sphere scaled (2, 1, 1), turned 45 degrees about z: the exact extent is sqrt(2.5) in x and y. */
    d.transform = bg_mat4_mul(bg_mat4_rotate(z, 45), bg_mat4_scale(2, 1, 1));
    assert_int_equal(add_object(s, d), BG_OK);
    /* Unit box turned 45 degrees about y: sqrt(2) in x and z, 1 in y. */
    d = bg_object_desc_init(BG_SHAPE_BOX, mat);
    d.transform = bg_mat4_mul(bg_mat4_translate(0, -5, 0), bg_mat4_rotate(y, 45));
    assert_int_equal(add_object(s, d), BG_OK);
    /* Rectangle: flat in y. */
    d = bg_object_desc_init(BG_SHAPE_RECTANGLE, mat);
    d.transform = bg_mat4_scale(3, 1, 2);
    assert_int_equal(add_object(s, d), BG_OK);
    /* Cylinder laid along x (rotated 90 about z), length 2 * 4, radius 1. */
    d = bg_object_desc_init(BG_SHAPE_CYLINDER, mat);
    d.transform = bg_mat4_mul(bg_mat4_rotate(z, 90), bg_mat4_scale(1, 4, 1));
    assert_int_equal(add_object(s, d), BG_OK);
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0, -10, 0), y, mat, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    double r = sqrt(2.5), q = sqrt(2.0);
    expect_box(&st->objects[0], 0, 0, 2.5, 2, 4, 3.5);
    expect_box(&st->objects[1], -r, -r, -1, r, r, 1);
    expect_box(&st->objects[2], -q, -6, -q, q, -4, q);
    expect_box(&st->objects[3], -3, 0, -2, 3, 0, 2);
    expect_box(&st->objects[4], -4, -1, -1, 4, 1, 1);
    assert_false(st->objects[5].bounded);
    assert_true(st->has_bounded_objects);
    /* The scene box is the union of the bounded ones; the plane does not widen it. */
    assert_true(fabs(st->bounds_min[0] + 4) < 1e-9 && fabs(st->bounds_max[0] - 4) < 1e-9);
    assert_true(fabs(st->bounds_min[1] + 6) < 1e-9 && fabs(st->bounds_max[1] - 4) < 1e-9);
    assert_true(fabs(st->bounds_min[2] + 2) < 1e-9 && fabs(st->bounds_max[2] - 3.5) < 1e-9);
    bg_scene_destroy(s);
}

static void test_commit_resolves_uv_mapping(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    uint32_t mat;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    const bg_uv_mapping want[BG_SHAPE_COUNT_] = {BG_UV_SPHERICAL, BG_UV_PLANAR, BG_UV_BOX, BG_UV_CYLINDRICAL, BG_UV_PLANAR};
    for (int i = 0; i < BG_SHAPE_COUNT_; i++)
        assert_int_equal(add_object(s, bg_object_desc_init((bg_shape)i, mat)), BG_OK);
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_SPHERE, mat);
    d.uv_mapping = BG_UV_BOX;
    d.uv_scale[0] = 3;
    d.casts_shadows = false;
    assert_int_equal(add_object(s, d), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    for (int i = 0; i < BG_SHAPE_COUNT_; i++) {
        assert_int_equal(st->objects[i].uv_mapping, want[i]);
        assert_int_equal(st->objects[i].shape, i);
        assert_true(st->objects[i].casts_shadows);
        assert_int_equal(st->objects[i].material, 0);
    }
    assert_int_equal(st->objects[5].uv_mapping, BG_UV_BOX);
    assert_true(st->objects[5].uv_scale[0] == 3.0 && st->objects[5].uv_scale[1] == 1.0);
    assert_false(st->objects[5].casts_shadows);
    bg_scene_destroy(s);
}

static void test_commit_camera_and_lights(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    const bg_camera_data *c = &bgi_scene_committed(s)->camera;
    assert_true(fabs(c->forward[2] + 1) < 1e-15 && fabs(c->right[0] - 1) < 1e-15 && fabs(c->up[1] - 1) < 1e-15);
    assert_true(fabs(c->half_y - tan(22.5 * 3.14159265358979323846 / 180)) < 1e-15);
    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(10, 0, 0);
    cam.up = bg_vec3_make(0, 3, 0.5); /* not perpendicular: the basis makes it so */
    cam.fov_y_degrees = 90;
    assert_int_equal(bg_scene_set_camera(s, &cam), BG_OK);
    bg_light sun = bg_light_init();
    sun.type = BG_LIGHT_DIRECTIONAL;
    sun.direction = bg_vec3_make(0, -2, 0);
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &sun, &id), BG_OK);
    double amb[3] = {0.2, 0.3, 0.4};
    assert_int_equal(bg_scene_set_ambient(s, amb), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    c = &st->camera;
    assert_true(fabs(c->forward[0] + 1) < 1e-15);
    double dots[3] = {
        c->forward[0] * c->right[0] + c->forward[1] * c->right[1] + c->forward[2] * c->right[2],
        c->forward[0] * c->up[0] + c->forward[1] * c->up[1] + c->forward[2] * c->up[2],
        c->right[0] * c->up[0] + c->right[1] * c->up[1] + c->right[2] * c->up[2]};
    for (int i = 0; i < 3; i++)
        assert_true(fabs(dots[i]) < 1e-15);
    /* Right-handed: right x up = -forward. */
    double fx = c->right[1] * c->up[2] - c->right[2] * c->up[1];
    assert_true(fabs(fx + c->forward[0]) < 1e-15);
    assert_true(c->up[1] > 0.9);
    assert_true(fabs(c->half_y - 1.0) < 1e-15);
    assert_true(st->lights[1].direction.x == 0 && st->lights[1].direction.y == -1 && st->lights[1].direction.z == 0);
    /* A direction whose length overflows a double still normalises (not to zero). */
    sun.direction = bg_vec3_make(DBL_MAX, -DBL_MAX, DBL_MAX);
    assert_int_equal(bg_scene_set_light(s, id, &sun), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    double third = 1 / sqrt(3.0);
    assert_true(fabs(st->lights[1].direction.x - third) < 1e-15 && fabs(st->lights[1].direction.y + third) < 1e-15);
    assert_true(st->ambient[0] == 0.2 && st->ambient[2] == 0.4);
    bg_scene_destroy(s);
}

static void test_cheap_recommit(void **state)
{
    (void)state;
    util_alloc_counter a = UTIL_ALLOC_COUNTER;
    bg_scene *s = counted_scene(&a);
    bg_material m = bg_material_init();
    uint32_t mat, obj, light;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1, mat, &obj), BG_OK);
    bg_light l = bg_light_init();
    assert_int_equal(bg_scene_add_light(s, &l, &light), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    const bg_object_data *objects = st->objects;
    const bg_material *materials = st->materials;
    const bg_light *lights = st->lights;
    long allocs = a.allocs, frees = a.frees;

    m.base.reflectance.r = 0.25;
    assert_int_equal(bg_scene_set_material(s, mat, &m), BG_OK);
    l.intensity = 3;
    assert_int_equal(bg_scene_set_light(s, light, &l), BG_OK);
    bg_mat4 t = bg_mat4_translate(0, 4, 0);
    assert_int_equal(bg_scene_set_transform(s, obj, &t), BG_OK);
    /* Values change only at commit. */
    assert_true(st->materials[0].base.reflectance.r == 0.8);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    assert_ptr_equal(bgi_scene_committed(s), st);
    assert_int_equal(st->commit_count, 2);
    assert_ptr_equal(st->objects, objects);
    assert_ptr_equal(st->materials, materials);
    assert_ptr_equal(st->lights, lights);
    assert_int_equal(a.allocs, allocs);
    assert_int_equal(a.frees, frees);
    assert_true(st->materials[0].base.reflectance.r == 0.25);
    assert_true(st->lights[0].intensity == 3);
    assert_true(st->objects[0].to_world[1][3] == 4 && st->objects[0].to_object[1][3] == -4);
    assert_true(fabs(st->objects[0].bounds_min[1] - 3) < 1e-9);
    bg_scene_destroy(s);
    assert_int_equal(a.allocs, a.frees);
}

/* ---- math ---- */

static void test_math_helpers(void **state)
{
    (void)state;
    bg_mat4 r = bg_mat4_rotate(bg_vec3_make(0, 0, 2), 90); /* axis normalised inside */
    assert_true(r.m[0][0] == 0 && r.m[1][0] == 1 && r.m[0][1] == -1 && r.m[1][1] == 0); /* x -> y exactly */
    bg_mat4 id = bg_mat4_rotate(bg_vec3_make(0, 0, 0), 33);
    bg_mat4 i4 = bg_mat4_identity();
    assert_memory_equal(&id, &i4, sizeof id);
    /* mul(a, b) applies b first: scale then translate moves the origin by the translation only. */
    bg_mat4 ts = bg_mat4_mul(bg_mat4_translate(1, 2, 3), bg_mat4_scale(2, 2, 2));
    assert_true(ts.m[0][3] == 1 && ts.m[0][0] == 2);
    bg_mat4 st = bg_mat4_mul(bg_mat4_scale(2, 2, 2), bg_mat4_translate(1, 2, 3));
    assert_true(st.m[0][3] == 2 && st.m[2][3] == 6);
    bg_mat4 rr = bg_mat4_rotate(bg_vec3_make(1, 1, 0), 30);
    bg_mat4 back = bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 1, 0), -30), rr);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            assert_true(fabs(back.m[i][j] - (i == j)) < 1e-15);
    bg_vec3 v = bg_vec3_make(1, -2, 3);
    assert_true(v.x == 1 && v.y == -2 && v.z == 3);
}

/* The plane shorthand: the prototype's y axis becomes the normal, the frame stays right-handed
 * and a floor gets the identity frame. */
static void test_plane_frame(void **state)
{
    (void)state;
    bg_scene *s = small_scene();
    const bg_vec3 normals[] = {{0, 0, 1}, {1, 0, 0}, {0, -3, 0}, {1, 2, 3}};
    uint32_t id;
    for (size_t i = 0; i < 4; i++)
        assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(1, 2, 3), normals[i], 1, &id), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    const bg_scene_state *st = bgi_scene_committed(s);
    const bg_object_data *floor = &st->objects[1];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            assert_true(floor->to_world[i][j] == (i == j));
    for (size_t k = 0; k < 4; k++) {
        const bg_object_data *o = &st->objects[2 + k];
        double n = sqrt(normals[k].x * normals[k].x + normals[k].y * normals[k].y + normals[k].z * normals[k].z);
        assert_true(fabs(o->to_world[0][1] - normals[k].x / n) < 1e-15);
        assert_true(fabs(o->to_world[1][1] - normals[k].y / n) < 1e-15);
        assert_true(fabs(o->to_world[2][1] - normals[k].z / n) < 1e-15);
        assert_true(o->to_world[0][3] == 1 && o->to_world[1][3] == 2 && o->to_world[2][3] == 3);
        const double (*m)[4] = o->to_world;
        double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        assert_true(fabs(det - 1) < 1e-12);
        assert_false(o->bounded);
    }
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_status_strings),
        cmocka_unit_test(test_not_committed_before_first_commit),
        cmocka_unit_test(test_pending_changes_invisible_until_commit),
        cmocka_unit_test(test_allocator_hooks),
        cmocka_unit_test(test_out_of_memory_leaves_scene_intact),
        cmocka_unit_test(test_logger_and_sticky_error),
        cmocka_unit_test(test_material_validation),
        cmocka_unit_test(test_object_validation),
        cmocka_unit_test(test_add_refuses_what_commit_would),
        cmocka_unit_test(test_object_scale_range),
        cmocka_unit_test(test_camera_validation),
        cmocka_unit_test(test_light_validation),
        cmocka_unit_test(test_texture_validation),
        cmocka_unit_test(test_commit_inverse_and_normal_matrix),
        cmocka_unit_test(test_commit_bounds),
        cmocka_unit_test(test_commit_resolves_uv_mapping),
        cmocka_unit_test(test_commit_camera_and_lights),
        cmocka_unit_test(test_cheap_recommit),
        cmocka_unit_test(test_math_helpers),
        cmocka_unit_test(test_plane_frame),
    };
    return cmocka_run_group_tests_name("bg_scene", tests, NULL, NULL);
}
