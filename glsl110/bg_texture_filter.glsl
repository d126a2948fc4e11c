#version 110
// requires:
// GL_LINEAR done in the shader (docs/shading.md 5.1), the twin of bgi_cpu_texture_sample in
// src/betelgeuse/cpu/texture_sample.c: the same wrap, the same half-texel shift, the same floor and
// the same four weights, from four GL_NEAREST fetches at texel centres. The texture unit's own
// filter keeps its weights in fixed point on most GPUs (8 fractional bits on NVIDIA's), cannot
// filter 32-bit floats on GeForce 6/7 or any float on Radeon X1000; here the weights are float on
// every driver, so the GPU differs from the CPU only by float against double.
//
// size is the texture's width and height in texels (whole numbers), repeat its wrap (true: REPEAT,
// false: CLAMP_TO_EDGE); the caller passes both as constants.

// Texel ij (whole numbers in [0, size)) of a NEAREST texture: a fetch at its centre, half a texel
// from either edge, so no driver's coordinate rounding can reach a neighbour.
vec4 bg_texel(sampler2D s, vec2 ij, vec2 size)
{
    return texture2D(s, (ij + 0.5) / size);
}

// The texels of uv's bilinear footprint, i0 and i1 per axis (whole numbers in [0, size)), and the
// weights' fractions a: bg_texture_linear's arithmetic, which the sRGB variant
// (bg_texture_srgb.glsl) shares so that both filter alike.
void bg_texture_taps(vec2 uv, vec2 size, bool repeat, out vec2 i0, out vec2 i1, out vec2 a)
{
    // The coordinate in [0, 1] as GL reduces it before filtering: fract for REPEAT (exact for
    // uv >= 0, one rounding of uv + 1 for uv < 0), clamp for CLAMP_TO_EDGE (exact).
    vec2 c = repeat ? fract(uv) : clamp(uv, 0.0, 1.0);
    // x in [-0.5, size - 0.5]: one rounding of the product (exact for a power-of-two size); the
    // subtraction, floor and x - f are exact in float for sizes up to 2^22.
    vec2 x = c * size - 0.5;
    vec2 f = floor(x);
    a = x - f;
    // The two texels per axis, f and f + 1 in [-1, size]: wrapped to the other edge (REPEAT) or
    // clamped to the edge texel, by whole-number arithmetic only (exact; mod() may divide
    // approximately and land on size).
    if (repeat) {
        i0 = f + size * vec2(lessThan(f, vec2(0.0)));
        i1 = (f + 1.0) - size * vec2(greaterThanEqual(f + 1.0, size));
    } else {
        i0 = max(f, vec2(0.0));
        i1 = min(f + 1.0, size - 1.0);
    }
}

// The four weights of the CPU reference, in its order.
vec4 bg_bilinear(vec4 t00, vec4 t10, vec4 t01, vec4 t11, vec2 a)
{
    vec2 b = 1.0 - a;
    return b.x * b.y * t00 + a.x * b.y * t10 + b.x * a.y * t01 + a.x * a.y * t11;
}

vec4 bg_texture_linear(sampler2D s, vec2 uv, vec2 size, bool repeat)
{
    vec2 i0, i1, a;
    bg_texture_taps(uv, size, repeat, i0, i1, a);
    return bg_bilinear(bg_texel(s, vec2(i0.x, i0.y), size), bg_texel(s, vec2(i1.x, i0.y), size),
                       bg_texel(s, vec2(i0.x, i1.y), size), bg_texel(s, vec2(i1.x, i1.y), size), a);
}
