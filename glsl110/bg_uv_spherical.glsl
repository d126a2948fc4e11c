#version 110
// requires: bg_uv_longitude.glsl
// Spherical UV mapping of an object-space point (docs/shading.md 4), ported from spherical() in
// uv_map.c; returns (u, v) before uv_scale and dP/du (zero at the poles: the tangent falls back).

vec2 bg_uv_map(vec3 p, out vec3 dpdu)
{
    float len = sqrt(dot(p, p));
    float u = bg_lon_u(p.x, p.z);
    float v = 0.5;
    if (len > 0.0) {
        // Rounding can push y / |p| a hair outside [-1, 1], where asin is undefined.
        float s = clamp(p.y / len, -1.0, 1.0);
        v = 0.5 + asin(s) / 3.14159265358979;
    }
    dpdu = vec3(p.z, 0.0, -p.x);
    return vec2(u, v);
}
