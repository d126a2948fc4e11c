/* Schlick's BRDF (C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering",
 * Computer Graphics Forum 13(3), 1994) and the dielectric Fresnel term (docs/shading.md section 6). */
#include "../common/shapes.h"
#include "cpu_internal.h"

#define PI 3.14159265358979323846264338327950288

void bgi_cpu_schlick_s(const double c[3], double u, double s[3])
{
    double k = 1.0 - (u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u));
    double k5 = k * k * k * k * k;
    for (int i = 0; i < 3; i++)
        s[i] = c[i] + (1.0 - c[i]) * k5;
}

void bgi_cpu_schlick_split(double r, double *a, double *b, double *c)
{
    *b = 4.0 * r * (1.0 - r);
    if (r < 0.5) {
        *a = 0.0;
        *c = 1.0 - *b;
    } else {
        *a = 1.0 - *b;
        *c = 0.0;
    }
}

double bgi_cpu_schlick_d(double r, double p, double t, double v, double vl, double w)
{
    if (!(v > 0.0) || !(vl > 0.0))
        return 0.0;
    /* G(v) = v / (r - r v + v); G(v) G(v') / (4 pi v v') is written without dividing by v or v'. */
    double gv_den = r - r * v + v, gl_den = r - r * vl + vl;
    double g = (v / gv_den) * (vl / gl_den);
    double z_den = 1.0 + r * t * t - t * t;
    double z = z_den > 0.0 ? r / (z_den * z_den) : 0.0;
    double a_den = p * p - p * p * w * w + w * w;
    double a = a_den > 0.0 ? sqrt(p / a_den) : 0.0;
    return z * a / (4.0 * PI * gv_den * gl_den) + (1.0 - g) / PI;
}

/* One layer's non-Dirac reflectance without its spectral factor: a / pi + b D. */
static double layer_directional(const bg_cpu_layer *layer, double t, double v, double vl, double w)
{
    double a, b, c;
    bgi_cpu_schlick_split(layer->r, &a, &b, &c);
    double f = a / PI;
    if (b > 0.0)
        f += b * bgi_cpu_schlick_d(layer->r, layer->p, t, v, vl, w);
    return f;
}

void bgi_cpu_brdf(const bg_cpu_surface *surface, const double n[3], const double tangent[3], const double view[3],
                 const double light[3], double f[3])
{
    bg_v3_set(f, 0.0, 0.0, 0.0);
    double v = bg_v3_dot(n, view), vl = bg_v3_dot(n, light);
    if (!(v > 0.0) || !(vl > 0.0))
        return;
    double h[3] = {view[0] + light[0], view[1] + light[1], view[2] + light[2]};
    if (!bg_v3_normalize(h))
        return;
    double t = bg_v3_dot(n, h), u = bg_v3_dot(view, h);
    t = t > 1.0 ? 1.0 : t;
    /* w: cosine of the azimuth of h in the tangent plane against the tangent; 1 when h is along n. */
    double hp[3] = {h[0] - t * n[0], h[1] - t * n[1], h[2] - t * n[2]};
    double w = 1.0;
    if (bg_v3_dot(hp, hp) > 1e-24 && bg_v3_normalize(hp))
        w = bg_v3_dot(hp, tangent);
    w = w < -1.0 ? -1.0 : (w > 1.0 ? 1.0 : w);

    double s_base[3];
    bgi_cpu_schlick_s(surface->base.c, u, s_base);
    double d_base = layer_directional(&surface->base, t, v, vl, w);
    if (!surface->has_coat) {
        for (int i = 0; i < 3; i++)
            f[i] = s_base[i] * d_base;
        return;
    }
    double s_coat[3];
    bgi_cpu_schlick_s(surface->coat.c, u, s_coat);
    double d_coat = layer_directional(&surface->coat, t, v, vl, w);
    for (int i = 0; i < 3; i++)
        f[i] = s_coat[i] * d_coat + (1.0 - s_coat[i]) * s_base[i] * d_base;
}

void bgi_cpu_mirror_weight(const bg_cpu_surface *surface, double v, double m[3])
{
    double a, b, c_base, c_coat;
    double s_base[3], s_coat[3];
    bgi_cpu_schlick_split(surface->base.r, &a, &b, &c_base);
    bgi_cpu_schlick_s(surface->base.c, v, s_base);
    if (!surface->has_coat) {
        for (int i = 0; i < 3; i++)
            m[i] = c_base * s_base[i];
        return;
    }
    bgi_cpu_schlick_split(surface->coat.r, &a, &b, &c_coat);
    bgi_cpu_schlick_s(surface->coat.c, v, s_coat);
    for (int i = 0; i < 3; i++)
        m[i] = c_coat * s_coat[i] + (1.0 - s_coat[i]) * c_base * s_base[i];
}

double bgi_cpu_fresnel(double cos_i, double n1, double n2, double *cos_t)
{
    cos_i = cos_i < 0.0 ? 0.0 : (cos_i > 1.0 ? 1.0 : cos_i);
    double eta = n1 / n2;
    double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) {
        *cos_t = 0.0;
        return 1.0;
    }
    double ct = sqrt(1.0 - sin2_t);
    *cos_t = ct;
    double rs_den = n1 * cos_i + n2 * ct, rp_den = n2 * cos_i + n1 * ct;
    if (!(rs_den > 0.0) || !(rp_den > 0.0))
        return 1.0;
    double rs = (n1 * cos_i - n2 * ct) / rs_den;
    double rp = (n2 * cos_i - n1 * ct) / rp_den;
    return 0.5 * (rs * rs + rp * rp);
}

bool bgi_cpu_thin(const bg_scene_state *state, const bg_object_data *object)
{
    /* An open mesh is thin as a plane is: lit on both sides, passing light straight on. */
    return bg_shape_thin(object->shape) || (object->mesh && state->materials[object->material].sides == BG_SIDES_BOTH);
}

void bgi_cpu_interface_at(const bg_cpu_surface *surface, bool thin, bool entering, double cos_i,
                          bg_cpu_interface *out)
{
    out->fresnel = 0.0;
    out->cos_t = 0.0;
    out->eta = 1.0;
    if (!(surface->transparency > 0.0) || thin)
        return;
    double n1 = entering ? 1.0 : surface->ior, n2 = entering ? surface->ior : 1.0;
    out->fresnel = bgi_cpu_fresnel(cos_i, n1, n2, &out->cos_t);
    out->eta = n1 / n2;
}
