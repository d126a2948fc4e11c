#version 110
// requires: bg_common.glsl
// The plane y = 0 with its front towards +y (docs/shading.md 2.5), ported from thin() in
// intersect.c. Returns 0 (miss) or 1 (t.x = t.y = the parameter, n0 = n1 = (0, 1, 0)).

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1)
{
    t = vec2(0.0);
    n0 = vec3(0.0);
    n1 = vec3(0.0);
    // 2^-20 (float form of 2^-40): a ray this grazing cannot resolve where it meets the plane,
    // and the quotient below stays under 2^20 |o'_y| / |d'|inf.
    if (abs(d.y) <= bg_maxabs3(d) * 9.5367432e-07)
        return 0;
    float h = -o.y / d.y;
    t = vec2(h);
    n0 = vec3(0.0, 1.0, 0.0);
    n1 = n0;
    return 1;
}
