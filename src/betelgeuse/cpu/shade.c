/* Whitted tracing of one ray: nearest hit, lights with shadows, ambient and emission, mirror and
 * dielectric secondary rays (docs/shading.md sections 7-9). */
#include <float.h>

#include "../common/shapes.h"
#include "cpu_internal.h"

#define PI 3.14159265358979323846264338327950288

/* The nearest-hit search of one ray: objects are offered by the tree walk (in tree order) and by
 * the always-tested list; of two equal distances the lower object index wins, as it would in a
 * loop over the objects in order, so the tree changes no pixel. */
typedef struct nearest_search {
    const bg_scene_state *state;
    const double *o, *d;
    uint32_t skip, skip_triangle, inside;
    bg_cpu_candidate best;
    uint32_t best_index;
} nearest_search;

static void offer(nearest_search *n, uint32_t j, double t_max)
{
    bg_cpu_candidate c;
    /* A ray leaving a mesh triangle skips that triangle only: a mesh is not convex. */
    bool skip_all = j == n->skip && n->skip_triangle == BG_CPU_NONE;
    uint32_t skip_triangle = j == n->skip ? n->skip_triangle : BG_CPU_NONE;
    if (skip_all)
        return;
    const bg_object_data *obj = &n->state->objects[j];
    bg_cpu_mesh_filter storage;
    const bg_cpu_mesh_filter *filter = obj->mesh ? bgi_cpu_mesh_filter_of(n->state, obj, &storage) : NULL;
    if (!bgi_cpu_intersect_object_except(obj, n->o, n->d, j == n->inside, skip_triangle, filter, t_max, &c))
        return;
    if (n->best_index == BG_CPU_NONE || c.t < n->best.t || (c.t == n->best.t && j < n->best_index)) {
        n->best = c;
        n->best_index = j;
    }
}

static bool offer_tree_leaf(void *user, uint32_t prim, double *t_max)
{
    nearest_search *n = user;
    offer(n, n->state->tree_objects[prim], *t_max);
    if (n->best_index != BG_CPU_NONE)
        *t_max = n->best.t;
    return true;
}

/* Calls visit for every tree primitive: the exact answer when a walk is refused (which a tree
 * built by commit never is; the walk's loop bound makes the refusal explicit, not silent). */
static void visit_every_leaf(const bg_scene_state *state, bg_bvh_visit_fn visit, void *user, double t_max)
{
    for (uint32_t i = 0; i < state->tree_count; i++)
        if (!visit(user, i, &t_max))
            return;
}

static void walk_tree(const bg_scene_state *state, const double o[3], const double d[3], double t_max,
                      bg_bvh_visit_fn visit, void *user)
{
    if (state->tree_count == 0)
        return;
    double t = t_max;
    if (bgi_bvh_traverse(state->tree, o, d, 0.0, &t, visit, user, NULL) != BG_OK)
        visit_every_leaf(state, visit, user, t_max);
}

bool bgi_cpu_nearest_hit(const bg_scene_state *state, const double o[3], const double d[3], uint32_t skip,
                        uint32_t inside, bg_cpu_hit *hit)
{
    return bgi_cpu_nearest_hit_except(state, o, d, skip, BG_CPU_NONE, inside, hit);
}

bool bgi_cpu_nearest_hit_except(const bg_scene_state *state, const double o[3], const double d[3], uint32_t skip,
                               uint32_t skip_triangle, uint32_t inside, bg_cpu_hit *hit)
{
    nearest_search n = {state, o, d, skip, skip_triangle, inside,
                        {0.0, 0, {0, 0, 0}, {0, 0, 0}, BG_CPU_NONE, {0, 0, 0}}, BG_CPU_NONE};
    for (uint32_t k = 0; k < state->always_count; k++)
        offer(&n, state->always_objects[k], n.best_index == BG_CPU_NONE ? DBL_MAX : n.best.t);
    walk_tree(state, o, d, n.best_index == BG_CPU_NONE ? DBL_MAX : n.best.t, offer_tree_leaf, &n);
    if (n.best_index == BG_CPU_NONE)
        return false;
    bgi_cpu_hit_attributes(&state->objects[n.best_index], n.best_index, o, d, &n.best, hit);
    return true;
}

