/* Glossy reflection (docs/shading.md 9.1): the mirror's normal drawn from Schlick's zenith factor. */
#include "cpu_internal.h"

#define TWO_PI 6.28318530717958647692

bool bgi_cpu_glossy_reflect(const double d[3], const double n[3], double r, const double uv[2], double out[3])
{
    /* Z(t) t / pi is a density of normals over the hemisphere (it is GGX's with alpha^2 = r): its
     * inverse gives t^2 = (1 - u) / (1 + (r - 1) u), and 1 - t^2 without cancellation. */
    double q = 1.0 + (r - 1.0) * uv[0];
    double cos2 = (1.0 - uv[0]) / q, sin2 = r * uv[0] / q;
    double cos_h = sqrt(cos2), sin_h = sqrt(sin2), phi = TWO_PI * uv[1];
    double a[3], b[3], h[3];
    bgi_cpu_basis_across(n, a, b);
    for (int i = 0; i < 3; i++)
        h[i] = cos_h * n[i] + sin_h * (cos(phi) * a[i] + sin(phi) * b[i]);
    double dh = bg_v3_dot(d, h);
    for (int i = 0; i < 3; i++)
        out[i] = d[i] - 2.0 * dh * h[i];
    return bg_v3_dot(out, n) > 0.0 && bg_v3_normalize(out);
}
