/* Affine inverse in double with a scale-aware singularity test (see affine.h). */
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

const char *bgi_affine_check_string(bg_affine_check check)
{
    switch (check) {
    case BG_AFFINE_OK: return "is fine";
    case BG_AFFINE_NOT_FINITE: return "is not finite (a NaN or infinite element, or an inverse that overflows)";
    case BG_AFFINE_NOT_AFFINE: return "is not affine (bottom row must be 0 0 0 1)";
    case BG_AFFINE_SINGULAR: return "is singular";
    }
    return "is invalid";
}

bg_affine_check bgi_affine_inverse(const bg_mat4 *transform, double inv[4][4])
{
    const double (*m)[4] = transform->m;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(m[i][j]))
                return BG_AFFINE_NOT_FINITE;
    if (m[3][0] != 0 || m[3][1] != 0 || m[3][2] != 0 || m[3][3] != 1)
        return BG_AFFINE_NOT_AFFINE;

    /* The determinant of L / s, where s is the root mean square of L's row norms (||L||_F / sqrt 3):
     * scale-free, invariant under rotation (so a thin slab is judged the same however it is turned),
     * and at most 1 (Hadamard and AM-GM), reached by scaled rotations. Computing it on the scaled
     * matrix keeps it clear of overflow and underflow for very large or small scales. */
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
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            u[i][j] /= rms;
    double ratio = u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) -
                   u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
                   u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0]);
    if (!(fabs(ratio) >= BG_AFFINE_SINGULAR_RATIO))
        return BG_AFFINE_SINGULAR;
    if (!inv)
        return BG_AFFINE_OK;

    /* Cofactors of the original matrix over its determinant. */
    double c[3][3];
    c[0][0] = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    c[0][1] = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    c[0][2] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    c[1][0] = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    c[1][1] = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    c[1][2] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    c[2][0] = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    c[2][1] = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    c[2][2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    double det = m[0][0] * c[0][0] + m[0][1] * c[1][0] + m[0][2] * c[2][0];
    if (det == 0.0 || !isfinite(det))
        return isfinite(det) ? BG_AFFINE_SINGULAR : BG_AFFINE_NOT_FINITE;
    double r[4][4];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            r[i][j] = c[i][j] / det;
        r[i][3] = -(r[i][0] * m[0][3] + r[i][1] * m[1][3] + r[i][2] * m[2][3]);
    }
    r[3][0] = r[3][1] = r[3][2] = 0;
    r[3][3] = 1;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            if (!isfinite(r[i][j]))
                return BG_AFFINE_NOT_FINITE;
        }
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            inv[i][j] = r[i][j];
    return BG_AFFINE_OK;
}
