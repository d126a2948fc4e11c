#version 110
// requires:
// The sample scramble (docs/shading.md 1.3), the twin of src/betelgeuse/common/scramble.c: every
// value an integer below 2^24, which float holds exactly, so both reach the same integers. mod by a
// power of two is exact (x / 4096.0 and floor are), which is why the hash uses no other modulus;
// the grid's column count is the one other, and it is corrected by hand, since GLSL 1.10 does not
// promise a correctly rounded division, and so may multiply by 1 / n, which llvmpipe does faster
// than it divides (the quotient is off by at most one either way).

float bg_mod_exact(float a, float n)
{
    float r = a - floor(a * (1.0 / n)) * n;
    if (r < 0.0)
        r += n;
    if (r >= n)
        r -= n;
    return r;
}

// One round: a permutation of [0, 4096): multiply by an odd constant and add, rotate the 12 bits by
// 7, then h + 2 h^2 (Rivest's permutation polynomial modulo a power of two, the nonlinear step:
// h^2 < 2^24, and every modulus is a power of two, so each step is exact without correction).
float bg_scramble_round(float h)
{
    h = mod(h * 2653.0 + 2731.0, 4096.0);
    float low = mod(h, 128.0);
    h = low * 32.0 + (h - low) / 128.0;
    return mod(h + 2.0 * mod(h * h, 2048.0), 4096.0);
}

float bg_scramble_mix1(float h, float v)
{
    return bg_scramble_round(mod(h + mod(v, 4096.0), 4096.0));
}

float bg_scramble_mix2(float h, float v)
{
    return bg_scramble_round(bg_scramble_mix1(h, v));
}

float bg_scramble_mix(float h, float v)
{
    return bg_scramble_round(bg_scramble_mix2(h, v));
}

// The hash of the frame pixel under frag (gl_FragCoord.xy); pixel_at = (the window's first frame
// column, the frame row of the window's bottom GL row), so that frame pixel (x, y) counts y down.
float bg_pixel_hash(vec2 frag, vec2 pixel_at)
{
    float x = floor(frag.x) + pixel_at.x, y = pixel_at.y - floor(frag.y);
    return bg_scramble_mix(bg_scramble_mix(floor(x / 4096.0) * 4.0 + floor(y / 4096.0), x), y);
}

// One round of the cell permutation on [0, 2^k), perm = (2^k, 2^(k - 1) or 1, 2^r, 2^(k - r)) with
// r = floor(k / 2): add the key, multiply and add, rotate the k bits by r, h + 2 h^2.
float bg_perm_round(float h, float key, vec4 perm)
{
    h = mod(h + key, perm.x);
    h = mod(h * 2653.0 + 2731.0, perm.x);
    float low = mod(h, perm.z);
    h = low * perm.w + (h - low) / perm.z;
    return mod(h + 2.0 * mod(h * h, perm.y), perm.x);
}

// The 12 bits of key rotated by k (perm.x = 2^k), so that each round of the permutation takes the
// next k bits of the key.
float bg_perm_key(float key, vec4 perm)
{
    float up = key * perm.x;
    return mod(up, 4096.0) + floor(up / 4096.0);
}

// Sample s's cell of n: three rounds, again while the result is no cell (cycle walking); after 32
// walks (one cell in 2^32) the sample keeps its own index, as on the CPU.
float bg_sample_cell(float s, float n, float key, vec4 perm)
{
    float t = s;
    float key2 = bg_perm_key(key, perm);
    float key3 = bg_perm_key(key2, perm);
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
    float g1 = bg_scramble_mix2(h, sample_of.x);
    float g2 = bg_scramble_mix1(g1, 1.0);
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
