/* The environment (docs/shading.md 7.1): what a ray that meets nothing sees, and the environment's
 * direction at a camera sample when it lights the scene, drawn from the importance tables or
 * uniformly. */
#include "cpu_internal.h"

#define PI 3.14159265358979323846

/* The first index of the nondecreasing table[0 .. n) whose value exceeds xi (n when none does):
 * the search the GPU runs unrolled, by halving steps from 2^13 (every answer up to 16383, and the
 * largest texture has 16384 texels a side, the last of them 1 > xi). */
static int first_above(const double *table, int n, double xi)
{
    int lo = 0;
    for (int step = 1 << 13; step >= 1; step >>= 1)
        if (lo + step <= n && table[lo + step - 1] <= xi)
            lo += step;
    return lo;
}

static void direction_uv(const double d[3], double *u, double *v);

void bgi_cpu_environment_radiance(const bg_scene_state *state, const double d[3], double rgb[3])
{
    const bg_environment_data *e = &state->environment;
    const bg_texture_data *t = &state->textures[e->texture - 1];
    double u, v;
    direction_uv(d, &u, &v);
    /* Kept half a texel off the poles, so that a repeating texture does not blend the top and bottom
     * rows there. */
    double lo = 0.5 / t->height, hi = 1.0 - lo;
    v = v < lo ? lo : (v > hi ? hi : v);
    double rgba[4];
    bgi_cpu_texture_sample(t, u, v, rgba);
    for (int i = 0; i < 3; i++)
        rgb[i] = e->intensity * rgba[i];
}

bool bgi_cpu_environment_light(const bg_scene_state *state, const bgi_sample_point *sample, double l[3],
                               double radiance[3])
{
    double xi[2], pdf, texel[3];
    bgi_sample_square(sample, BGI_DIMENSION_LIGHT((int)state->light_count), xi);
    if (!bgi_cpu_environment_draw(state, xi, l, &pdf, texel))
        return false;
    /* As a light of 7, E_l = L / (pi pdf): then pi f E_l v' = f L v' / pdf estimates the integral. */
    double k = state->environment.intensity / (PI * pdf);
    for (int c = 0; c < 3; c++)
        radiance[c] = texel[c] * k;
    return radiance[0] > 0.0 || radiance[1] > 0.0 || radiance[2] > 0.0;
}

/* The (u, v) of a direction, v not yet kept off the poles (7.1). */
static void direction_uv(const double d[3], double *u, double *v)
{
    double y = d[1] < -1.0 ? -1.0 : (d[1] > 1.0 ? 1.0 : d[1]);
    /* Straight up or down the azimuth is any: the centre column. */
    *u = fabs(d[0]) + fabs(d[2]) > 0.0 ? 0.5 + atan2(d[0], -d[2]) / (2.0 * PI) : 0.5;
    *v = 1.0 - acos(y) / PI;
}

double bgi_cpu_environment_pdf(const bg_scene_state *state, const double d[3])
{
    const bg_environment_data *e = &state->environment;
    if (!e->marginal)
        return 1.0 / (4.0 * PI);
    const bg_texture_data *t = &state->textures[e->texture - 1];
    int w = t->width, h = t->height;
    double u, v;
    direction_uv(d, &u, &v);
    int i = (int)floor(u * w), j = (int)floor(v * h);
    i = i < w ? (i < 0 ? 0 : i) : w - 1;
    j = j < h ? (j < 0 ? 0 : j) : h - 1;
    const double *row = e->conditional + (size_t)j * (size_t)w;
    double dm = e->marginal[j] - (j > 0 ? e->marginal[j - 1] : 0.0);
    double dc = row[i] - (i > 0 ? row[i - 1] : 0.0);
    double sin_t = sin(PI * v);
    if (!(sin_t > 0.0) || !(dm > 0.0) || !(dc > 0.0))
        return 0.0;
    return dm * dc * w * h / (2.0 * PI * PI * sin_t);
}

bool bgi_cpu_environment_draw(const bg_scene_state *state, const double xi[2], double l[3], double *pdf_out,
                              double texel[3])
{
    const bg_environment_data *e = &state->environment;
    const bg_texture_data *t = &state->textures[e->texture - 1];
    int w = t->width, h = t->height, i, j;
    double u, v, pdf;
    if (e->marginal) {
        j = first_above(e->marginal, h, xi[0]);
        double m0 = j > 0 ? e->marginal[j - 1] : 0.0, dm = e->marginal[j] - m0;
        const double *row = e->conditional + (size_t)j * (size_t)w;
        i = first_above(row, w, xi[1]);
        double c0 = i > 0 ? row[i - 1] : 0.0, dc = row[i] - c0;
        if (!(dm > 0.0) || !(dc > 0.0))
            return false;
        v = (j + (xi[0] - m0) / dm) / h;
        u = (i + (xi[1] - c0) / dc) / w;
        /* The texel's share, spread over its square of (u, v) and then over the sphere, where the
         * square around v covers 2 pi^2 sin(theta) du dv of solid angle. */
        double sin_t = sin(PI * v);
        if (!(sin_t > 0.0))
            return false;
        pdf = dm * dc * w * h / (2.0 * PI * PI * sin_t);
    } else {
        double y = 1.0 - 2.0 * xi[0];
        u = xi[1];
        v = 1.0 - acos(y) / PI;
        i = (int)floor(u * w);
        j = (int)floor(v * h);
        i = i < w ? i : w - 1;
        j = j < h ? (j < 0 ? 0 : j) : h - 1;
        pdf = 1.0 / (4.0 * PI);
    }
    double theta = PI * (1.0 - v), phi = 2.0 * PI * (u - 0.5);
    bg_v3_set(l, sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
    double px[4];
    bgi_texture_texel(t, (size_t)j * (size_t)w + (size_t)i, px);
    for (int c = 0; c < 3; c++)
        texel[c] = px[c];
    *pdf_out = pdf;
    return true;
}
