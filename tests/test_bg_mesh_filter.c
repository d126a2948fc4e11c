/* Cut-outs (bg_material.coverage_cutoff, glTF's alphaMode MASK) and front-only meshes
 * (BG_SIDES_FRONT, glTF's doubleSided false) in the CPU reference and every GPU plan: a quad with a
 * hole over a red floor, seen from above under a light above it, shows the lit floor through the
 * hole and casts a shadow with a lit hole; a front-only quad is seen from its front and not from
 * its back, and a mirroring transform keeps its front; an open quad's back is lit as a front. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "util_gl.h"
#include "util_gpu.h"

enum { W = 64, H = 64 };

/* The quad x, z in [-1, 1] at y = 0 in object space, its front +y, texture coordinates over it. */
static const float quad_positions[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
static const float quad_uvs[] = {0, 0, 1, 0, 1, 1, 0, 1};
static const uint32_t quad_indices[] = {0, 2, 1, 0, 3, 2};

static bg_scene *new_scene(bg_vec3 eye, bg_vec3 up, double light_y)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    const double ambient[3] = {0.1, 0.1, 0.1};
    assert_int_equal(bg_scene_set_ambient(s, ambient), BG_OK);
    bg_camera c = bg_camera_init();
    c.position = eye;
    c.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    c.up = up;
    c.fov_y_degrees = 60.0;
    assert_int_equal(bg_scene_set_camera(s, &c), BG_OK);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(0.0, light_y, 0.0);
    uint32_t id;
    assert_int_equal(bg_scene_add_light(s, &l, &id), BG_OK);
    return s;
}

static uint32_t diffuse(bg_scene *s, double r, double g, double b, const bg_material *from)
{
    bg_material m = from ? *from : bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    uint32_t id;
    if (bg_scene_add_material(s, &m, &id) != BG_OK)
        fail_msg("bg_scene_add_material: %s", bg_scene_error_message(s));
    return id;
}

static void add_quad(bg_scene *s, uint32_t material, bg_mat4 transform)
{
    bg_mesh_desc d = bg_mesh_desc_init(material);
    d.positions = quad_positions;
    d.vertex_count = 4;
    d.indices = quad_indices;
    d.triangle_count = 2;
    d.uvs = quad_uvs;
    d.transform = transform;
    uint32_t id;
    if (bg_scene_add_mesh(s, &d, &id) != BG_OK)
        fail_msg("bg_scene_add_mesh: %s", bg_scene_error_message(s));
}

/* A 4 x 4 coverage texture: alpha 0 on the middle 2 x 2 texels, 1 elsewhere. */
static uint32_t hole_texture(bg_scene *s, bg_texture_filter filter)
{
    float texels[4 * 4 * 4];
    for (int i = 0; i < 16; i++) {
        int x = i % 4, y = i / 4;
        bool hole = x >= 1 && x <= 2 && y >= 1 && y <= 2;
        texels[4 * i] = texels[4 * i + 1] = texels[4 * i + 2] = 1.0f;
        texels[4 * i + 3] = hole ? 0.0f : 1.0f;
    }
    bg_image img = {4, 4, BG_PIXEL_RGBA32F, 0, texels};
    bg_texture_desc td = {BG_WRAP_CLAMP, BG_TEXTURE_LINEAR, filter};
    uint32_t id;
    assert_int_equal(bg_scene_add_texture(s, &img, &td, &id), BG_OK);
    return id;
}

static bg_mat4 translate_y(double y, double scale_y)
{
    bg_mat4 m = bg_mat4_identity();
    m.m[1][1] = scale_y;
    m.m[1][3] = y;
    return m;
}

static void commit(bg_scene *s)
{
    if (bg_scene_commit(s) != BG_OK)
        fail_msg("bg_scene_commit: %s", bg_scene_error_message(s));
}

/* The renderers compared: the CPU reference first, then every GPU plan. */
static const bg_gpu_plan plans[] = {BG_PLAN_FUSED_TREE, BG_PLAN_FUSED, BG_PLAN_MULTIPASS};
#define RENDERERS (1 + (int)(sizeof plans / sizeof plans[0]))
static const char *const renderer_name[RENDERERS] = {"cpu", "tree", "fused", "multipass"};

