#version 110
// requires: bg_common.glsl
// The square [-1, 1] x [-1, 1] in y = 0 with its front towards +y (docs/shading.md 2.6), ported
// from thin() in intersect.c. Returns 0 (miss) or 1 (t.x = t.y = the parameter, n0 = n1 = (0, 1, 0)).

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1)
{
    t = vec2(0.0);
    n0 = vec3(0.0);
    n1 = vec3(0.0);
    // 2^-20 (float form of 2^-40), as for the unbounded plane.
    if (abs(d.y) <= bg_maxabs3(d) * 9.5367432e-07)
        return 0;
    float h = -o.y / d.y;
    float x = o.x + h * d.x;
    float z = o.z + h * d.z;
    // Inclusive bounds (2.6): a ray exactly through an edge or corner hits in both renderers.
    if (!(x >= -1.0 && x <= 1.0 && z >= -1.0 && z <= 1.0))
        return 0;
    t = vec2(h);
    n0 = vec3(0.0, 1.0, 0.0);
    n1 = n0;
    return 1;
}
