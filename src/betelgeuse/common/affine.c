/* Affine inverse in double with a scale-free singularity test (see affine.h). Everything is
 * computed on the linear part divided by its overall scale s, entries of order 1, so that neither
 * the test nor the inverse can overflow or underflow for any s in the accepted range; the inverse
 * is that of the normalised part, divided by s. */
#include "affine.h"

#include <math.h>

bool bgi_vec3_finite(bg_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

double bgi_vec3_length(bg_vec3 v)
{
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (m == 0.0 || !isfinite(m))
        return m;
    double x = v.x / m, y = v.y / m, z = v.z / m;
    return m * sqrt(x * x + y * y + z * z);
}

bg_vec3 bgi_vec3_normalize(bg_vec3 v)
{
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (m == 0.0 || !isfinite(m))
        return v;
    double x = v.x / m, y = v.y / m, z = v.z / m;
    double l = sqrt(x * x + y * y + z * z);
    return bg_vec3_make(x / l, y / l, z / l);
}

const char *bgi_affine_check_string(bg_affine_check check)
{
    switch (check) {
    case BG_AFFINE_OK: return "is fine";
    case BG_AFFINE_NOT_FINITE: return "is not finite (a NaN or infinite element)";
    case BG_AFFINE_NOT_AFFINE: return "is not affine (bottom row must be 0 0 0 1)";
    case BG_AFFINE_SINGULAR: return "is singular";
    case BG_AFFINE_SCALE: return "has an overall scale (|L|_F / sqrt 3) outside " BG_AFFINE_SCALE_RANGE;
    case BG_AFFINE_INVERSE_OVERFLOW:
        return "has an inverse beyond the double range (translation too large for its scale)";
    }
    return "is invalid";
}

bg_affine_check bgi_affine_inverse(const bg_mat4 *transform, double inv[4][4], double *out_scale)
{
    const double (*m)[4] = transform->m;
    if (out_scale)
        *out_scale = 0.0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(m[i][j]))
                return BG_AFFINE_NOT_FINITE;
    if (m[3][0] != 0 || m[3][1] != 0 || m[3][2] != 0 || m[3][3] != 1)
        return BG_AFFINE_NOT_AFFINE;

    /* u = L / s, s the root mean square of L's row norms (||L||_F / sqrt 3), found through L / big
     * (big its largest entry) so that the sum of squares cannot overflow or underflow. det u is
     * scale-free, invariant under rotation (a thin slab is judged the same however it is turned),
     * and at most 1 (Hadamard and AM-GM), reached by scaled rotations. */
    double big = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            big = fmax(big, fabs(m[i][j]));
    if (big == 0.0)
        return BG_AFFINE_SINGULAR;
    double u[3][3], sum = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            u[i][j] = m[i][j] / big;
            sum += u[i][j] * u[i][j];
        }
    double rms = sqrt(sum / 3.0);
    double scale = big * rms; /* may overflow to infinity: then it is out of range below */
    if (out_scale)
        *out_scale = scale;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            u[i][j] /= rms;

    /* The adjugate of u; its first column gives det u by expansion along the first row. */
    double c[3][3];
    c[0][0] = u[1][1] * u[2][2] - u[1][2] * u[2][1];
    c[0][1] = u[0][2] * u[2][1] - u[0][1] * u[2][2];
    c[0][2] = u[0][1] * u[1][2] - u[0][2] * u[1][1];
    c[1][0] = u[1][2] * u[2][0] - u[1][0] * u[2][2];
    c[1][1] = u[0][0] * u[2][2] - u[0][2] * u[2][0];
    c[1][2] = u[0][2] * u[1][0] - u[0][0] * u[1][2];
    c[2][0] = u[1][0] * u[2][1] - u[1][1] * u[2][0];
    c[2][1] = u[0][1] * u[2][0] - u[0][0] * u[2][1];
    c[2][2] = u[0][0] * u[1][1] - u[0][1] * u[1][0];
    double ratio = u[0][0] * c[0][0] + u[0][1] * c[1][0] + u[0][2] * c[2][0];
    if (!(fabs(ratio) >= BG_AFFINE_SINGULAR_RATIO))
        return BG_AFFINE_SINGULAR;
    if (!(scale >= BG_AFFINE_MIN_SCALE && scale <= BG_AFFINE_MAX_SCALE))
        return BG_AFFINE_SCALE;

    /* L^-1 = u^-1 / s = adj(u) / (det u * s); with s in range its entries are at most about
     * 6e12 / 1e-100, so only the translation -L^-1 t can leave the double range. */
    double k = ratio * scale;
    double r[4][4];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            r[i][j] = c[i][j] / k;
        r[i][3] = -(r[i][0] * m[0][3] + r[i][1] * m[1][3] + r[i][2] * m[2][3]);
    }
    r[3][0] = r[3][1] = r[3][2] = 0;
    r[3][3] = 1;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(r[i][j]))
                return BG_AFFINE_INVERSE_OVERFLOW;
    if (inv)
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                inv[i][j] = r[i][j];
    return BG_AFFINE_OK;
}