/* Renderer k's image of s (RGBA8, W x H, rows top first): k 0 the CPU, else plans[k - 1]. */
static unsigned char *render(bg_scene *s, int k)
{
    bg_render_settings set = bg_render_settings_init();
    set.threads = 2;
    return k == 0 ? util_cpu_reference(s, &set, W, H) : util_gpu_plan_image(s, &set, plans[k - 1], W, H, renderer_name[k]);
}

static const unsigned char *at(const unsigned char *px, int x, int y)
{
    return px + 4 * (y * W + x);
}

/* Pixels whose largest channel differs by more than 8 between two images. */
static int differing(const unsigned char *a, const unsigned char *b)
{
    int n = 0;
    for (int i = 0; i < W * H; i++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int e = abs((int)a[4 * i + c] - (int)b[4 * i + c]);
            worst = e > worst ? e : worst;
        }
        n += worst > 8;
    }
    return n;
}

static bool reddish(const unsigned char *p)
{
    return p[0] > 2 * p[1] + 20 && p[0] > 2 * p[2] + 20;
}

static bool greenish(const unsigned char *p)
{
    return p[1] > 2 * p[0] + 20 && p[1] > 2 * p[2] + 20;
}

/* Seen straight down from (0, 6, 0) with 60 degrees, the floor's point (x, 0, z) is at pixel
 * W / 2 + x / (6 tan 30) W / 2 (and the quad at height 1 is 6/5 as wide). */
static int column_of(double x, double height)
{
    return (int)(W / 2.0 + x / ((6.0 - height) * 0.57735026918962576) * W / 2.0);
}

static void cut_out_quad_over_a_floor(bg_texture_filter filter)
{
    bg_scene *s = new_scene(bg_vec3_make(0.0, 6.0, 0.0), bg_vec3_make(0.0, 0.0, -1.0), 5.0);
    uint32_t floor_id;
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0.0, 0.0, 0.0), bg_vec3_make(0.0, 1.0, 0.0),
                                        diffuse(s, 0.8, 0.1, 0.1, NULL), &floor_id),
                     BG_OK);
    bg_material cut = bg_material_init();
    cut.coverage.texture = hole_texture(s, filter);
    cut.coverage.channel = 3;
    cut.coverage_cutoff = 0.5;
    add_quad(s, diffuse(s, 0.1, 0.8, 0.1, &cut), translate_y(1.0, 1.0));
    commit(s);

    unsigned char *img[RENDERERS];
    for (int k = 0; k < RENDERERS; k++) {
        img[k] = render(s, k);
        const unsigned char *centre = at(img[k], W / 2, H / 2);
        /* Through the hole: the floor, lit through the same hole (its shadow has a hole too). */
        print_message("%s: centre (%d, %d, %d)\n", renderer_name[k], centre[0], centre[1], centre[2]);
        assert_true(reddish(centre));
        assert_true(centre[0] > 120);
        /* The quad around the hole (x = 0.75 on the quad at height 1). */
        assert_true(greenish(at(img[k], column_of(0.75, 1.0), H / 2)));
        /* The floor just outside the quad lies in its shadow (x = 1.1, the shadow reaching 1.25);
         * further out it is lit. */
        const unsigned char *shade = at(img[k], column_of(1.12, 0.0), H / 2);
        const unsigned char *lit = at(img[k], column_of(1.6, 0.0), H / 2);
        if (getenv("BG_TEST_DUMP")) {
            char name[64];
            snprintf(name, sizeof name, "/tmp/filter_%s.png", renderer_name[k]);
            bg_image out = {W, H, BG_PIXEL_RGBA8, 0, img[k]};
            bg_png_save(name, &out, NULL, 0);
            print_message("shade (%d, %d) %d, lit (%d) %d\n", column_of(1.12, 0.0), H / 2, shade[0], column_of(1.6, 0.0), lit[0]);
        }
        assert_true(reddish(lit));
        assert_true(shade[0] < lit[0] / 2); /* sRGB: ambient alone is about 92 of 228 */
        if (k > 0) {
            int n = differing(img[0], img[k]);
            print_message("%s against the cpu: %d pixels differ by more than 8\n", renderer_name[k], n);
            assert_true(n <= W * H / 100); /* the hole's edge may fall on either side in float */
        }
    }
    for (int k = 0; k < RENDERERS; k++)
        free(img[k]);
    bg_scene_destroy(s);
}

