/* Geometry passes (macs_geometry, macs_pass_draw): triangles drawn from a vertex buffer with the
 * caller's vertex code. Two triangles sharing an edge cover each pixel of their square exactly once
 * (GL's fill rule); the depth test keeps the nearest of overlapping draws; solid + edges + corners
 * cover every pixel whose centre lies within half their size of a triangle, even a sliver the fill
 * rule gives no pixel; macs_uv is the texel centre as in a full-screen pass; the work is counted;
 * every misuse is refused naming the argument. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

enum { W = 32, H = 24 };

static void expect_error(macs_context *ctx, macs_status got, macs_status want, const char *needle)
{
    assert_int_equal(got, want);
    assert_int_equal(macs_context_error(ctx), want);
    if (!strstr(macs_context_error_message(ctx), needle))
        fail_msg("message \"%s\" does not name \"%s\"", macs_context_error_message(ctx), needle);
    macs_context_clear_error(ctx);
}

/* Vertices are (x, y) in pixels of the W x H output, a depth in 0..1 and a value written out. */
static const macs_attribute_desc attributes[] = {{"corner", 2}, {"depth", 1}, {"value", 1}};
static const char *const vertex_main =
    "gl_Position = vec4(corner * (2.0 / size) - 1.0, depth * 2.0 - 1.0, 1.0);\n"
    "v_value = value;\n";

/* A geometry pass writing (value, 1, macs_uv) with the given blend and depth state. */
static macs_pass *geometry_pass(macs_context *ctx, macs_texture *out, macs_depth_stencil *ds, macs_blend blend,
                                bool depth)
{
    static const macs_uniform_desc uniforms[] = {{"size", MACS_UNIFORM_VEC2, 0}};
    static const macs_output_desc outputs[] = {{"o", "vec4(v_value, 1.0, macs_uv)"}};
    macs_pass_desc d = {0};
    d.uniforms = uniforms;
    d.uniform_count = 1;
    d.outputs = outputs;
    d.output_count = 1;
    d.output_textures = &out;
    d.vertex_main = vertex_main;
    d.varyings = "varying float v_value;\n";
    d.attributes = attributes;
    d.attribute_count = 3;
    d.blend = blend;
    d.depth_stencil = ds;
    d.depth.test = depth;
    d.depth.write = depth;
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &p), MACS_OK);
    const float size[2] = {W, H};
    assert_int_equal(macs_pass_set_uniform(p, "size", size), MACS_OK);
    return p;
}

static macs_geometry *geometry_of(macs_context *ctx, const float *v, int vertices)
{
    macs_geometry *g = NULL;
    macs_geometry_desc d = {vertices, 4, v};
    assert_int_equal(macs_geometry_create(ctx, &d, &g), MACS_OK);
    return g;
}

static void read_floats(macs_texture *t, float *px)
{
    assert_int_equal(macs_texture_read(t, px, 0), MACS_OK);
}

/* A square of two triangles sharing a diagonal, drawn with additive blending: every pixel of the
 * square gets 1 exactly (the shared edge's pixels go to one triangle only), every other 0; and
 * macs_uv is each pixel's texel centre. */
static void shared_edge_covers_once(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *out = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    macs_pass *p = geometry_pass(ctx, out, NULL, MACS_BLEND_ADD, false);
    /* The square [4, 20] x [3, 19], split along a diagonal that passes through pixel centres. */
    const float v[] = {4, 3, 0.5f, 1, 20, 3, 0.5f, 1, 20, 19, 0.5f, 1, 4, 3, 0.5f, 1, 20, 19, 0.5f, 1, 4, 19, 0.5f, 1};
    macs_geometry *g = geometry_of(ctx, v, 6);
    const float zero[4] = {0, 0, 0, 0};
    assert_int_equal(macs_texture_clear(out, zero), MACS_OK);
    macs_draw_desc draw = {0};
    draw.geometry = g;
    assert_int_equal(macs_pass_draw(p, &draw), MACS_OK);
    static float px[W * H * 4];
    read_floats(out, px);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *o = &px[4 * (y * W + x)];
            bool inside = x >= 4 && x < 20 && y >= 3 && y < 19;
            if (o[0] != (inside ? 1.0f : 0.0f))
                fail_msg("pixel (%d, %d) was covered %g times, expected %d", x, y, (double)o[0], inside ? 1 : 0);
            if (inside) {
                /* gl_FragCoord times the inverse size: within a float rounding of the quotient. */
                assert_true(fabs(o[2] - (x + 0.5) / W) < 1e-6);
                assert_true(fabs(o[3] - (y + 0.5) / H) < 1e-6);
            }
        }
    macs_geometry_destroy(g);
    macs_pass_destroy(p);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

