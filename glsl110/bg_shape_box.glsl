#version 110
// requires: bg_common.glsl bg_slab.glsl
// The cube [-1, 1]^3 (docs/shading.md 2.3), ported from box() in intersect.c: three slabs, no
// infinities. Returns 0 (miss) or 2 (interval t.x <= t.y with the outward prototype normals).

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
    if (!bg_slab(o.x, d.x, s, vec3(1.0, 0.0, 0.0), iv, has, n_lo, n_hi))
        return 0;
    if (!bg_slab(o.y, d.y, s, vec3(0.0, 1.0, 0.0), iv, has, n_lo, n_hi))
        return 0;
    if (!bg_slab(o.z, d.z, s, vec3(0.0, 0.0, 1.0), iv, has, n_lo, n_hi))
        return 0;
    // Still unbounded after every axis only happens for d' = 0: no ray at all.
    if (!(has.x && has.y))
        return 0;
    t = iv;
    n0 = n_lo;
    n1 = n_hi;
    return 2;
}
