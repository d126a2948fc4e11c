/* The sample scramble of docs/shading.md 1.3. Every value is an integer below 2^24, which float holds
 * exactly, so the GLSL twin (glsl110/bg_scramble.glsl) reaches the same integers computing in float;
 * here they are plain integers (glibc's fmod made the CPU reference three to five times slower). The
 * hash is a small permutation network on 12-bit integers (multiply by an odd constant and add, modulo
 * 4096, rotate the 12 bits by 7, h + 2 h^2 modulo 4096), three rounds per value mixed into a key,
 * since GLSL 1.10 has no bitwise operators to build a better-known hash from. Every modulus but the
 * grid's columns is a power of two, because the GPU computes such a remainder exactly in one step: an
 * earlier round cubed modulo the prime 4091, which needed two corrected remainders, and the scramble
 * then took about 40 % of the GPU's time on an area-light frame. A dimension pairs the pixel's
 * samples with its cells by a permutation of the n cells made the same way on the next power of two
 * (cycle walking): a fresh-looking Latin pairing per pixel and dimension. */
#include <math.h>

#include "render_view.h"
#include "scramble.h"

#define M 4096u

static uint32_t rotate7(uint32_t h);

/* One round: a permutation of [0, 4096). h * 2653 + 2731 < 2^24. The last step, h + 2 h^2 modulo
 * 4096 (a permutation polynomial modulo a power of two, Rivest 2001), is what makes the round
 * nonlinear: without a nonlinear step the lens and a light fell in one cell at half the rate chance
 * gives. h^2 < 2^24, and each modulus is a power of two, which float reaches exactly too. */
static uint32_t round_(uint32_t h)
{
    h = rotate7((h * 2653u + 2731u) % M);
    return (h + 2u * (h * h % 2048u)) % M;
}

/* h and a value v >= 0 mixed into a new hash in [0, 4096) by `rounds` rounds. */
static uint32_t mix(uint32_t h, uint32_t v, int rounds)
{
    h = (h + v % M) % M;
    for (int i = 0; i < rounds; i++)
        h = round_(h);
    return h;
}

void bgi_sample_point_make(int x, int y, int s, int n, bgi_sample_point *out)
{
    uint32_t high = (uint32_t)(x / 4096) * 4u + (uint32_t)(y / 4096);
    out->pixel_hash = mix(mix(high, (uint32_t)x, 3), (uint32_t)y, 3);
    out->sample = s;
    out->samples = n > 1 ? n : 1;
    out->rows = bgi_sample_rows(out->samples);
    out->columns = out->samples / out->rows;
    int k = 0;
    while ((1 << k) < out->samples)
        k++;
    out->perm_bits = k;
}

/* One round of the cell permutation on [0, 2^k): add the key, multiply and add, rotate the k bits by
 * floor(k / 2), h + 2 h^2. */
static uint32_t perm_round(uint32_t h, uint32_t key, const bgi_sample_point *p)
{
    uint32_t size = 1u << p->perm_bits, r = (uint32_t)p->perm_bits / 2u, half = size > 1u ? size / 2u : 1u;
    h = (h + key) % size;
    h = (h * 2653u + 2731u) % size;
    h = (h % (1u << r)) * (size >> r) + (h >> r);
    return (h + 2u * (h * h % half)) % size;
}

/* The 12 bits of h rotated by 7. */
static uint32_t rotate7(uint32_t h)
{
    return (h % 128u) * 32u + h / 128u;
}

/* The 12 bits of a key rotated by k, so that each round of the permutation adds the next k bits of
 * the key (with the same low bits in every round, n = 16 had only 16 permutations, and sample 0 fell
 * in 8 of the 16 cells). */
static uint32_t perm_key(uint32_t key, const bgi_sample_point *p)
{
    uint32_t up = key << p->perm_bits;
    return up % M + up / M;
}

/* Sample s's cell: three rounds on [0, 2^k), again while the result is not a cell (cycle walking, a
 * permutation of the n cells; each walk leaves [0, n) with chance below 1/2, so 32 walks settle all
 * but one cell in 2^32, which then keeps its own index on both renderers alike). */
static uint32_t cell_of(const bgi_sample_point *p, uint32_t key)
{
    uint32_t n = (uint32_t)p->samples, t = (uint32_t)p->sample;
    uint32_t key2 = perm_key(key, p), key3 = perm_key(key2, p);
    for (int walk = 0; walk < 32; walk++) {
        t = perm_round(perm_round(perm_round(t, key, p), key2, p), key3, p);
        if (t < n)
            return t;
    }
    return (uint32_t)p->sample;
}

/* The jitter in the cell takes fewer rounds than the keys: it only places the point inside its
 * cell, and g2 is a fixed permutation of g1 however many rounds make it. */
void bgi_sample_square(const bgi_sample_point *point, int dimension, double uv[2])
{
    uint32_t h = mix(point->pixel_hash, (uint32_t)dimension, 3);
    uint32_t cell = cell_of(point, h);
    uint32_t g1 = mix(h, (uint32_t)point->sample, 2), g2 = mix(g1, 1u, 1);
    uint32_t column = cell % (uint32_t)point->columns, row = cell / (uint32_t)point->columns;
    uv[0] = ((double)column + (g1 + 0.5) / M) / point->columns;
    uv[1] = ((double)row + (g2 + 0.5) / M) / point->rows;
}

void bgi_sample_disc(const double uv[2], double xy[2])
{
    const double quarter_pi = 0.78539816339744830962;
    double a = 2.0 * uv[0] - 1.0, b = 2.0 * uv[1] - 1.0;
    if (a == 0.0 && b == 0.0) {
        xy[0] = xy[1] = 0.0;
        return;
    }
    double r, phi;
    if (fabs(a) > fabs(b)) {
        r = a;
        phi = quarter_pi * (b / a);
    } else {
        r = b;
        phi = 2.0 * quarter_pi - quarter_pi * (a / b);
    }
    xy[0] = r * cos(phi);
    xy[1] = r * sin(phi);
}