/* Two overlapping quads in two draws, the far one drawn second: the depth test keeps the near one
 * where they overlap, in either order. */
static void depth_keeps_the_nearest(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *out = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    macs_depth_stencil *ds = NULL;
    macs_depth_stencil_desc dd = {W, H, MACS_DEPTH24_STENCIL8};
    assert_int_equal(macs_depth_stencil_create(ctx, &dd, &ds), MACS_OK);
    macs_pass *p = geometry_pass(ctx, out, ds, MACS_BLEND_NONE, true);
    const float v[] = {
        /* near (depth 0.25, value 7): [0, 16] x [0, 24] */
        0, 0, 0.25f, 7, 16, 0, 0.25f, 7, 16, 24, 0.25f, 7, 0, 0, 0.25f, 7, 16, 24, 0.25f, 7, 0, 24, 0.25f, 7,
        /* far (depth 0.75, value 3): [8, 32] x [0, 24] */
        8, 0, 0.75f, 3, 32, 0, 0.75f, 3, 32, 24, 0.75f, 3, 8, 0, 0.75f, 3, 32, 24, 0.75f, 3, 8, 24, 0.75f, 3};
    macs_geometry *g = geometry_of(ctx, v, 12);
    static float px[W * H * 4];
    for (int order = 0; order < 2; order++) {
        const float zero[4] = {0, 0, 0, 0};
        assert_int_equal(macs_texture_clear(out, zero), MACS_OK);
        assert_int_equal(macs_depth_stencil_clear(ds, 1.0f, 0, 0), MACS_OK);
        for (int k = 0; k < 2; k++) {
            macs_draw_desc draw = {0};
            draw.geometry = g;
            draw.first = ((k + order) % 2) * 6;
            draw.vertex_count = 6;
            assert_int_equal(macs_pass_draw(p, &draw), MACS_OK);
        }
        read_floats(out, px);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                float want = x < 16 ? 7.0f : 3.0f;
                if (px[4 * (y * W + x)] != want)
                    fail_msg("order %d: pixel (%d, %d) holds %g, expected %g", order, x, y,
                             (double)px[4 * (y * W + x)], (double)want);
            }
    }
    macs_geometry_destroy(g);
    macs_pass_destroy(p);
    macs_depth_stencil_destroy(ds);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

/* Distance from (px, py) to the segment a-b. */
static double segment_distance(double px, double py, const float *a, const float *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double len2 = dx * dx + dy * dy;
    double s = len2 > 0 ? ((px - a[0]) * dx + (py - a[1]) * dy) / len2 : 0.0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double ex = a[0] + s * dx - px, ey = a[1] + s * dy - py;
    return sqrt(ex * ex + ey * ey);
}

/* Whether (px, py) lies inside the triangle (either winding), edges included. */
static bool inside_triangle(double px, double py, const float *v0, const float *v1, const float *v2)
{
    const float *v[3] = {v0, v1, v2};
    int pos = 0, neg = 0;
    for (int i = 0; i < 3; i++) {
        const float *a = v[i], *b = v[(i + 1) % 3];
        double c = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
        pos += c > 0;
        neg += c < 0;
    }
    return pos == 0 || neg == 0;
}

/* Slivers and small triangles: a pixel whose centre lies within 0.5 pixel of a triangle is covered
 * by its solid, edge or corner draw of size 2, every one, though the fill rule alone gives a
 * sliver no pixel at all; and no pixel farther than 1.5 from every triangle is touched. */