/* The any-hit search of one shadow segment. */
typedef struct shadow_search {
    const bg_scene_state *state;
    const double *p, *l;
    double t_max;
    uint32_t self, self_triangle;
    bool blocked;
} shadow_search;

/* An analytic shape never shadows its own lit side; a mesh may shadow itself, except by the
 * triangle the segment starts on. */
static bool blocks(const shadow_search *s, uint32_t j)
{
    const bg_object_data *obj = &s->state->objects[j];
    if (!obj->casts_shadows || (j == s->self && s->self_triangle == BG_CPU_NONE))
        return false;
    bg_cpu_mesh_filter storage;
    const bg_cpu_mesh_filter *filter = obj->mesh ? bgi_cpu_mesh_filter_of(s->state, obj, &storage) : NULL;
    return bgi_cpu_segment_blocked_except(obj, s->p, s->l, j == s->self ? s->self_triangle : BG_CPU_NONE, filter,
                                          s->t_max);
}

static bool test_tree_blocker(void *user, uint32_t prim, double *t_max)
{
    (void)t_max;
    shadow_search *s = user;
    s->blocked = blocks(s, s->state->tree_objects[prim]);
    return !s->blocked;
}

bool bgi_cpu_shadowed(const bg_scene_state *state, const double p[3], const double l[3], double t_max, uint32_t self,
                      uint32_t self_triangle)
{
    shadow_search s = {state, p, l, t_max, self, self_triangle, false};
    for (uint32_t k = 0; k < state->always_count; k++)
        if (blocks(&s, state->always_objects[k]))
            return true;
    walk_tree(state, p, l, t_max, test_tree_blocker, &s);
    return s.blocked;
}

bool bgi_cpu_light_arrival(const bg_light *light, const double p[3], double l[3], double *t_max, double radiance[3])
{
    double scale = light->intensity;
    if (light->type == BG_LIGHT_DIRECTIONAL) {
        bg_v3_set(l, -light->direction.x, -light->direction.y, -light->direction.z);
        if (!bg_v3_normalize(l))
            return false;
        *t_max = DBL_MAX;
    } else {
        const double lp[3] = {light->position.x, light->position.y, light->position.z};
        bg_v3_set(l, lp[0] - p[0], lp[1] - p[1], lp[2] - p[2]);
        double dist = sqrt(bg_v3_dot(l, l));
        if (!(dist > 0.0) || !bg_v3_normalize(l))
            return false;
        *t_max = dist;
        if (light->spot_cutoff_degrees < 180.0) {
            double axis[3] = {light->direction.x, light->direction.y, light->direction.z};
            if (!bg_v3_normalize(axis))
                return false;
            double cos_angle = -bg_v3_dot(l, axis);
            if (cos_angle < cos(light->spot_cutoff_degrees * (PI / 180.0)))
                return false;
            if (light->spot_exponent > 0.0)
                scale *= pow(cos_angle > 0.0 ? cos_angle : 0.0, light->spot_exponent);
        }
        double att = light->attenuation[0] + light->attenuation[1] * dist + light->attenuation[2] * dist * dist;
        if (!(att > 0.0))
            return false;
        scale /= att;
    }
    for (int i = 0; i < 3; i++)
        radiance[i] = light->color[i] * scale;
    return scale > 0.0;
}

bool bgi_cpu_worth_following(const double w[3], double min_weight)
{
    double m = w[0] > w[1] ? w[0] : w[1];
    m = m > w[2] ? m : w[2];
    return m > 0.0 && m >= min_weight;
}