static void cut_out_nearest(void **state)
{
    (void)state;
    cut_out_quad_over_a_floor(BG_FILTER_NEAREST);
}

static void cut_out_linear(void **state)
{
    (void)state;
    cut_out_quad_over_a_floor(BG_FILTER_LINEAR);
}

/* The green channel at the centre of a green quad seen from above or below, its material given
 * sides, lit from the side the camera is on; mirrored flips y. */
static int quad_green(bg_mesh_sides sides, bool from_above, bool mirrored, int k)
{
    double y = from_above ? 6.0 : -6.0;
    bg_scene *s = new_scene(bg_vec3_make(0.0, y, 0.0), bg_vec3_make(0.0, 0.0, -1.0), 5.0 / 6.0 * y);
    bg_material m = bg_material_init();
    m.sides = sides;
    add_quad(s, diffuse(s, 0.1, 0.8, 0.1, &m), translate_y(0.0, mirrored ? -1.0 : 1.0));
    commit(s);
    unsigned char *px = render(s, k);
    int green = at(px, W / 2, H / 2)[1];
    free(px);
    bg_scene_destroy(s);
    return green;
}

static void front_only_quad_is_seen_from_its_front(void **state)
{
    (void)state;
    for (int k = 0; k < RENDERERS; k++) {
        int front = quad_green(BG_SIDES_FRONT, true, false, k);
        print_message("%s: front-only quad from its front %d\n", renderer_name[k], front);
        assert_true(front > 150);
        assert_int_equal(quad_green(BG_SIDES_FRONT, false, false, k), 0);
        /* Mirrored in y, its front faces down: the front is the side of the mesh's own winding
         * (glTF reverses the world winding under a negative determinant to keep it so). */
        assert_true(quad_green(BG_SIDES_FRONT, false, true, k) > 150);
        assert_int_equal(quad_green(BG_SIDES_FRONT, true, true, k), 0);
    }
}

/* Seen from below and lit from below: a solid's back is its inside, which direct light does not
 * reach (ambient alone, about 0.1 x 0.8 of green); an open quad's back is lit as its front is. */
static void open_quad_is_lit_on_its_back(void **state)
{
    (void)state;
    for (int k = 0; k < RENDERERS; k++) {
        int solid = quad_green(BG_SIDES_SOLID, false, false, k), open = quad_green(BG_SIDES_BOTH, false, false, k);
        int open_front = quad_green(BG_SIDES_BOTH, true, false, k);
        print_message("%s: back of a solid %d, of an open quad %d, its front %d\n", renderer_name[k], solid, open,
                      open_front);
        assert_true(solid > 0 && solid < 110);
        assert_true(open > 150);
        assert_true(abs(open - open_front) <= 1);
    }
}

/* The floor's brightness (red) just outside a front-only quad at height 1, in the quad's shadow
 * when its front faces the light above; mirrored, its front faces down. */
static int shadow_red(bool mirrored, int k)
{
    bg_scene *s = new_scene(bg_vec3_make(0.0, 6.0, 0.0), bg_vec3_make(0.0, 0.0, -1.0), 5.0);
    uint32_t floor_id;
    assert_int_equal(bg_scene_add_plane(s, bg_vec3_make(0.0, 0.0, 0.0), bg_vec3_make(0.0, 1.0, 0.0),
                                        diffuse(s, 0.8, 0.1, 0.1, NULL), &floor_id),
                     BG_OK);
    bg_material m = bg_material_init();
    m.sides = BG_SIDES_FRONT;
    add_quad(s, diffuse(s, 0.1, 0.8, 0.1, &m), translate_y(1.0, mirrored ? -1.0 : 1.0));
    commit(s);
    unsigned char *px = render(s, k);
    int red = at(px, column_of(1.12, 0.0), H / 2)[0];
    free(px);
    bg_scene_destroy(s);
    return red;
}

