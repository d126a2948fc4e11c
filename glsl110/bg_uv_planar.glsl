#version 110
// requires:
// Planar UV mapping (docs/shading.md 4), ported from planar() in uv_map.c: one texture repeat
// across the prototype square, upright seen from +y with -z up the screen.

vec2 bg_uv_map(vec3 p, out vec3 dpdu)
{
    dpdu = vec3(1.0, 0.0, 0.0);
    return vec2(0.5 * (p.x + 1.0), 0.5 * (1.0 - p.z));
}
