/* The public vector and matrix helpers. Row-major, column vectors: p' = M p. */
#include "betelgeuse.h"

#include <math.h>

bg_vec3 bg_vec3_make(double x, double y, double z)
{
    bg_vec3 v = {x, y, z};
    return v;
}

bg_mat4 bg_mat4_identity(void)
{
    bg_mat4 r = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    return r;
}

bg_mat4 bg_mat4_translate(double x, double y, double z)
{
    bg_mat4 r = bg_mat4_identity();
    r.m[0][3] = x;
    r.m[1][3] = y;
    r.m[2][3] = z;
    return r;
}

bg_mat4 bg_mat4_scale(double x, double y, double z)
{
    bg_mat4 r = bg_mat4_identity();
    r.m[0][0] = x;
    r.m[1][1] = y;
    r.m[2][2] = z;
    return r;
}

/* sin and cos of an angle in degrees, exact at multiples of 90 so axis-aligned rotations stay
 * exactly axis-aligned (no 6e-17 residue that turns a box's bounds into slivers). */
static void sincos_degrees(double degrees, double *s, double *c)
{
    double a = fmod(degrees, 360.0);
    if (a < 0)
        a += 360.0;
    if (a == 0.0) {
        *s = 0; *c = 1;
    } else if (a == 90.0) {
        *s = 1; *c = 0;
    } else if (a == 180.0) {
        *s = 0; *c = -1;
    } else if (a == 270.0) {
        *s = -1; *c = 0;
    } else {
        double r = a * (3.14159265358979323846 / 180.0);
        *s = sin(r);
        *c = cos(r);
    }
}

bg_mat4 bg_mat4_rotate(bg_vec3 axis, double angle_degrees)
{
    double len = sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    if (len == 0.0)
        return bg_mat4_identity();
    double x = axis.x / len, y = axis.y / len, z = axis.z / len;
    double s, c;
    sincos_degrees(angle_degrees, &s, &c);
    double t = 1.0 - c;
    bg_mat4 r = bg_mat4_identity();
    r.m[0][0] = t * x * x + c;
    r.m[0][1] = t * x * y - s * z;
    r.m[0][2] = t * x * z + s * y;
    r.m[1][0] = t * x * y + s * z;
    r.m[1][1] = t * y * y + c;
    r.m[1][2] = t * y * z - s * x;
    r.m[2][0] = t * x * z - s * y;
    r.m[2][1] = t * y * z + s * x;
    r.m[2][2] = t * z * z + c;
    return r;
}

bg_mat4 bg_mat4_mul(bg_mat4 a, bg_mat4 b)
{
    bg_mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += a.m[i][k] * b.m[k][j];
            r.m[i][j] = sum;
        }
    return r;
}
