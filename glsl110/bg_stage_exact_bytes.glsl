#version 110
// requires:
// The bytes the host's encoding gives a mean of samples (gpu/exact_bytes.c): the host's byte of
// sum / n is a step function of the float sum, so the byte is how many of its 255 steps the sum has
// reached. thresholds is 256 x 1, texel k holding in .r the least float sum whose byte is k (texel 0
// holds n - 0.5, for alpha); eight comparisons find the byte. A comparison of floats is exact on every GL, so the bytes
// are the host's without any GPU division, pow or rounding taking part.

float bg_exact_step(sampler2D thresholds, float b, float step, float s)
{
    // (b + step + 0.5) / 256 is a texel's centre, exact in float, so NEAREST reads that texel.
    float t = texture2D(thresholds, vec2((b + step + 0.5) / 256.0, 0.5)).r;
    return s >= t ? b + step : b;
}

float bg_exact_byte(sampler2D thresholds, float s)
{
    float b = 0.0;
    b = bg_exact_step(thresholds, b, 128.0, s);
    b = bg_exact_step(thresholds, b, 64.0, s);
    b = bg_exact_step(thresholds, b, 32.0, s);
    b = bg_exact_step(thresholds, b, 16.0, s);
    b = bg_exact_step(thresholds, b, 8.0, s);
    b = bg_exact_step(thresholds, b, 4.0, s);
    b = bg_exact_step(thresholds, b, 2.0, s);
    b = bg_exact_step(thresholds, b, 1.0, s);
    return b;
}

// Written as b / 255, which an RGBA8 target stores as b (as bg_encode's output). Alpha is 255, or 0
// where a sample's walk ran out of steps: the sum's alpha counts the samples that finished, and
// texel 0 holds n - 0.5 (gpu/shared/fallback.c renders the marked pixels again).
vec4 bg_exact_bytes(sampler2D thresholds, vec4 sum)
{
    float whole = texture2D(thresholds, vec2(0.5 / 256.0, 0.5)).r;
    return vec4(bg_exact_byte(thresholds, sum.r), bg_exact_byte(thresholds, sum.g), bg_exact_byte(thresholds, sum.b),
                sum.a >= whole ? 255.0 : 0.0) / 255.0;
}
