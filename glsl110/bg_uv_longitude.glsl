#version 110
// requires:
// The longitude coordinate shared by the spherical and cylindrical mappings (docs/shading.md 4),
// ported from longitude_u() in src/betelgeuse/uv_map.c. u = 0.5 faces +z and grows towards +x.

float bg_lon_u(float x, float z)
{
    // GLSL leaves atan(0, 0) undefined; every point on the axis gets the middle of the texture.
    if (x == 0.0 && z == 0.0)
        return 0.5;
    return 0.5 + atan(x, z) / 6.28318530717959;
}
