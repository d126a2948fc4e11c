/* The edge scene of util_coverage.h and its exact pixel coverage: the camera ray through frame point
 * (fx, fy) meets the plane z = 0 at 5 (sx, sy) (docs/shading.md 1), linear in (fx, fy), so the bright
 * side is a half-plane of the frame too and a pixel's share is the area of the unit square clipped
 * by one line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>

#include <cmocka.h>

#include "util_coverage.h"

static const double pi = 3.14159265358979323846;

bg_scene *util_edge_scene(void)
{
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_material m = bg_material_init();
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 0.0;
    m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    m.emission.r = m.emission.g = m.emission.b = 1.0;
    uint32_t mat = 0;
    assert_int_equal(bg_scene_add_material(s, &m, &mat), BG_OK);
    /* The prototype square (y = 0, front +y) turned to face the camera (+z), 20 wide, moved so its
     * left edge runs through the origin, then slanted about the view axis. */
    bg_mat4 t = bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 0, 1), UTIL_EDGE_DEGREES),
                            bg_mat4_mul(bg_mat4_translate(10, 0, 0),
                                        bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 0, 0), 90.0),
                                                    bg_mat4_scale(10, 1, 10))));
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_RECTANGLE, mat);
    d.transform = t;
    uint32_t obj = 0;
    assert_int_equal(bg_scene_add_object(s, &d, &obj), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

bg_render_settings util_edge_settings(int samples)
{
    bg_render_settings set = bg_render_settings_init();
    set.max_depth = 0;
    set.encoding = BG_ENCODING_LINEAR;
    set.samples = samples;
    return set;
}

/* The area of the unit square [x, x+1] x [y, y+1] where a fx + b fy + c >= 0 (Sutherland-Hodgman
 * against one line, then the shoelace formula). */
static double clipped_area(double a, double b, double c, double x, double y)
{
    double in[4][2] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
    double out[8][2];
    int n = 0;
    for (int i = 0; i < 4; i++) {
        const double *p = in[i], *q = in[(i + 1) % 4];
        double fp = a * p[0] + b * p[1] + c, fq = a * q[0] + b * q[1] + c;
        if (fp >= 0) {
            out[n][0] = p[0];
            out[n][1] = p[1];
            n++;
        }
        if ((fp >= 0) != (fq >= 0)) {
            double t = fp / (fp - fq);
            out[n][0] = p[0] + t * (q[0] - p[0]);
            out[n][1] = p[1] + t * (q[1] - p[1]);
            n++;
        }
    }
    double area = 0;
    for (int i = 0; i < n; i++)
        area += out[i][0] * out[(i + 1) % n][1] - out[(i + 1) % n][0] * out[i][1];
    return fabs(area) / 2;
}

double util_edge_coverage(int width, int height, int x, int y)
{
    double tan_half = tan(22.5 * pi / 180), aspect = (double)width / height;
    double ca = cos(UTIL_EDGE_DEGREES * pi / 180), sa = sin(UTIL_EDGE_DEGREES * pi / 180);
    /* ca sx + sa sy >= 0 with sx = (2 fx / W - 1) aspect tan, sy = (1 - 2 fy / H) tan. */
    double a = ca * 2 * aspect * tan_half / width, b = -sa * 2 * tan_half / height;
    double c = -ca * aspect * tan_half + sa * tan_half;
    return clipped_area(a, b, c, x, y);
}

void util_edge_error(const float *rgba, int width, int height, double *max_error, double *mean_error)
{
    double max = 0, sum = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            double e = fabs(rgba[((size_t)y * width + x) * 4] - util_edge_coverage(width, height, x, y));
            max = e > max ? e : max;
            sum += e;
        }
    *max_error = max;
    *mean_error = sum / ((double)width * height);
}
