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

vec4 bg_texture_linear(sampler2D s, vec2 uv, vec2 size, bool repeat)
{
    // The coordinate in [0, 1] as GL reduces it before filtering: fract for REPEAT (exact for
    // uv >= 0, one rounding of uv + 1 for uv < 0), clamp for CLAMP_TO_EDGE (exact).
    vec2 c = repeat ? fract(uv) : clamp(uv, 0.0, 1.0);
    // x in [-0.5, size - 0.5]: one rounding of the product (exact for a power-of-two size); the
    // subtraction, floor and x - f are exact in float for sizes up to 2^22.
    vec2 x = c * size - 0.5;
    vec2 f = floor(x);
    vec2 a = x - f;
    // The two texels per axis, f and f + 1 in [-1, size]: wrapped to the other edge (REPEAT) or
    // clamped to the edge texel, by whole-number arithmetic only (exact; mod() may divide
    // approximately and land on size).
    vec2 i0, i1;
    if (repeat) {
        i0 = f + size * vec2(lessThan(f, vec2(0.0)));
        i1 = (f + 1.0) - size * vec2(greaterThanEqual(f + 1.0, size));
    } else {
        i0 = max(f, vec2(0.0));
        i1 = min(f + 1.0, size - 1.0);
    }
    vec4 t00 = bg_texel(s, vec2(i0.x, i0.y), size);
    vec4 t10 = bg_texel(s, vec2(i1.x, i0.y), size);
    vec4 t01 = bg_texel(s, vec2(i0.x, i1.y), size);
    vec4 t11 = bg_texel(s, vec2(i1.x, i1.y), size);
    vec2 b = 1.0 - a;
    return b.x * b.y * t00 + a.x * b.y * t10 + b.x * a.y * t01 + a.x * a.y * t11;
}