/* A shadow segment runs from the point to the light, but light travels it the other way: what
 * counts is the side the light sees. A leaf lit on its front shadows the floor; lit from behind, it
 * lets the light through. */
static void front_only_shadows_by_the_side_the_light_sees(void **state)
{
    (void)state;
    for (int k = 0; k < RENDERERS; k++) {
        int front_lit = shadow_red(false, k), back_lit = shadow_red(true, k);
        print_message("%s: floor beside a front-only quad lit on its front %d, from behind %d\n", renderer_name[k],
                      front_lit, back_lit);
        assert_true(front_lit < back_lit / 2);
        assert_true(back_lit > 200);
    }
}

/* A cube, every face counter-clockwise seen from outside. */
static const float cube_positions[] = {-1, -1, -1, -1, -1, 1, -1, 1, -1, -1, 1, 1, 1, -1, -1, 1, -1, 1, 1, 1, -1, 1, 1, 1};
static const uint32_t cube_indices[] = {0, 3, 2, 0, 1, 3, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                        2, 7, 6, 2, 3, 7, 0, 6, 4, 0, 2, 6, 1, 5, 7, 1, 7, 3};

/* The image of a cube mirrored in x, or not, from a camera on its plane of symmetry. */
static unsigned char *cube_image(bool mirrored, int k)
{
    bg_scene *s = new_scene(bg_vec3_make(0.0, 2.5, 4.0), bg_vec3_make(0.0, 1.0, 0.0), 5.0);
    bg_mesh_desc d = bg_mesh_desc_init(diffuse(s, 0.8, 0.6, 0.2, NULL));
    d.positions = cube_positions;
    d.vertex_count = 8;
    d.indices = cube_indices;
    d.triangle_count = 12;
    d.transform.m[0][0] = mirrored ? -1.0 : 1.0;
    uint32_t id;
    assert_int_equal(bg_scene_add_mesh(s, &d, &id), BG_OK);
    commit(s);
    unsigned char *px = render(s, k);
    bg_scene_destroy(s);
    return px;
}

/* A mirroring transform turns the world winding over but not the mesh's own: a mirrored solid is
 * still entered from outside, and lit as the cube it mirrors is. */
static void mirrored_solid_is_lit_from_outside(void **state)
{
    (void)state;
    for (int k = 0; k < RENDERERS; k++) {
        unsigned char *plain = cube_image(false, k), *mirrored = cube_image(true, k);
        int n = differing(plain, mirrored);
        const unsigned char *top = at(mirrored, W / 2, H / 3);
        print_message("%s: mirrored cube top (%d, %d, %d), %d pixels differ from the plain cube\n", renderer_name[k],
                      top[0], top[1], top[2], n);
        assert_true(top[0] > 150);
        assert_true(n <= W * H / 200); /* the diagonals of the faces may round apart */
        free(plain);
        free(mirrored);
    }
}

static void bad_values_are_refused(void **state)
{
    (void)state;
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    uint32_t id;
    m.coverage_cutoff = 1.5;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "coverage_cutoff"));
    bg_scene_clear_error(s);
    m = bg_material_init();
    m.sides = (bg_mesh_sides)7;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "sides"));
    bg_scene_clear_error(s);
    m = bg_material_init();
    m.coverage.channel = 4;
    assert_int_equal(bg_scene_add_material(s, &m, &id), BG_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bg_scene_error_message(s), "coverage.channel"));
    bg_scene_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bad_values_are_refused),
        cmocka_unit_test(cut_out_nearest),
        cmocka_unit_test(cut_out_linear),
        cmocka_unit_test(front_only_quad_is_seen_from_its_front),
        cmocka_unit_test(open_quad_is_lit_on_its_back),
        cmocka_unit_test(front_only_shadows_by_the_side_the_light_sees),
        cmocka_unit_test(mirrored_solid_is_lit_from_outside),
    };
    return cmocka_run_group_tests_name("bg_mesh_filter", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
