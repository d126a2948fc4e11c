/* The sample scramble of docs/shading.md 1.3. Every value is an integer below 2^24 (or a multiple
 * of 2^-13 below 2^14), which float holds exactly, so the GLSL twin (glsl110/bg_scramble.glsl)
 * reaches the same integers; the hash is a small permutation network on 12-bit integers
 * (multiply by an odd constant and add, modulo 4096, rotate the 12 bits by 7, cube modulo 4091),
 * three rounds per value mixed in, since GLSL 1.10 has no bitwise operators to build a better-known hash from. */
#include <math.h>

#include "render_view.h"
#include "scramble.h"

#define M 4096.0

/* The prime of the cube step: 4091 = 2 mod 3, so cubing permutes [0, 4091); 4090^2 < 2^24. */
#define P 4091.0

/* One round: a permutation of [0, 4096). An affine map modulo 4096 (h * 2653 + 2731 < 2^24) and a
 * rotation of the 12 bits mix the bits; the cube modulo a prime is what makes the round nonlinear
 * (without it the lens and a light fell in one cell at half the rate chance gives). */
static double round_(double h)
{
    h = fmod(h * 2653.0 + 2731.0, M);
    double low = fmod(h, 128.0);
    h = low * 32.0 + (h - low) / 128.0;
    if (h < P)
        h = fmod(fmod(h * h, P) * h, P);
    return h;
}

/* h and a value v >= 0 (below 2^24) mixed into a new hash in [0, 4096). */
static double mix(double h, double v)
{
    h = fmod(h + fmod(v, M), M);
    return round_(round_(round_(h)));
}

void bgi_sample_point_make(int x, int y, int s, int n, bgi_sample_point *out)
{
    double h = mix(mix(0.0, (double)x), (double)y);
    out->pixel_hash = mix(h, floor(x / M) * 4.0 + floor(y / M));
    out->sample = s;
    out->samples = n > 1 ? n : 1;
    out->rows = bgi_sample_rows(out->samples);
    out->columns = out->samples / out->rows;
}

void bgi_sample_square(const bgi_sample_point *point, int dimension, double uv[2])
{
    double n = (double)point->samples;
    double h = mix(point->pixel_hash, (double)dimension);
    double cell = fmod((double)point->sample + fmod(h, n), n);
    double g1 = mix(h, (double)point->sample), g2 = mix(g1, 1.0);
    double column = fmod(cell, (double)point->columns), row = (cell - column) / point->columns;
    uv[0] = (column + (g1 + 0.5) / M) / point->columns;
    uv[1] = (row + (g2 + 0.5) / M) / point->rows;
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
