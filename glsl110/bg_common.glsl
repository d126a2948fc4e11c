#version 110
// requires:
// Small helpers shared by the Betelgeuse GLSL library (docs/shading.md). Everything that could
// divide by zero or take the root of a negative number is guarded here once, so the callers stay
// free of NaN and Inf for any finite input (section 11).

float bg_max3(vec3 v)
{
    return max(max(v.x, v.y), v.z);
}

float bg_maxabs3(vec3 v)
{
    vec3 a = abs(v);
    return max(max(a.x, a.y), a.z);
}

vec3 bg_normalize_or(vec3 v, vec3 fallback)
{
    // Dividing by the largest component first keeps v.v in [1, 3]: no overflow for huge vectors and
    // no underflow to a false zero for tiny ones, which a plain v / sqrt(v.v) cannot promise in float.
    float m = bg_maxabs3(v);
    if (!(m > 0.0))
        return fallback;
    vec3 w = v / m;
    return w / sqrt(dot(w, w));
}

float bg_sgn(float x)
{
    return x >= 0.0 ? 1.0 : -1.0;
}

// a t^2 + 2 b t + c = 0 with the discriminant disc = b^2 - a c supplied in a cancellation-free form
// by the caller (sections 2.2, 2.4). q carries the sign of b so that neither root is a difference of
// nearly equal numbers; q == 0 only for a tangent ray starting on the surface.
bool bg_stable_roots(float a, float b, float c, float disc, out vec2 t)
{
    t = vec2(0.0);
    if (!(a > 0.0) || disc < 0.0)
        return false;
    float q = -(b + bg_sgn(b) * sqrt(disc));
    if (q == 0.0)
        return false;
    float r0 = c / q;
    float r1 = q / a;
    t = r0 < r1 ? vec2(r0, r1) : vec2(r1, r0);
    return true;
}
