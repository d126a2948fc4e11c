#version 110
// requires:
// Exact unpolarised dielectric Fresnel reflectance (docs/shading.md 6.5), ported from
// bgi_cpu_fresnel() in src/betelgeuse/cpu/brdf.c. n1 is the index on the ray's side, n2 > 0 the other.
// cos_t receives the cosine of the refracted ray (0.0 on total internal reflection).

float bg_fresnel(float cos_i, float n1, float n2, out float cos_t)
{
    cos_t = 0.0;
    float ci = clamp(cos_i, 0.0, 1.0);
    float eta = n1 / n2;
    float sin2_t = eta * eta * (1.0 - ci * ci);
    // Total internal reflection is tested first: it is also what keeps the sqrt below defined.
    if (sin2_t >= 1.0)
        return 1.0;
    float ct = sqrt(1.0 - sin2_t);
    cos_t = ct;
    float rs_den = n1 * ci + n2 * ct;
    float rp_den = n2 * ci + n1 * ct;
    // ct > 0 here, so both are positive for valid indices; the test keeps invalid ones from
    // dividing by zero.
    if (!(rs_den > 0.0) || !(rp_den > 0.0))
        return 1.0;
    float rs = (n1 * ci - n2 * ct) / rs_den;
    float rp = (n2 * ci - n1 * ct) / rp_den;
    return 0.5 * (rs * rs + rp * rp);
}
