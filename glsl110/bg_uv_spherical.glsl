#version 110
// requires: bg_uv_longitude.glsl
// Spherical UV mapping of an object-space point (docs/shading.md 4), ported from spherical() in
// uv_map.c; returns (u, v) before uv_scale and dP/du (zero at the poles: the tangent falls back).

vec2 bg_uv_map(vec3 p, out vec3 dpdu)
{
    float u = bg_lon_u(p.x, p.z);
    float v = 0.5;
    // The latitude as atan(y, distance from the axis), not asin(y / |p|) as the CPU computes it in
    // double: asin's slope is unbounded near the poles, so the float rounding of y / |p| became a
    // visible error in v there (the stress case "pole of spherical UV": 55.6 dB; with atan, 86.2 dB).
    float axis = sqrt(p.x * p.x + p.z * p.z);
    if (axis > 0.0 || p.y != 0.0)
        v = 0.5 + atan(p.y, axis) / 3.14159265358979;
    dpdu = vec3(p.z, 0.0, -p.x);
    return vec2(u, v);
}