void bgi_cpu_trace(const bg_scene_state *state, const bg_render_settings *settings, const bgi_sample_point *sample,
                   const double o[3], const double d[3], int level, const double weight[3], uint32_t skip,
                   uint32_t skip_triangle, uint32_t inside, double out[3])
{
    bg_cpu_hit hit;
    if (!bgi_cpu_nearest_hit_except(state, o, d, skip, skip_triangle, inside, &hit)) {
        double seen[3] = {settings->background[0], settings->background[1], settings->background[2]};
        if (state->environment.on)
            bgi_cpu_environment_radiance(state, d, seen);
        for (int i = 0; i < 3; i++)
            out[i] += weight[i] * seen[i];
        return;
    }
    const bg_object_data *object = &state->objects[hit.object];
    const bg_material *material = &state->materials[object->material];
    bg_cpu_surface surface;
    bgi_cpu_surface_eval(state, material, hit.uv, &surface);

    const double *n = hit.normal;
    const double view[3] = {-d[0], -d[1], -d[2]};
    double v = bg_v3_dot(n, view);
    double opaque = 1.0 - surface.transparency;
    /* An open mesh is thin as a plane is: lit on both sides, passing light straight on. */
    bool thin = bg_shape_thin(object->shape) ||
                (object->mesh && state->materials[object->material].sides == BG_SIDES_BOTH);

    for (int i = 0; i < 3; i++)
        out[i] += weight[i] * (surface.emission[i] + opaque * state->ambient[i] * surface.ambient[i]);

    /* Direct light reaches a closed object's surface only from outside. */
    if (opaque > 0.0 && v > 0.0 && (thin || hit.entering)) {
        /* The lights in order, then the environment as a distant light (7.1). */
        uint32_t lights = state->light_count + (state->environment.on && state->environment.lights ? 1 : 0);
        for (uint32_t k = 0; k < lights; k++) {
            double l[3], radiance[3], t_max = DBL_MAX;
            if (k < state->light_count ? !bgi_cpu_light_sample(state, k, sample, hit.position, l, &t_max, radiance)
                                       : !bgi_cpu_environment_light(state, sample, l, radiance))
                continue;
            double vl = bg_v3_dot(n, l);
            if (!(vl > 0.0))
                continue; /* facing away from the light: none of it */
            double from[3];
            bgi_cpu_leave_origin(&hit, l, from);
            if (bgi_cpu_shadowed(state, from, l, t_max, hit.object, hit.triangle))
                continue;
            double f[3];
            bgi_cpu_brdf(&surface, n, hit.tangent, view, l, f);
            for (int i = 0; i < 3; i++)
                out[i] += weight[i] * opaque * PI * f[i] * radiance[i] * vl;
        }
    }

    if (level >= settings->max_depth)
        return;

    /* Interface: exact dielectric Fresnel for closed shapes; thin shapes pass light straight on. */
    double fresnel = 0.0, cos_t = 0.0, eta = 1.0;
    double cos_i = v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0;
    if (surface.transparency > 0.0 && !thin) {
        double n1 = hit.entering ? 1.0 : surface.ior, n2 = hit.entering ? surface.ior : 1.0;
        fresnel = bgi_cpu_fresnel(cos_i, n1, n2, &cos_t);
        eta = n1 / n2;
    }

    double mirror[3], w_refl[3], w_refr[3];
    bgi_cpu_mirror_weight(&surface, cos_i, mirror);
    for (int i = 0; i < 3; i++) {
        w_refl[i] = weight[i] * (opaque * mirror[i] + surface.transparency * fresnel);
        w_refr[i] = weight[i] * surface.transparency * (1.0 - fresnel);
    }

    /* A ray leaving a closed object's inside stays inside after reflection (far root); any other
     * secondary ray leaves the object it starts on and skips it. */
    bool stays_inside = !thin && !hit.entering && !object->mesh;
    /* A ray leaving a mesh skips the triangle it starts on and nothing else, from a point just off
     * the surface on its own side (docs/shading.md 2.10); it may meet the same mesh again. */
    uint32_t leave_skip = object->mesh ? hit.object : BG_CPU_NONE, leave_triangle = hit.triangle;
    if (bgi_cpu_worth_following(w_refl, settings->min_weight)) {
        double dn = bg_v3_dot(d, n);
        double r[3] = {d[0] - 2.0 * dn * n[0], d[1] - 2.0 * dn * n[1], d[2] - 2.0 * dn * n[2]};
        /* A glossy material's lobe, of the coat's roughness if it has one (docs/shading.md 9.1). */
        double lobe = surface.has_coat ? surface.coat.r : surface.base.r;
        bool leaves = true;
        if (material->glossy && lobe > 0.0) {
            double uv[2];
            bgi_sample_square(sample, BGI_DIMENSION_GLOSSY(level), uv);
            leaves = bgi_cpu_glossy_reflect(d, n, lobe, uv, r);
        }
        double from[3];
        bgi_cpu_leave_origin(&hit, r, from);
        if (leaves && bg_v3_normalize(r))
            bgi_cpu_trace(state, settings, sample, from, r, level + 1, w_refl,
                         object->mesh ? leave_skip : stays_inside ? BG_CPU_NONE : hit.object, leave_triangle,
                         stays_inside ? hit.object : BG_CPU_NONE, out);
    }
    if (bgi_cpu_worth_following(w_refr, settings->min_weight)) {
        double t[3] = {d[0], d[1], d[2]};
        if (!thin) {
            double k = eta * cos_i - cos_t;
            for (int i = 0; i < 3; i++)
                t[i] = eta * d[i] + k * n[i];
        }
        if (bg_v3_normalize(t)) {
            bool enters = !thin && hit.entering && !object->mesh;
            double from[3];
            bgi_cpu_leave_origin(&hit, t, from);
            bgi_cpu_trace(state, settings, sample, from, t, level + 1, w_refr,
                         object->mesh ? leave_skip : enters ? BG_CPU_NONE : hit.object, leave_triangle,
                         enters ? hit.object : BG_CPU_NONE, out);
        }
    }
}