static void edges_and_corners_cover_what_is_near(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_features f;
    macs_context_get_features(ctx, &f);
    if (f.max_line_width < 2.0f || f.max_point_size < 2.0f) {
        print_message("SKIP: the GL draws lines up to %g and points up to %g pixels wide, under 2\n",
                      (double)f.max_line_width, (double)f.max_point_size);
        macs_context_destroy(ctx);
        skip();
    }
    macs_texture *out = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    macs_pass *p = geometry_pass(ctx, out, NULL, MACS_BLEND_NONE, false);
    const float v[] = {/* a sliver along a pixel row's centres and a slanted one */
                       2.5f, 4.5f, 0.5f, 1, 28.5f, 4.5f, 0.5f, 1, 15.0f, 4.52f, 0.5f, 1,
                       3.1f, 8.2f, 0.5f, 2, 29.7f, 20.9f, 0.5f, 2, 29.71f, 20.93f, 0.5f, 2,
                       /* a triangle smaller than a pixel, between centres */
                       10.6f, 14.6f, 0.5f, 3, 10.9f, 14.6f, 0.5f, 3, 10.7f, 14.9f, 0.5f, 3};
    macs_geometry *g = geometry_of(ctx, v, 9);
    const float zero[4] = {0, 0, 0, 0};
    assert_int_equal(macs_texture_clear(out, zero), MACS_OK);
    macs_work before, after;
    macs_context_get_work(ctx, &before);
    for (int fill = MACS_FILL_SOLID; fill <= MACS_FILL_CORNERS; fill++) {
        macs_draw_desc draw = {0};
        draw.geometry = g;
        draw.fill = (macs_fill)fill;
        draw.size = 2.0f;
        assert_int_equal(macs_pass_draw(p, &draw), MACS_OK);
    }
    macs_context_get_work(ctx, &after);
    macs_work w = macs_work_since(&after, &before);
    assert_int_equal(w.draws, 3);
    assert_int_equal(w.vertex_bytes, 0);
    static float px[W * H * 4];
    read_floats(out, px);
    int near_count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double cx = x + 0.5, cy = y + 0.5, d = 1e9;
            for (int t = 0; t < 3; t++) {
                const float *a = &v[12 * t], *b = &v[12 * t + 4], *c = &v[12 * t + 8];
                double dt = inside_triangle(cx, cy, a, b, c) ? 0.0 : segment_distance(cx, cy, a, b);
                dt = fmin(dt, segment_distance(cx, cy, b, c));
                dt = fmin(dt, segment_distance(cx, cy, c, a));
                d = fmin(d, dt);
            }
            bool covered = px[4 * (y * W + x) + 1] == 1.0f;
            if (d <= 0.5) {
                near_count++;
                if (!covered)
                    fail_msg("pixel (%d, %d), %.3f from a triangle, was not covered", x, y, d);
            }
            if (d > 1.5 && covered)
                fail_msg("pixel (%d, %d), %.3f from every triangle, was covered", x, y, d);
        }
    assert_true(near_count > 40);
    macs_geometry_destroy(g);
    macs_pass_destroy(p);
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

