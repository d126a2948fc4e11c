#version 110
// requires: bg_common.glsl bg_slab.glsl
// The capped cylinder of radius 1 about the y axis, y in [-1, 1] (docs/shading.md 2.4), ported from
// cylinder() in intersect.c. Returns 0 (miss) or 2 (interval t.x <= t.y with outward normals).

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1)
{
    t = vec2(0.0);
    n0 = vec3(0.0);
    n1 = vec3(0.0);
    vec2 iv = vec2(0.0);
    bvec2 has = bvec2(false);
    vec3 n_lo = vec3(0.0);
    vec3 n_hi = vec3(0.0);
    float s = bg_maxabs3(d);
    float a = d.x * d.x + d.z * d.z;
    float b = o.x * d.x + o.z * d.z;
    float c = o.x * o.x + o.z * o.z - 1.0;
    // 2^-60 (float form of 2^-1000): a ray this close to the axis direction never crosses the side
    // at a representable t, and b / a must not overflow.
    if (a <= s * s * 8.6736174e-19) {
        if (c > 0.0)
            return 0;
    } else {
        // The 2-D form of the sphere's cancellation-free discriminant.
        float k = b / a;
        float gx = o.x - k * d.x;
        float gz = o.z - k * d.z;
        float disc = a * (1.0 - (gx * gx + gz * gz));
        vec2 r;
        if (!bg_stable_roots(a, b, c, disc, r))
            return 0;
        vec3 m0 = vec3(o.x + r.x * d.x, 0.0, o.z + r.x * d.z);
        vec3 m1 = vec3(o.x + r.y * d.x, 0.0, o.z + r.y * d.z);
        // Always non-empty (r.x <= r.y); clipping first makes the side win ties with the caps.
        bg_clip(r.x, m0, r.y, m1, iv, has, n_lo, n_hi);
    }
    if (!bg_slab(o.y, d.y, s, vec3(0.0, 1.0, 0.0), iv, has, n_lo, n_hi))
        return 0;
    // Unbounded on a side: d' has no x, z or y component worth resolving, i.e. no ray.
    if (!(has.x && has.y))
        return 0;
    t = iv;
    n0 = n_lo;
    n1 = n_hi;
    return 2;
}