void bgi_cpu_shade_ray(const bg_scene_state *state, const bg_render_settings *settings,
                       const bgi_sample_point *sample, const double o[3], const double d[3], double rgb[3])
{
    const double one[3] = {1.0, 1.0, 1.0};
    bgi_sample_point first;
    if (!sample) {
        bgi_sample_point_make(0, 0, 0, 1, &first);
        sample = &first;
    }
    if (settings->integrator == BG_INTEGRATOR_PATH) {
        bgi_cpu_path_ray(state, settings, sample, o, d, rgb);
        return;
    }
    bg_v3_set(rgb, 0.0, 0.0, 0.0);
    bgi_cpu_trace(state, settings, sample, o, d, 0, one, BG_CPU_NONE, BG_CPU_NONE, BG_CPU_NONE, rgb);
}

void bgi_cpu_primary_ray(const bg_camera_data *camera, int width, int height, int x, int y, double o[3],
                        double d[3])
{
    bgi_cpu_frame_ray(camera, width, height, x + 0.5, y + 0.5, o, d);
}

void bgi_cpu_frame_ray(const bg_camera_data *camera, int width, int height, double fx, double fy, double o[3],
                      double d[3])
{
    double aspect = (double)width / (double)height;
    double sx = (2.0 * fx / width - 1.0) * aspect * camera->half_y;
    double sy = (1.0 - 2.0 * fy / height) * camera->half_y;
    bg_v3_set(o, camera->camera.position.x, camera->camera.position.y, camera->camera.position.z);
    if (camera->orthographic) {
        /* docs/shading.md 1.5: parallel rays from the view's rectangle through position. */
        for (int i = 0; i < 3; i++) {
            o[i] += sx * camera->right[i] + sy * camera->up[i];
            d[i] = camera->forward[i];
        }
        return;
    }
    for (int i = 0; i < 3; i++)
        d[i] = camera->forward[i] + sx * camera->right[i] + sy * camera->up[i];
    bg_v3_normalize(d);
}
