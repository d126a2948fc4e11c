#version 110
// requires:
// Output encoding (docs/shading.md section 10): clamp, optional sRGB, and the byte value
// floor(y * 255 + 0.5) written as an exact multiple of 1/255 so the RGBA8 target stores it unchanged.

vec3 bg_encode(vec3 linear, bool srgb)
{
    vec3 x = clamp(linear, 0.0, 1.0);
    if (srgb) {
        vec3 lo = 12.92 * x;
        vec3 hi = 1.055 * pow(max(x, vec3(0.0031308)), vec3(1.0 / 2.4)) - 0.055;
        x = vec3(x.r <= 0.0031308 ? lo.r : hi.r, x.g <= 0.0031308 ? lo.g : hi.g, x.b <= 0.0031308 ? lo.b : hi.b);
    }
    return floor(x * 255.0 + 0.5) / 255.0;
}
