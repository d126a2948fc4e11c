/* The path integrator (docs/shading.md 13): one path per camera sample, each hit adding what it
 * emits and every light sampled towards it, then going on one way drawn from the surface, with
 * multiple importance sampling where a light can be met both ways and Russian roulette deep down. */
#include <float.h>

#include "../common/shapes.h"
#include "cpu_internal.h"

#define PI 3.14159265358979323846264338327950288

static double max3(const double v[3])
{
    double m = v[0] > v[1] ? v[0] : v[1];
    return m > v[2] ? m : v[2];
}

/* The power heuristic's weight of a strategy of density a against one of density b. */
static double power_weight(double a, double b)
{
    double a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

/* The ways on from one hit (13.3, step 5) and what the f lobe's density needs. */
typedef struct ways {
    double w_f[3], w_refl[3], w_refr[3];
    double p_f, p_refl, p_refr; /* the shares of the choice */
    double r_g, q_c;            /* the lobe's roughness and the cosine's share of the f mix */
} ways;

/* rho of 13.3: the non-Dirac reflectance's weight at cos_i, per channel. */
static void f_weight(const bg_cpu_surface *s, double cos_i, double rho[3])
{
    double a, b, c, sb[3];
    bgi_cpu_schlick_split(s->base.r, &a, &b, &c);
    bgi_cpu_schlick_s(s->base.c, cos_i, sb);
    for (int i = 0; i < 3; i++)
        rho[i] = sb[i] * (a + b);
    if (!s->has_coat)
        return;
    double ac, bc, cc, sc[3];
    bgi_cpu_schlick_split(s->coat.r, &ac, &bc, &cc);
    bgi_cpu_schlick_s(s->coat.c, cos_i, sc);
    for (int i = 0; i < 3; i++)
        rho[i] = sc[i] * (ac + bc) + (1.0 - sc[i]) * rho[i];
}

/* Z(t) of 6.2 at roughness r (0 where its denominator vanishes). */
static double zenith(double r, double t)
{
    double den = 1.0 + r * t * t - t * t;
    return den > 0.0 ? r / (den * den) : 0.0;
}

/* The density with which the f way draws the unit direction l (0 where it cannot). */
static double f_pdf(const ways *w, const double n[3], const double view[3], const double l[3])
{
    double cos_l = bg_v3_dot(n, l);
    if (!(w->p_f > 0.0) || !(cos_l > 0.0))
        return 0.0;
    double p = w->q_c * cos_l / PI;
    if (w->q_c < 1.0) {
        double h[3] = {view[0] + l[0], view[1] + l[1], view[2] + l[2]};
        if (bg_v3_normalize(h)) {
            double t = bg_v3_dot(n, h), vh = bg_v3_dot(view, h);
            t = t > 1.0 ? 1.0 : t;
            if (t > 0.0 && vh > 0.0)
                p += (1.0 - w->q_c) * zenith(w->r_g, t) * t / (4.0 * PI * vh);
        }
    }
    return w->p_f * p;
}

/* The f way's direction for the rescaled event e1 and the direction point uv; false below the
 * surface. */
static bool f_direction(const ways *w, const double n[3], const double view[3], double e1, const double uv[2],
                        double l[3])
{
    double a[3], b[3];
    bgi_cpu_basis_across(n, a, b);
    if (e1 < w->q_c) {
        double xy[2];
        bgi_sample_disc(uv, xy);
        double z2 = 1.0 - xy[0] * xy[0] - xy[1] * xy[1];
        double z = sqrt(z2 > 0.0 ? z2 : 0.0);
        for (int i = 0; i < 3; i++)
            l[i] = xy[0] * a[i] + xy[1] * b[i] + z * n[i];
    } else {
        /* 9.1's normal of the lobe, then the view mirrored about it. */
        double q = 1.0 + (w->r_g - 1.0) * uv[0];
        double cos_h = sqrt((1.0 - uv[0]) / q), sin_h = sqrt(w->r_g * uv[0] / q), phi = 2.0 * PI * uv[1], h[3];
        for (int i = 0; i < 3; i++)
            h[i] = cos_h * n[i] + sin_h * (cos(phi) * a[i] + sin(phi) * b[i]);
        double vh = bg_v3_dot(view, h);
        for (int i = 0; i < 3; i++)
            l[i] = 2.0 * vh * h[i] - view[i];
    }
    return bg_v3_normalize(l) && bg_v3_dot(l, n) > 0.0;
}

/* Under the path integrator an area light is an emitter of uniform radiance (13.1). */
static void light_radiance(const bg_light *light, double le[3])
{
    double k;
    if (light->type == BG_LIGHT_SPHERE) {
        k = light->intensity / (light->radius * light->radius);
    } else {
        double n[3], area;
        bgi_cpu_rectangle_light_frame(light, n, &area);
        k = PI * light->intensity / area;
    }
    for (int i = 0; i < 3; i++)
        le[i] = light->color[i] * k;
}

/* The solid angle of a sphere of radius r seen from distance dist > r. */
static double sphere_solid_angle(double r, double dist)
{
    double x = (r * r) / (dist * dist);
    return 2.0 * PI * (x / (1.0 + sqrt(1.0 - x)));
}

/* The density with which a light's own sampling draws the ray from `from` along unit d that meets
 * its object at distance t (13.3, step 2); 0 when it cannot. */
static double light_pdf(const bg_light *light, const double from[3], const double d[3], double t)
{
    if (light->type == BG_LIGHT_SPHERE) {
        double c[3] = {light->position.x - from[0], light->position.y - from[1], light->position.z - from[2]};
        double dist = sqrt(bg_v3_dot(c, c));
        return dist > light->radius ? 1.0 / sphere_solid_angle(light->radius, dist) : 0.0;
    }
    double n[3], area;
    bgi_cpu_rectangle_light_frame(light, n, &area);
    double cos_l = -bg_v3_dot(d, n);
    return cos_l > 0.0 ? t * t / (area * cos_l) : 0.0;
}

/* What a hit itself gives (13.3, step 2): a visible light's object its radiance on its front,
 * weighted against the light's sampling where the ray was drawn from f (p_b > 0), any other
 * object its material's emission. */
static void emission(const bg_scene_state *state, const bg_cpu_hit *hit, const bg_cpu_surface *surface,
                     const double from[3], const double d[3], double p_b, double e[3])
{
    const bg_object_data *object = &state->objects[hit->object];
    if (!object->light) {
        bg_v3_set(e, surface->emission[0], surface->emission[1], surface->emission[2]);
        return;
    }
    const bg_light *light = &state->lights[object->light - 1];
    bool front;
    if (light->type == BG_LIGHT_SPHERE) {
        front = hit->entering;
    } else {
        double n[3], area;
        bgi_cpu_rectangle_light_frame(light, n, &area);
        front = bg_v3_dot(d, n) < 0.0;
    }
    bg_v3_set(e, 0.0, 0.0, 0.0);
    if (!front)
        return;
    light_radiance(light, e);
    double w = p_b > 0.0 ? power_weight(p_b, light_pdf(light, from, d, hit->t)) : 1.0;
    for (int i = 0; i < 3; i++)
        e[i] *= w;
}

/* One hit's surface, as every step of 13.3 needs it. */
typedef struct vertex {
    const bg_cpu_hit *hit;
    const bg_cpu_surface *surface;
    double view[3];
    double opaque;
} vertex;

/* Adds beta x f(V, l) x le x (n.l) x w / pdf for a light direction l that reaches the hit unshadowed. */
static void add_light(const vertex *v, const double beta[3], const double l[3], const double le[3], double pdf,
                      double w, double out[3])
{
    double f[3];
    bgi_cpu_brdf(v->surface, v->hit->normal, v->hit->tangent, v->view, l, f);
    double k = v->opaque * bg_v3_dot(v->hit->normal, l) * w / pdf;
    for (int i = 0; i < 3; i++)
        out[i] += beta[i] * f[i] * le[i] * k;
}

/* Next-event estimation (13.3, step 3) towards light k from the sample point of its dimension. */
static void sample_light(const bg_scene_state *state, const bgi_sample_point *sample, const vertex *v, const ways *w,
                         uint32_t k, int level, const double beta[3], double out[3])
{
    const bg_cpu_hit *hit = v->hit;
    const double *n = hit->normal;
    const bg_light *light = &state->lights[k];
    int slots = (int)state->light_count + 1;
    double l[3], t_max, from[3];
    if (light->type != BG_LIGHT_SPHERE && light->type != BG_LIGHT_RECTANGLE) {
        /* A Dirac light: Whitted's term, pi f E_l v' (8). */
        double e[3];
        if (!bgi_cpu_light_arrival(light, hit->position, l, &t_max, e) || !(bg_v3_dot(n, l) > 0.0))
            return;
        bgi_cpu_leave_origin(hit, l, from);
        if (!bgi_cpu_shadowed(state, from, l, t_max, hit->object, hit->triangle))
            add_light(v, beta, l, e, 1.0 / PI, 1.0, out);
        return;
    }
    double uv[2], q[3];
    bgi_sample_square(sample, BGI_DIMENSION_PATH_LIGHT((int)k, level, slots), uv);
    const double c[3] = {light->position.x, light->position.y, light->position.z};
    double pdf = 0.0;
    if (light->type == BG_LIGHT_SPHERE) {
        double to[3] = {c[0] - hit->position[0], c[1] - hit->position[1], c[2] - hit->position[2]};
        double dist = sqrt(bg_v3_dot(to, to));
        if (!(dist > light->radius))
            return; /* inside the light: it has no outside to see */
        pdf = 1.0 / sphere_solid_angle(light->radius, dist);
    }
    bgi_cpu_area_light_point(light, hit->position, uv, q);
    bg_v3_set(l, q[0] - hit->position[0], q[1] - hit->position[1], q[2] - hit->position[2]);
    t_max = sqrt(bg_v3_dot(l, l));
    if (!(t_max > 0.0) || !bg_v3_normalize(l) || !(bg_v3_dot(n, l) > 0.0))
        return;
    if (light->type == BG_LIGHT_RECTANGLE) {
        double nl[3], area;
        bgi_cpu_rectangle_light_frame(light, nl, &area);
        double cos_l = -bg_v3_dot(nl, l);
        if (!(cos_l > 0.0))
            return;
        pdf = t_max * t_max / (area * cos_l);
    }
    bgi_cpu_leave_origin(hit, l, from);
    if (bgi_cpu_shadowed(state, from, l, t_max, hit->object, hit->triangle))
        return;
    double le[3];
    light_radiance(light, le);
    /* A light nobody sees is met by this strategy only. */
    double weight = light->visible ? power_weight(pdf, f_pdf(w, n, v->view, l)) : 1.0;
    add_light(v, beta, l, le, pdf, weight, out);
}

/* Next-event estimation towards the environment (13.3, step 3). */
static void sample_environment(const bg_scene_state *state, const bgi_sample_point *sample, const vertex *v,
                               const ways *w, int level, const double beta[3], double out[3])
{
    int slots = (int)state->light_count + 1;
    double xi[2], l[3], pdf, texel[3], from[3];
    bgi_sample_square(sample, BGI_DIMENSION_PATH_LIGHT((int)state->light_count, level, slots), xi);
    if (!bgi_cpu_environment_draw(state, xi, l, &pdf, texel) || !(pdf > 0.0) ||
        !(bg_v3_dot(v->hit->normal, l) > 0.0))
        return;
    bgi_cpu_leave_origin(v->hit, l, from);
    if (bgi_cpu_shadowed(state, from, l, DBL_MAX, v->hit->object, v->hit->triangle))
        return;
    double le[3];
    bgi_cpu_environment_radiance(state, l, le);
    add_light(v, beta, l, le, pdf, power_weight(pdf, f_pdf(w, v->hit->normal, v->view, l)), out);
}

/* The ways on and their shares (13.3, step 5); lit: lights reach the hit (its f way exists). */
static void make_ways(const bg_cpu_surface *s, bool lit, double opaque, double cos_i, double fresnel, ways *w)
{
    double m[3], rho[3];
    bgi_cpu_mirror_weight(s, cos_i, m);
    f_weight(s, cos_i, rho);
    for (int i = 0; i < 3; i++) {
        w->w_f[i] = lit ? opaque * rho[i] : 0.0;
        w->w_refl[i] = opaque * m[i] + s->transparency * fresnel;
        w->w_refr[i] = s->transparency * (1.0 - fresnel);
    }
    double f = max3(w->w_f), r = max3(w->w_refl), t = max3(w->w_refr), sum = f + r + t;
    w->p_f = sum > 0.0 ? f / sum : 0.0;
    w->p_refl = sum > 0.0 ? r / sum : 0.0;
    w->p_refr = sum > 0.0 ? t / sum : 0.0;
    w->r_g = s->has_coat ? s->coat.r : s->base.r;
    w->q_c = 1.0 - 2.0 * w->r_g * (1.0 - w->r_g); /* 1 - b_g / 2 */
}

/* The path's state between hits. */
typedef struct path {
    double o[3], d[3];
    double beta[3];
    double p_b; /* the density the ray was drawn with from f; 0 for the camera ray and Dirac ways */
    uint32_t skip, skip_triangle, inside;
} path;

void bgi_cpu_path_ray(const bg_scene_state *state, const bg_render_settings *settings, const bgi_sample_point *sample,
                      const double o[3], const double d[3], double out[3])
{
    path ray = {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, {1.0, 1.0, 1.0}, 0.0, BG_CPU_NONE, BG_CPU_NONE,
                BG_CPU_NONE};
    bg_v3_set(out, 0.0, 0.0, 0.0);
    for (int level = 0;; level++) {
        bg_cpu_hit hit;
        if (!bgi_cpu_nearest_hit_except(state, ray.o, ray.d, ray.skip, ray.skip_triangle, ray.inside, &hit)) {
            double seen[3] = {settings->background[0], settings->background[1], settings->background[2]};
            double w = 1.0;
            if (state->environment.on) {
                bgi_cpu_environment_radiance(state, ray.d, seen);
                if (state->environment.lights && ray.p_b > 0.0)
                    w = power_weight(ray.p_b, bgi_cpu_environment_pdf(state, ray.d));
            }
            for (int i = 0; i < 3; i++)
                out[i] += ray.beta[i] * w * seen[i];
            return;
        }
        const bg_object_data *object = &state->objects[hit.object];
        bg_cpu_surface surface;
        bgi_cpu_surface_eval(state, &state->materials[object->material], hit.uv, &surface);
        const double *n = hit.normal;
        vertex v = {&hit, &surface, {-ray.d[0], -ray.d[1], -ray.d[2]}, 1.0 - surface.transparency};
        double e[3];
        emission(state, &hit, &surface, ray.o, ray.d, ray.p_b, e);
        /* A light's own object is an emitter and nothing else: it reflects nothing (13.1). */
        if (object->light) {
            for (int i = 0; i < 3; i++)
                out[i] += ray.beta[i] * e[i];
            return;
        }
        for (int i = 0; i < 3; i++)
            out[i] += ray.beta[i] * (e[i] + (settings->path_ambient ? v.opaque * state->ambient[i] * surface.ambient[i]
                                                                    : 0.0));

        double cos_v = bg_v3_dot(n, v.view);
        bool thin = bg_shape_thin(object->shape) || (object->mesh && state->materials[object->material].sides ==
                                                                          BG_SIDES_BOTH);
        bool lit = v.opaque > 0.0 && cos_v > 0.0 && (thin || hit.entering);
        double fresnel = 0.0, cos_t = 0.0, eta = 1.0;
        double cos_i = cos_v > 0.0 ? (cos_v < 1.0 ? cos_v : 1.0) : 0.0;
        if (surface.transparency > 0.0 && !thin) {
            double n1 = hit.entering ? 1.0 : surface.ior, n2 = hit.entering ? surface.ior : 1.0;
            fresnel = bgi_cpu_fresnel(cos_i, n1, n2, &cos_t);
            eta = n1 / n2;
        }
        ways w;
        make_ways(&surface, lit, v.opaque, cos_i, fresnel, &w);
        if (lit) {
            for (uint32_t k = 0; k < state->light_count; k++)
                sample_light(state, sample, &v, &w, k, level, ray.beta, out);
            if (state->environment.on && state->environment.lights)
                sample_environment(state, sample, &v, &w, level, ray.beta, out);
        }
        if (level >= settings->max_depth)
            return;

        /* The way on, from the event point: f, reflect, transmit in that order along [0, 1). */
        double event[2], uv[2], next[3], beta[3];
        bgi_sample_square(sample, BGI_DIMENSION_PATH_EVENT(level), event);
        bgi_sample_square(sample, BGI_DIMENSION_PATH_DIRECTION(level), uv);
        bool transmit = false;
        ray.p_b = 0.0;
        if (event[0] < w.p_f) {
            if (!f_direction(&w, n, v.view, event[0] / w.p_f, uv, next))
                return;
            double pdf = f_pdf(&w, n, v.view, next), f[3];
            if (!(pdf > 0.0))
                return;
            bgi_cpu_brdf(&surface, n, hit.tangent, v.view, next, f);
            double k = v.opaque * bg_v3_dot(n, next) / pdf;
            for (int i = 0; i < 3; i++)
                beta[i] = ray.beta[i] * f[i] * k;
            ray.p_b = pdf;
        } else if (event[0] < w.p_f + w.p_refl || !(w.p_refr > 0.0)) {
            if (!(w.p_refl > 0.0))
                return;
            double dn = bg_v3_dot(ray.d, n);
            for (int i = 0; i < 3; i++)
                next[i] = ray.d[i] - 2.0 * dn * n[i];
            double lobe = surface.has_coat ? surface.coat.r : surface.base.r;
            const bg_material *material = &state->materials[object->material];
            if (material->glossy && lobe > 0.0 && !bgi_cpu_glossy_reflect(ray.d, n, lobe, uv, next))
                return;
            if (!bg_v3_normalize(next))
                return;
            for (int i = 0; i < 3; i++)
                beta[i] = ray.beta[i] * w.w_refl[i] / w.p_refl;
        } else {
            transmit = true;
            bg_v3_set(next, ray.d[0], ray.d[1], ray.d[2]);
            if (!thin) {
                double k = eta * cos_i - cos_t;
                for (int i = 0; i < 3; i++)
                    next[i] = eta * ray.d[i] + k * n[i];
            }
            if (!bg_v3_normalize(next))
                return;
            for (int i = 0; i < 3; i++)
                beta[i] = ray.beta[i] * w.w_refr[i] / w.p_refr;
        }
        /* Russian roulette (13.3, step 6). */
        double keep = max3(beta);
        if (!(keep > 0.0) || !isfinite(keep))
            return;
        if (level >= BG_PATH_ROULETTE_DEPTH && keep < 1.0) {
            if (!(event[1] < keep))
                return;
            for (int i = 0; i < 3; i++)
                beta[i] /= keep;
        }
        /* The roots the next ray takes are 9's. */
        bool stays_inside = !transmit && !thin && !hit.entering && !object->mesh;
        bool enters = transmit && !thin && hit.entering && !object->mesh;
        if (object->mesh) {
            ray.skip = hit.object;
            ray.inside = BG_CPU_NONE;
        } else if (transmit) {
            ray.skip = enters ? BG_CPU_NONE : hit.object;
            ray.inside = enters ? hit.object : BG_CPU_NONE;
        } else {
            ray.skip = stays_inside ? BG_CPU_NONE : hit.object;
            ray.inside = stays_inside ? hit.object : BG_CPU_NONE;
        }
        ray.skip_triangle = hit.triangle;
        bgi_cpu_leave_origin(&hit, next, ray.o);
        bg_v3_set(ray.d, next[0], next[1], next[2]);
        bg_v3_set(ray.beta, beta[0], beta[1], beta[2]);
    }
}
