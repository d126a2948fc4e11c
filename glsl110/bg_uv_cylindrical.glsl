#version 110
// requires: bg_uv_longitude.glsl
// Cylindrical UV mapping (docs/shading.md 4), ported from cylindrical() in uv_map.c: longitude
// around the side, the box's +y / -y face layout on the caps.

vec2 bg_uv_map(vec3 p, out vec3 dpdu)
{
    float radial = sqrt(p.x * p.x + p.z * p.z);
    // The hit face is not passed in: |y| > radial tells a cap (|y| = 1, radial < 1) from the side
    // (radial = 1), and the rim itself goes to the side, as in the reference.
    if (abs(p.y) > radial) {
        dpdu = vec3(1.0, 0.0, 0.0);
        return vec2(0.5 * (1.0 + p.x), p.y >= 0.0 ? 0.5 * (1.0 - p.z) : 0.5 * (1.0 + p.z));
    }
    dpdu = vec3(p.z, 0.0, -p.x);
    return vec2(bg_lon_u(p.x, p.z), 0.5 * (1.0 + p.y));
}
