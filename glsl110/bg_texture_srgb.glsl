#version 110
// requires: bg_texture_filter.glsl
// An 8-bit sRGB scene texture decoded where it is sampled (docs/shading.md 5.2), the twin of
// bgi_texture_channel in src/betelgeuse/scene/texture.c: each fetched texel's R, G and B become the
// linear values of bgi_srgb_table (common/srgb_table.c) before any filter weight, so the filter works
// in linear light as the CPU reference's does; alpha is linear. table is that table on the GPU: a
// 256 x 1 RGBA32F NEAREST texture holding the float of entry k in every channel of texel k. A
// lookup rather than pow(): GLSL leaves pow's precision unspecified, the table is exact.

// Channel value v of an RGBA8 texel, which GL hands over as k / 255 (to within its conversion's
// rounding): k is the nearest whole number to 255 v, and entry k sits at the centre of texel k.
float bg_srgb_channel(float v, sampler2D table)
{
    float k = floor(v * 255.0 + 0.5);
    return texture2D(table, vec2((k + 0.5) / 256.0, 0.5)).r;
}

vec4 bg_srgb_decode(vec4 t, sampler2D table)
{
    return vec4(bg_srgb_channel(t.r, table), bg_srgb_channel(t.g, table), bg_srgb_channel(t.b, table), t.a);
}

// bg_texture_linear of an sRGB texture: the same footprint and weights, each texel decoded first.
vec4 bg_texture_linear_srgb(sampler2D s, vec2 uv, vec2 size, bool repeat, sampler2D table)
{
    vec2 i0, i1, a;
    bg_texture_taps(uv, size, repeat, i0, i1, a);
    return bg_bilinear(bg_srgb_decode(bg_texel(s, vec2(i0.x, i0.y), size), table),
                       bg_srgb_decode(bg_texel(s, vec2(i1.x, i0.y), size), table),
                       bg_srgb_decode(bg_texel(s, vec2(i0.x, i1.y), size), table),
                       bg_srgb_decode(bg_texel(s, vec2(i1.x, i1.y), size), table), a);
}
