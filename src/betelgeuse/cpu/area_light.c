/* Area lights' sample points (docs/shading.md 7): a sphere's point seen from the lit point, uniform
 * in solid angle, and a rectangle's, uniform in area; each then lights as a point light. */
#include "cpu_internal.h"

#define TWO_PI 6.28318530717958647692

void bgi_cpu_sphere_light_point(const double c[3], double r, const double p[3], const double uv[2], double q[3])
{
    double to[3] = {c[0] - p[0], c[1] - p[1], c[2] - p[2]};
    double d2 = bg_v3_dot(to, to), r2 = r * r;
    if (!(d2 > r2)) {
        bg_v3_set(q, c[0], c[1], c[2]);
        return;
    }
    double dist = sqrt(d2), w[3] = {to[0] / dist, to[1] / dist, to[2] / dist};
    /* 1 - cos of the cone's half angle, without the cancellation of 1 - sqrt(1 - x) for small x. */
    double x = r2 / d2;
    double one_minus_cos = uv[0] * (x / (1.0 + sqrt(1.0 - x)));
    double cos_t = 1.0 - one_minus_cos;
    double sin2 = one_minus_cos * (2.0 - one_minus_cos);
    double sin_t = sqrt(sin2 > 0.0 ? sin2 : 0.0);
    double phi = TWO_PI * uv[1], a[3], b[3], dir[3];
    bgi_cpu_basis_across(w, a, b);
    for (int i = 0; i < 3; i++)
        dir[i] = cos_t * w[i] + sin_t * (cos(phi) * a[i] + sin(phi) * b[i]);
    /* The nearer root of |p + t dir - c| = r. */
    double inside = r2 - d2 * sin2;
    double t = dist * cos_t - sqrt(inside > 0.0 ? inside : 0.0);
    for (int i = 0; i < 3; i++)
        q[i] = p[i] + t * dir[i];
}

void bgi_cpu_area_light_point(const bg_light *light, const double p[3], const double uv[2], double q[3])
{
    const double corner[3] = {light->position.x, light->position.y, light->position.z};
    if (light->type == BG_LIGHT_SPHERE) {
        bgi_cpu_sphere_light_point(corner, light->radius, p, uv, q);
        return;
    }
    const double eu[3] = {light->edge_u.x, light->edge_u.y, light->edge_u.z};
    const double ev[3] = {light->edge_v.x, light->edge_v.y, light->edge_v.z};
    for (int i = 0; i < 3; i++)
        q[i] = corner[i] + uv[0] * eu[i] + uv[1] * ev[i];
}

void bgi_cpu_rectangle_light_frame(const bg_light *light, double n[3], double *area)
{
    /* From unit edges, so that no edge length in the double range overflows the cross product. */
    double u[3] = {light->edge_u.x, light->edge_u.y, light->edge_u.z};
    double v[3] = {light->edge_v.x, light->edge_v.y, light->edge_v.z};
    double lu = sqrt(bg_v3_dot(u, u)), lv = sqrt(bg_v3_dot(v, v));
    bg_v3_normalize(u);
    bg_v3_normalize(v);
    bg_v3_cross(u, v, n);
    double sine = sqrt(bg_v3_dot(n, n));
    bg_v3_normalize(n);
    *area = lu * lv * sine;
}

bool bgi_cpu_light_sample(const bg_scene_state *state, uint32_t light, const bgi_sample_point *sample,
                          const double p[3], double l[3], double *t_max, double radiance[3])
{
    const bg_light *src = &state->lights[light];
    if (src->type != BG_LIGHT_SPHERE && src->type != BG_LIGHT_RECTANGLE)
        return bgi_cpu_light_arrival(src, p, l, t_max, radiance);
    double uv[2], q[3];
    bgi_sample_square(sample, BGI_DIMENSION_LIGHT((int)light), uv);
    bgi_cpu_area_light_point(src, p, uv, q);
    bg_light point = *src;
    point.type = BG_LIGHT_POINT;
    point.position = bg_vec3_make(q[0], q[1], q[2]);
    if (!bgi_cpu_light_arrival(&point, p, l, t_max, radiance))
        return false;
    if (src->type == BG_LIGHT_SPHERE)
        return true;
    /* The panel's cosine towards p: it shines from its front only. */
    double n[3], area;
    bgi_cpu_rectangle_light_frame(src, n, &area);
    double cos_l = -bg_v3_dot(n, l);
    if (!(cos_l > 0.0))
        return false;
    for (int i = 0; i < 3; i++)
        radiance[i] *= cos_l;
    return true;
}
