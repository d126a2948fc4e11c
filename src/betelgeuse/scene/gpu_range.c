/* The lengths the GPU renderer's float arithmetic resolves (docs/gpu_pipeline.md, "Float range"),
 * checked once per commit so that a GPU frame can refuse a scene beyond them by name, where it would
 * otherwise miss objects or diverge. The scene model and the CPU reference keep their double range.
 *
 * The GPU intersects each object in its own space, where a ray's direction is the world direction
 * divided by the object's scale, and forms squares of such vectors: a sphere of radius 1e19 makes
 * |d|^2 about 1e-38, the edge of float's normal range, and the sphere vanishes; at 1e-20 the squares
 * overflow or flush likewise. Measured (a lit sphere over a plane, camera at four radii, 64 x 48,
 * GPU against CPU): scales 1e-18 to 1e17 agree, 3e17 and 1e-20 do not. Lengths are taken relative
 * to the camera, as the GPU forms them (its camera-relative frame), so a scene far from the origin
 * is not refused. The bounds keep two decades of margin on each side. A lens much wider than its
 * focus distance sends rays from points so far from the scene that float cannot aim them: measured,
 * aperture radius 1e4 times the focus distance agrees, 1e7 times does not. */
#include <math.h>
#include <stdio.h>

#include "../common/affine.h"
#include "scene_private.h"

#define LENGTH_MIN 1e-15
#define LENGTH_MAX 1e15
#define APERTURE_PER_FOCUS 1e3
#define RANGE_TEXT "[1e-15, 1e15]"

/* Records the first offence only: a later one cannot replace what the caller will be told. */
static void note_once(char *note, size_t size, const char *where, const char *what, double value, const char *bound)
{
    if (note[0])
        return;
    snprintf(note, size, "%s: %s %g is %s, the lengths the GPU renderer resolves in float; the CPU renderer takes it",
             where, what, value, bound);
}

static void check_size(char *note, size_t size, const char *where, const char *what, double value)
{
    if (!(value >= LENGTH_MIN && value <= LENGTH_MAX))
        note_once(note, size, where, what, value, "outside " RANGE_TEXT);
}

static void check_distance(char *note, size_t size, const char *where, const char *what, double value)
{
    if (value > LENGTH_MAX)
        note_once(note, size, where, what, value, "beyond 1e15");
}

/* The largest distance along an axis from the camera to a point or box. */
static double reach(const double cam[3], const double lo[3], const double hi[3])
{
    double r = 0.0;
    for (int k = 0; k < 3; k++)
        r = fmax(r, fmax(fabs(lo[k] - cam[k]), fabs(hi[k] - cam[k])));
    return r;
}

static void check_object(char *note, size_t size, const char *where, const bg_object_data *o, const double cam[3])
{
    double sum = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            sum += o->to_world[i][j] * o->to_world[i][j];
    check_size(note, size, where, "overall scale", sqrt(sum / 3.0));
    if (o->bounded) {
        check_distance(note, size, where, "box's reach from the camera", reach(cam, o->bounds_min, o->bounds_max));
        return;
    }
    /* A plane: its distance from the camera, the camera's object-space height times the scale the
     * plane's normal direction has. */
    double h = o->to_object[1][3];
    for (int k = 0; k < 3; k++)
        h += o->to_object[1][k] * cam[k];
    double n = sqrt(o->to_object[1][0] * o->to_object[1][0] + o->to_object[1][1] * o->to_object[1][1] +
                    o->to_object[1][2] * o->to_object[1][2]);
    check_distance(note, size, where, "plane's distance from the camera", n > 0.0 ? fabs(h) / n : 0.0);
}

static void check_light(char *note, size_t size, const char *where, const bg_light *l, const double cam[3])
{
    if (l->type == BG_LIGHT_DIRECTIONAL)
        return;
    double p[3] = {l->position.x, l->position.y, l->position.z};
    check_distance(note, size, where, "position's distance from the camera", reach(cam, p, p));
    if (l->type == BG_LIGHT_SPHERE && l->radius > 0.0)
        check_size(note, size, where, "radius", l->radius);
    if (l->type == BG_LIGHT_RECTANGLE) {
        check_size(note, size, where, "edge_u length", bgi_vec3_length(l->edge_u));
        check_size(note, size, where, "edge_v length", bgi_vec3_length(l->edge_v));
    }
}

void bgi_gpu_range_note(const bg_scene *s, const bg_camera_data *camera, char *note, size_t size)
{
    note[0] = '\0';
    const bg_camera *c = &camera->camera;
    const double cam[3] = {c->position.x, c->position.y, c->position.z};
    if (camera->orthographic)
        check_size(note, size, "camera", "half_height", c->half_height);
    if (c->aperture_radius > 0.0) {
        check_size(note, size, "camera", "aperture_radius", c->aperture_radius);
        if (c->aperture_radius > APERTURE_PER_FOCUS * camera->focus && !note[0])
            snprintf(note, size,
                     "camera: aperture_radius %g is more than 1000 times the focus distance %g, wider than the "
                     "GPU renderer can aim rays in float; the CPU renderer takes it",
                     c->aperture_radius, camera->focus);
    }
    char where[64], text[BG_HANDLE_TEXT_SIZE];
    const bg_object_data *objects = s->p_objects.data;
    uint32_t k = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->objects) && !note[0]; slot++) {
        if (!bgi_pool_live(&s->objects, slot))
            continue;
        snprintf(where, sizeof where, "object %s", bgi_handle_text(bgi_pool_id(&s->objects, slot), text));
        check_object(note, size, where, &objects[k++], cam);
    }
    const bg_light *lights = s->p_lights.data;
    k = 0;
    for (uint32_t slot = 0; slot < bgi_pool_slot_count(&s->lights) && !note[0]; slot++) {
        if (!bgi_pool_live(&s->lights, slot))
            continue;
        snprintf(where, sizeof where, "light %s", bgi_handle_text(bgi_pool_id(&s->lights, slot), text));
        check_light(note, size, where, &lights[k++], cam);
    }
}
