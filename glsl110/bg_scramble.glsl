#version 110
// requires:
// The sample scramble (docs/shading.md 1.3), the twin of src/betelgeuse/common/scramble.c: every
// value an integer below 2^24, which float holds exactly, so both reach the same integers. mod by a
// power of two is exact (x / 4096.0 and floor are); by another n it is corrected by hand, since
// GLSL 1.10 does not promise a correctly rounded division, and so may multiply by 1 / n, which
// llvmpipe does faster than it divides (the quotient is off by at most one either way).

float bg_mod_exact(float a, float n)
{
    float r = a - floor(a * (1.0 / n)) * n;
    if (r < 0.0)
        r += n;
    if (r >= n)
        r -= n;
    return r;
}

// One round: a permutation of [0, 4096) (multiply, add, rotate the 12 bits by 7, cube modulo the
// prime 4091, which permutes [0, 4091) since 4091 = 2 mod 3).
float bg_scramble_round(float h)
{
    h = mod(h * 2653.0 + 2731.0, 4096.0);
    float low = mod(h, 128.0);
    h = low * 32.0 + (h - low) / 128.0;
    if (h < 4091.0)
        h = bg_mod_exact(bg_mod_exact(h * h, 4091.0) * h, 4091.0);
    return h;
}

float bg_scramble_mix(float h, float v)
{
    h = mod(h + mod(v, 4096.0), 4096.0);
    return bg_scramble_round(bg_scramble_round(bg_scramble_round(h)));
}

// The hash of the frame pixel under frag (gl_FragCoord.xy); pixel_at = (the window's first frame
// column, the frame row of the window's bottom GL row), so that frame pixel (x, y) counts y down.
float bg_pixel_hash(vec2 frag, vec2 pixel_at)
{
    float x = floor(frag.x) + pixel_at.x, y = pixel_at.y - floor(frag.y);
    float h = bg_scramble_mix(bg_scramble_mix(0.0, x), y);
    return bg_scramble_mix(h, floor(x / 4096.0) * 4.0 + floor(y / 4096.0));
}

// One round of the cell permutation on [0, 2^k), perm = (2^k, the prime = 2 mod 3 below it, 2^r,
// 2^(k - r)) with r = floor(k / 2): add the key, multiply and add, rotate the k bits by r, cube.
float bg_perm_round(float h, float key, vec4 perm)
{
    h = mod(h + key, perm.x);
    h = mod(h * 2653.0 + 2731.0, perm.x);
    float low = mod(h, perm.z);
    h = low * perm.w + (h - low) / perm.z;
    if (h < perm.y)
        h = bg_mod_exact(bg_mod_exact(h * h, perm.y) * h, perm.y);
    return h;
}

// Sample s's cell of n: three rounds, again while the result is no cell (cycle walking); after 32
// walks (one cell in 2^32) the sample keeps its own index, as on the CPU.
float bg_sample_cell(float s, float n, float key, vec4 perm)
{
    float t = s;
    // Each round adds other bits of the key, rotated by 7 from round to round, as on the CPU.
    float low = mod(key, 128.0);
    float key2 = low * 32.0 + (key - low) / 128.0;
    low = mod(key2, 128.0);
    float key3 = low * 32.0 + (key2 - low) / 128.0;
    for (int walk = 0; walk < 32; walk++) {
        t = bg_perm_round(bg_perm_round(bg_perm_round(t, key, perm), key2, perm), key3, perm);
        if (t < n)
            return t;
    }
    return s;
}

// The unit-square point of a dimension at camera sample sample_of = (s, n, columns, rows), its
// cells permuted by perm (bg_perm_round).
vec2 bg_sample_square(float pixel_hash, float dimension, vec4 sample_of, vec4 perm)
{
    float h = bg_scramble_mix(pixel_hash, dimension);
    float cell = bg_sample_cell(sample_of.x, sample_of.y, h, perm);
    float g1 = bg_scramble_mix(h, sample_of.x);
    float g2 = bg_scramble_mix(g1, 1.0);
    float column = bg_mod_exact(cell, sample_of.z);
    float row = floor((cell - column) / sample_of.z + 0.5);
    return vec2((column + (g1 + 0.5) / 4096.0) / sample_of.z, (row + (g2 + 0.5) / 4096.0) / sample_of.w);
}

// Shirley and Chiu's concentric map of the unit square onto the unit disc.
vec2 bg_sample_disc(vec2 uv)
{
    float a = 2.0 * uv.x - 1.0, b = 2.0 * uv.y - 1.0;
    if (a == 0.0 && b == 0.0)
        return vec2(0.0);
    float r, phi;
    if (abs(a) > abs(b)) {
        r = a;
        phi = 0.785398163 * (b / a);
    } else {
        r = b;
        phi = 1.570796327 - 0.785398163 * (a / b);
    }
    return r * vec2(cos(phi), sin(phi));
}
