#version 110
// requires: bg_common.glsl
// The shading tangent of docs/shading.md 3, ported from bgi_cpu_hit_attributes() and
// fallback_tangent() in src/betelgeuse/intersect.c. t0 = to_world_linear * dP/du, n = the unit
// world normal; the result is unit and perpendicular to n. It only orients the anisotropic azimuth.

vec3 bg_tangent(vec3 t0, vec3 n)
{
    // The test |T| > 1e-9 |t0| does not depend on the length of t0, so t0 is first scaled to a
    // largest component of 1: its squared length can then neither overflow nor underflow.
    float m0 = bg_maxabs3(t0);
    if (m0 > 0.0) {
        vec3 ts = t0 / m0;
        float len0 = sqrt(dot(ts, ts));
        vec3 tp = ts - dot(ts, n) * n;
        float len = sqrt(dot(tp, tp));
        if (len > len0 * 1.0e-9)
            return tp / len;
    }
    // dP/du vanishes (a pole) or lies along n: the coordinate axis least aligned with n, ties to
    // x then y, is never closer than 55 degrees to n, so its projection cannot vanish.
    vec3 a = abs(n);
    vec3 e = vec3(0.0, 0.0, 1.0);
    if (a.x <= a.y && a.x <= a.z)
        e = vec3(1.0, 0.0, 0.0);
    else if (a.y <= a.z)
        e = vec3(0.0, 1.0, 0.0);
    return bg_normalize_or(e - dot(e, n) * n, e);
}
