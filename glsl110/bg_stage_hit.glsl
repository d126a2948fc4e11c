#version 110
// requires: bg_common.glsl bg_hit_code.glsl
// What every intersection pass shares (docs/shading.md sections 2.7 and 3): the depth of a hit, the
// key the depth test compares, and the normal facing the ray. The roots come from bg_hit_root.glsl,
// once per shape of the pass (gpu_hit_pass.c renames it for each).

// Depth of a hit at distance t > 0: t / (2 dmax) up to dmax, where the scene's bounded objects are
// and depth steps are finest, then 1 - dmax / (2 t) beyond, so that planes reach the horizon. The
// two halves meet at 1/2 and the whole is increasing, so the depth test LESS keeps the nearest hit.
// A distance so large that the depth rounds to 1.0 fails against the cleared 1.0: a miss.
float bg_depth(float t, float dmax)
{
    return t < dmax ? 0.5 * (t / dmax) : 1.0 - 0.5 * (dmax / t);
}

// The value the depth buffer stores for depth z, for choosing among several objects in one pass
// exactly as the depth test LESS between separate passes would: unorm24 buffers round z * (2^24 - 1)
// to the nearest integer (ties to even, as the conversion instructions do), float buffers keep z.
// The steps below are exact in float: x < 2^24, so x - floor(x) and the +1 lose nothing.
float bg_depth_key(float z, bool fixed24)
{
    if (!fixed24)
        return z;
    float x = z * 16777215.0;
    float q = floor(x);
    float f = x - q;
    if (f > 0.5 || (f == 0.5 && mod(q, 2.0) == 1.0))
        q += 1.0;
    return q;
}

// The world normal facing the ray and whether the ray arrives from outside (section 3).
vec3 bg_hit_normal(mat3 normal_to_world, vec3 n_obj, vec3 d, bool thin, bool first_root, out bool entering)
{
    vec3 n = bg_normalize_or(normal_to_world * n_obj, -d);
    entering = thin ? dot(n, d) <= 0.0 : first_root;
    return entering ? n : -n;
}
