#version 110
// requires:
// The marks of the pixels whose walks ran out of steps, packed for a small read-back
// (gpu/shared/fallback.c): each RGBA8 texel of the marks holds 32 pixels of one row, 8 to a channel,
// bit b of channel c for pixel 32 * texel + 8 * c + b. A pixel is marked when its alpha is below
// whole - 0.5: a frame's alpha is 1, or 0 where a walk ran out (whole 1); a sum of n samples' alpha
// counts the samples that finished (whole n). The frame comes as an argument, since the pass
// declares its sampler.

// The byte of the 8 pixels from x0 on in row `row` (a texel centre in 0..1) of a frame of `size`
// pixels: bit b set when pixel x0 + b is marked. Pixels past the row's end are not. The texel is
// read before the test, so that no texture2D sits in control flow that differs between pixels.
float bg_mark_byte(sampler2D frame, vec2 size, float whole, float x0, float row)
{
    float byte = 0.0;
    float bit = 1.0;
    for (int b = 0; b < 8; b++) {
        float x = x0 + float(b);
        float alpha = texture2D(frame, vec2((x + 0.5) / size.x, row)).a;
        if (x < size.x && alpha < whole - 0.5)
            byte += bit;
        bit *= 2.0;
    }
    return byte;
}

// The marks texel at fragment column `column` (floor(gl_FragCoord.x)), as RGBA8 stores it:
// each byte k written as k / 255.
vec4 bg_mark_texel(sampler2D frame, vec2 size, float whole, float column, float row)
{
    float x0 = column * 32.0;
    return vec4(bg_mark_byte(frame, size, whole, x0, row), bg_mark_byte(frame, size, whole, x0 + 8.0, row),
                bg_mark_byte(frame, size, whole, x0 + 16.0, row),
                bg_mark_byte(frame, size, whole, x0 + 24.0, row)) / 255.0;
}
