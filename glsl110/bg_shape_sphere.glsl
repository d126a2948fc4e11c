#version 110
// requires: bg_common.glsl
// The unit sphere at the origin (docs/shading.md 2.2), ported from sphere() in intersect.c.
// Returns 0 (miss) or 2 (interval t.x <= t.y with the outward prototype normals n0, n1).

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1)
{
    t = vec2(0.0);
    n0 = vec3(0.0);
    n1 = vec3(0.0);
    float a = dot(d, d);
    float b = dot(o, d);
    float c = dot(o, o) - 1.0;
    if (!(a > 0.0))
        return 0;
    // b^2 - a c as a (1 - g.g): the distance of the line from the centre is computed directly,
    // so a far-away ray does not lose the discriminant to cancellation of two large squares.
    float k = b / a;
    vec3 g = o - k * d;
    float disc = a * (1.0 - dot(g, g));
    vec2 r;
    if (!bg_stable_roots(a, b, c, disc, r))
        return 0;
    t = r;
    // On the unit sphere the point is its own outward normal.
    n0 = o + r.x * d;
    n1 = o + r.y * d;
    return 2;
}