/* The bytes a geometry takes are counted; misuse is refused naming the argument. */
static void work_and_misuse(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *out = util_texture(ctx, W, H, MACS_FORMAT_RGBA32F);
    macs_work before, after;
    macs_context_get_work(ctx, &before);
    const float v[12] = {0, 0, 0.5f, 1, 8, 0, 0.5f, 1, 0, 8, 0.5f, 1};
    macs_geometry *g = geometry_of(ctx, v, 3);
    assert_int_equal(macs_geometry_upload(g, 1, 2, v), MACS_OK);
    macs_context_get_work(ctx, &after);
    assert_int_equal(macs_work_since(&after, &before).vertex_bytes, 12 * 4 + 8 * 4);

    macs_geometry *none = NULL;
    macs_geometry_desc gd = {0, 4, NULL};
    expect_error(ctx, macs_geometry_create(ctx, &gd, &none), MACS_ERR_INVALID_ARGUMENT, "desc.vertex_count 0");
    gd = (macs_geometry_desc){3, 65, NULL};
    expect_error(ctx, macs_geometry_create(ctx, &gd, &none), MACS_ERR_INVALID_ARGUMENT, "desc.floats_per_vertex 65");
    assert_null(none);
    expect_error(ctx, macs_geometry_upload(g, 2, 2, v), MACS_ERR_INVALID_ARGUMENT, "outside");
    expect_error(ctx, macs_geometry_upload(g, 0, 1, NULL), MACS_ERR_INVALID_ARGUMENT, "vertices is NULL");

    macs_pass *p = geometry_pass(ctx, out, NULL, MACS_BLEND_NONE, false);
    expect_error(ctx, macs_pass_run(p, NULL), MACS_ERR_INVALID_ARGUMENT, "macs_pass_draw");
    expect_error(ctx, macs_pass_draw(p, NULL), MACS_ERR_INVALID_ARGUMENT, "draw is NULL");
    macs_draw_desc draw = {0};
    expect_error(ctx, macs_pass_draw(p, &draw), MACS_ERR_INVALID_ARGUMENT, "draw.geometry is NULL");
    draw.geometry = g;
    draw.vertex_count = 2;
    expect_error(ctx, macs_pass_draw(p, &draw), MACS_ERR_INVALID_ARGUMENT, "multiple of 3");
    draw.vertex_count = 6;
    expect_error(ctx, macs_pass_draw(p, &draw), MACS_ERR_INVALID_ARGUMENT, "exceeds");
    draw.vertex_count = 0;
    draw.fill = MACS_FILL_EDGES;
    draw.size = 1e9f;
    expect_error(ctx, macs_pass_draw(p, &draw), MACS_ERR_LIMIT, "max_line_width");
    draw.fill = MACS_FILL_CORNERS;
    expect_error(ctx, macs_pass_draw(p, &draw), MACS_ERR_LIMIT, "max_point_size");
    macs_geometry *narrow = NULL;
    gd = (macs_geometry_desc){3, 3, NULL};
    assert_int_equal(macs_geometry_create(ctx, &gd, &narrow), MACS_OK);
    draw = (macs_draw_desc){0};
    draw.geometry = narrow;
    expect_error(ctx, macs_pass_draw(p, &draw), MACS_ERR_INVALID_ARGUMENT, "3 floats per vertex but the pass's attributes take 4");

    /* A full-screen pass cannot draw; attributes need a vertex_main and valid sizes and names. */
    static const macs_output_desc outputs[] = {{"o", "vec4(1.0)"}};
    macs_pass_desc d = {0};
    d.outputs = outputs;
    d.output_count = 1;
    d.output_textures = &out;
    macs_pass *fullscreen = NULL;
    assert_int_equal(macs_pass_create(ctx, &d, &fullscreen), MACS_OK);
    draw.geometry = g;
    expect_error(ctx, macs_pass_draw(fullscreen, &draw), MACS_ERR_INVALID_ARGUMENT, "macs_pass_run");
    macs_pass *bad = NULL;
    d.attributes = attributes;
    d.attribute_count = 3;
    expect_error(ctx, macs_pass_create(ctx, &d, &bad), MACS_ERR_INVALID_ARGUMENT, "desc.vertex_main is NULL");
    d.vertex_main = "gl_Position = vec4(0.0);";
    static const macs_attribute_desc wide[] = {{"a", 5}};
    d.attributes = wide;
    d.attribute_count = 1;
    expect_error(ctx, macs_pass_create(ctx, &d, &bad), MACS_ERR_INVALID_ARGUMENT, "size 5");
    static const macs_attribute_desc twice[] = {{"a", 1}, {"a", 2}};
    d.attributes = twice;
    d.attribute_count = 2;
    expect_error(ctx, macs_pass_create(ctx, &d, &bad), MACS_ERR_INVALID_ARGUMENT, "already used by attribute 0");
    d.attribute_count = 0;
    expect_error(ctx, macs_pass_create(ctx, &d, &bad), MACS_ERR_INVALID_ARGUMENT, "desc.attribute_count 0");
    d.attributes = attributes;
    d.attribute_count = 3;
    d.vertex_main = "gl_Position = vec4(corner, undeclared, 1.0);";
    assert_int_equal(macs_pass_create(ctx, &d, &bad), MACS_ERR_SHADER_COMPILE);
    assert_non_null(strstr(macs_context_error_message(ctx), "vertex shader"));
    macs_context_clear_error(ctx);
    assert_null(bad);

    macs_pass_destroy(fullscreen);
    macs_pass_destroy(p);
    macs_geometry_destroy(narrow);
    /* g is left for the context to destroy. */
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shared_edge_covers_once),
        cmocka_unit_test(depth_keeps_the_nearest),
        cmocka_unit_test(edges_and_corners_cover_what_is_near),
        cmocka_unit_test(work_and_misuse),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
