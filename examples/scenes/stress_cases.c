/* The float32 stress cases: the table and the small scenes of their own (stress_cases.h). */
#include "stress_cases.h"
#include "meshes.h"
#include "scene_try.h"

#include <string.h>

/* ---- small scene helpers ---- */

static bg_status mat(bg_scene *s, double r, double g, double b, double roughness, double transparency, double ior,
                     uint32_t *out)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    m.base.roughness.value = roughness;
    m.transparency.value = transparency;
    m.ior = ior;
    if (roughness < 0.5)
        m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    return bg_scene_add_material(s, &m, out);
}

static bg_status ball(bg_scene *s, double x, double y, double z, double r, uint32_t m)
{
    uint32_t id;
    return bg_scene_add_sphere(s, bg_vec3_make(x, y, z), r, m, &id);
}

static bg_status floor_y(bg_scene *s, double y, uint32_t m)
{
    uint32_t id;
    return bg_scene_add_plane(s, bg_vec3_make(0, y, 0), bg_vec3_make(0, 1, 0), m, &id);
}

static bg_status shape(bg_scene *s, bg_shape sh, bg_mat4 t, uint32_t m)
{
    bg_object_desc d = bg_object_desc_init(sh, m);
    d.transform = t;
    uint32_t id;
    return bg_scene_add_object(s, &d, &id);
}

/* A point light; attenuation (kc, kl, kq). */
static bg_status lamp(bg_scene *s, double x, double y, double z, double intensity, double kc, double kl, double kq)
{
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(x, y, z);
    l.intensity = intensity;
    l.attenuation[0] = kc;
    l.attenuation[1] = kl;
    l.attenuation[2] = kq;
    uint32_t id;
    return bg_scene_add_light(s, &l, &id);
}

static bg_status view(bg_scene *s, bg_vec3 from, bg_vec3 at, bg_vec3 up, double fov)
{
    bg_camera c = bg_camera_init();
    c.position = from;
    c.look_at = at;
    c.up = up;
    c.fov_y_degrees = fov;
    return bg_scene_set_camera(s, &c);
}

static const bg_vec3 Y = {0, 1, 0};

/* Two lights and an ambient term: the usual lighting of the small scenes. */
static bg_status two_lamps(bg_scene *s)
{
    TRY(lamp(s, 3, 5, 4, 0.9, 1, 0, 0));
    TRY(lamp(s, -4, 3, 2, 0.35, 1, 0, 0));
    const double amb[3] = {0.3, 0.3, 0.3};
    return bg_scene_set_ambient(s, amb);
}

/* ---- the scenes ---- */

/* The camera a millimetre above an endless floor, looking along it: floor hits at ever more grazing
 * angles up to the horizon (the plane's 2^-20 grazing cut on the GPU, 2^-40 on the CPU). */
static bg_status grazing_camera(bg_scene *s)
{
    uint32_t f, red;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &red));
    TRY(floor_y(s, 0, f));
    TRY(ball(s, 0, 1, -10, 1, red));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 1e-3, 0), bg_vec3_make(0, 1e-3, -1), Y, 45);
}

/* A light a hundredth above the floor far to the side: the floor is lit at a cosine of about 1e-3
 * and the sphere's shadow stretches across the whole floor. */
static bg_status grazing_light(bg_scene *s)
{
    uint32_t f, red;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 0.6, 0, 1.5, &red));
    TRY(floor_y(s, 0, f));
    TRY(ball(s, 0, 1, 0, 1, red));
    TRY(lamp(s, 20, 0.01, 0, 400, 1, 0, 0));
    const double amb[3] = {0.2, 0.2, 0.2};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 3, 6), bg_vec3_make(0, 0.5, 0), Y, 45);
}

/* Two spheres touching at one point, both resting on the floor: shadow segments from near the
 * contact points pass within float resolution of the other object. */
static bg_status touching(bg_scene *s)
{
    uint32_t f, a, b;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 0.7, 0, 1.5, &a));
    TRY(mat(s, 0.2, 0.4, 0.85, 1, 0, 1.5, &b));
    TRY(floor_y(s, -1, f));
    TRY(ball(s, -1, 0, 0, 1, a));
    TRY(ball(s, 1, 0, 0, 1, b));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 1.5, 6), bg_vec3_make(0, -0.2, 0), Y, 45);
}

/* Three spheres cutting into each other: the intersection curves are where two depths tie. */
static bg_status intersecting(bg_scene *s)
{
    uint32_t f, a, b, c;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &a));
    TRY(mat(s, 0.2, 0.7, 0.25, 0.6, 0, 1.5, &b));
    TRY(mat(s, 0.2, 0.35, 0.85, 1, 0, 1.5, &c));
    TRY(floor_y(s, -1, f));
    TRY(ball(s, -0.6, 0, 0, 1, a));
    TRY(ball(s, 0.6, 0, 0, 1, b));
    TRY(ball(s, 0, 0.8, 0.4, 0.6, c));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 1.5, 6), bg_vec3_make(0, 0, 0), Y, 45);
}

/* An opaque sphere inside a glass one, and a sphere hidden inside an opaque one: refracted rays
 * start inside an object and must find the inner one before the far root. */
static bg_status nested(bg_scene *s)
{
    uint32_t f, g, red, white, blue;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.04, 0.04, 0.04, 0, 1, 1.5, &g));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &red));
    TRY(mat(s, 0.85, 0.85, 0.85, 1, 0, 1.5, &white));
    TRY(mat(s, 0.2, 0.35, 0.85, 1, 0, 1.5, &blue));
    TRY(floor_y(s, -1, f));
    TRY(ball(s, -1.1, 0, 0, 1, g));
    TRY(ball(s, -1.1, 0, 0, 0.45, red));
    TRY(ball(s, 1.1, 0, 0, 1, white));
    TRY(ball(s, 1.1, 0, 0, 0.5, blue));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 1.2, 6), bg_vec3_make(0, 0, 0), Y, 45);
}

/* A glass sphere (ior 1.5) holding a smaller one of water (1.33) holding a diffuse core: rays
 * change media three times each way, eight bounce levels. */
static bg_status glass_in_glass(bg_scene *s)
{
    uint32_t f, g1, g2, core;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.04, 0.04, 0.04, 0, 1, 1.5, &g1));
    TRY(mat(s, 0.02, 0.02, 0.02, 0, 1, 1.33, &g2));
    TRY(mat(s, 0.85, 0.75, 0.1, 1, 0, 1.5, &core));
    TRY(floor_y(s, -1.2, f));
    TRY(ball(s, 0, 0, 0, 1.2, g1));
    TRY(ball(s, 0.2, 0.1, 0.1, 0.7, g2));
    TRY(ball(s, 0.3, 0.1, 0.2, 0.25, core));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 1, 5), bg_vec3_make(0, 0, 0), Y, 45);
}

/* Boxes 1e-4 as thick as they are wide: a lit slab with a sphere's shadow on it, and one standing
 * almost edge-on to the camera. Both faces of a slab lie within a few float steps of each other. */
static bg_status thin_boxes(bg_scene *s)
{
    uint32_t slab, wall, red;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &slab));
    TRY(mat(s, 0.2, 0.7, 0.25, 0.6, 0, 1.5, &wall));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &red));
    TRY(shape(s, BG_SHAPE_BOX,
              bg_mat4_mul(bg_mat4_rotate(Y, 20), bg_mat4_scale(2.5, 2.5e-4, 2.5)), slab));
    TRY(shape(s, BG_SHAPE_BOX,
              bg_mat4_mul(bg_mat4_translate(1.8, 0.8, -1),
                          bg_mat4_mul(bg_mat4_rotate(Y, 80), bg_mat4_scale(1e-4, 0.8, 1))), wall));
    TRY(ball(s, -0.3, 0.8, 0.2, 0.5, red));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 2.5, 5), bg_vec3_make(0, 0, 0), Y, 45);
}

/* Spheres at 10, 20 and 40 units from the camera over a floor; the cases set dmax just past the
 * farthest sphere or well in front of it. */
static bg_status depth_row(bg_scene *s)
{
    uint32_t f, a, b, c;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &a));
    TRY(mat(s, 0.2, 0.7, 0.25, 0.6, 0, 1.5, &b));
    TRY(mat(s, 0.2, 0.35, 0.85, 1, 0, 1.5, &c));
    TRY(floor_y(s, -4, f));
    TRY(ball(s, -1.5, 0, -10, 1, a));
    TRY(ball(s, 2, 0, -20, 2, b));
    TRY(ball(s, -4, 0, -40, 4, c));
    TRY(lamp(s, 10, 20, 0, 1, 1, 0, 0));
    TRY(lamp(s, -10, 5, -5, 0.4, 1, 0, 0));
    const double amb[3] = {0.3, 0.3, 0.3};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 0, 0), bg_vec3_make(-0.05, -0.02, -1), Y, 45);
}

/* A sphere on a floor lit by one light of the given intensity and attenuation. */
static bg_status lit_by(bg_scene *s, double intensity, double kc, double kl, double kq)
{
    uint32_t f, red;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 0.6, 0, 1.5, &red));
    TRY(floor_y(s, -1, f));
    TRY(ball(s, 0, 0, 0, 1, red));
    TRY(lamp(s, 3, 4, 2, intensity, kc, kl, kq));
    const double amb[3] = {0.2, 0.2, 0.2};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 1.5, 5), bg_vec3_make(0, -0.2, 0), Y, 45);
}

/* Each pair below balances to about the radiance of a plain light of intensity 1 at distance 5,
 * so the image is an ordinary one computed from extreme factors. */
static bg_status light_huge(bg_scene *s) { return lit_by(s, 3e30, 0, 0, 1e29); }
static bg_status light_tiny(bg_scene *s) { return lit_by(s, 1e-30, 1e-30, 0, 0); }
static bg_status attenuation_tiny(bg_scene *s) { return lit_by(s, 3e-30, 0, 0, 1e-31); }
static bg_status attenuation_huge_linear(bg_scene *s) { return lit_by(s, 5e30, 0, 1e30, 0); }
/* Not balanced: a light 1e30 times too bright saturates every lit pixel; only finiteness matters. */
static bg_status light_saturating(bg_scene *s) { return lit_by(s, 1e30, 1, 0, 0); }

/* Two facing mirrors with spheres between: sixteen bounce levels of a corridor of reflections. */
static bg_status mirror_corridor(bg_scene *s)
{
    uint32_t m, f, red, blue;
    TRY(mat(s, 0.9, 0.9, 0.9, 0, 0, 1.5, &m));
    TRY(mat(s, 0.7, 0.7, 0.7, 1, 0, 1.5, &f));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &red));
    TRY(mat(s, 0.2, 0.35, 0.85, 0.6, 0, 1.5, &blue));
    TRY(floor_y(s, -1, f));
    bg_vec3 z = {0, 0, 1};
    TRY(shape(s, BG_SHAPE_RECTANGLE,
              bg_mat4_mul(bg_mat4_translate(-2, 0.5, 0), bg_mat4_mul(bg_mat4_rotate(z, -90), bg_mat4_scale(1.5, 1, 4))),
              m));
    TRY(shape(s, BG_SHAPE_RECTANGLE,
              bg_mat4_mul(bg_mat4_translate(2, 0.5, 0), bg_mat4_mul(bg_mat4_rotate(z, 90), bg_mat4_scale(1.5, 1, 4))),
              m));
    TRY(ball(s, -0.6, -0.4, 0, 0.6, red));
    TRY(ball(s, 0.7, -0.5, -1.2, 0.5, blue));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0.4, 0.8, 5), bg_vec3_make(-0.6, 0, 0), Y, 40);
}

/* The camera inside a large diffuse sphere (a room lit from inside) looking at a sphere. */
static bg_status inside_sphere(bg_scene *s)
{
    uint32_t room, red;
    TRY(mat(s, 0.7, 0.7, 0.7, 1, 0, 1.5, &room));
    TRY(mat(s, 0.8, 0.2, 0.15, 0.6, 0, 1.5, &red));
    TRY(ball(s, 0, 0, 0, 10, room));
    TRY(ball(s, 0, 0, 0, 1, red));
    TRY(lamp(s, 3, 4, 3, 1, 1, 0, 0));
    const double amb[3] = {0.3, 0.3, 0.3};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 1, 5), bg_vec3_make(0, 0, 0), Y, 60);
}

/* The camera inside a closed box room, and inside a glass sphere within it. */
static bg_status inside_box_glass(bg_scene *s)
{
    uint32_t room, g, red, blue;
    TRY(mat(s, 0.7, 0.7, 0.7, 1, 0, 1.5, &room));
    TRY(mat(s, 0.04, 0.04, 0.04, 0, 1, 1.5, &g));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &red));
    TRY(mat(s, 0.2, 0.35, 0.85, 1, 0, 1.5, &blue));
    TRY(shape(s, BG_SHAPE_BOX, bg_mat4_scale(6, 4, 8), room));
    TRY(ball(s, 0, 0, 4, 1.5, g));
    TRY(ball(s, -1, -1, -2, 1, red));
    TRY(ball(s, 1.5, 0, -3, 1, blue));
    TRY(lamp(s, 2, 3, 2, 1, 1, 0, 0));
    const double amb[3] = {0.3, 0.3, 0.3};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 0.2, 4.3), bg_vec3_make(0, -0.3, 0), Y, 60);
}

/* A sphere of radius 1e-6 resting on a unit sphere, seen from 5e-6 away, so that it fills the view
 * in front of the big one: a 1e6 ratio of sizes in one scene, with the automatic dmax set by the
 * big sphere. */
static bg_status tiny_sphere(bg_scene *s)
{
    uint32_t white, red;
    TRY(mat(s, 0.85, 0.85, 0.85, 1, 0, 1.5, &white));
    TRY(mat(s, 0.8, 0.2, 0.15, 0.6, 0, 1.5, &red));
    TRY(ball(s, 0, 0, 0, 1, white));
    TRY(ball(s, 0, 1 + 1e-6, 0, 1e-6, red));
    TRY(lamp(s, 3, 5, 4, 1, 1, 0, 0));
    const double amb[3] = {0.3, 0.3, 0.3};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 1 + 2e-6, 5e-6), bg_vec3_make(0, 1 + 0.5e-6, 0), Y, 45);
}

/* Lights exactly on surfaces: one on top of a sphere, one on the floor. */
static bg_status light_on_surface(bg_scene *s)
{
    uint32_t f, white;
    TRY(mat(s, 0.8, 0.8, 0.8, 1, 0, 1.5, &f));
    TRY(mat(s, 0.85, 0.85, 0.85, 0.6, 0, 1.5, &white));
    TRY(floor_y(s, -1, f));
    TRY(ball(s, 0, 0, 0, 1, white));
    TRY(lamp(s, 0, 1, 0, 1, 1, 0, 0));
    TRY(lamp(s, 2, -1, 0.5, 1, 1, 0, 0.5));
    const double amb[3] = {0.3, 0.3, 0.3};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 2, 5), bg_vec3_make(0, 0, 0), Y, 45);
}

/* The earth texture seen from straight above its north pole: the spherical UV's latitude is most
 * ill-conditioned there. */
static bg_status pole_uv(bg_scene *s)
{
    uint32_t tex, m;
    TRY(scenes_add_earth_texture(s, &tex));
    bg_material e = bg_material_init();
    e.base.reflectance.r = e.base.reflectance.g = e.base.reflectance.b = 1;
    e.base.reflectance.texture = tex;
    e.ambient.texture = tex;
    TRY(bg_scene_add_material(s, &e, &m));
    TRY(ball(s, 0, 0, 0, 1, m));
    TRY(lamp(s, 1, 5, 2, 1, 1, 0, 0));
    const double amb[3] = {0.5, 0.5, 0.5};
    TRY(bg_scene_set_ambient(s, amb));
    return view(s, bg_vec3_make(0, 2.2, 0), bg_vec3_make(0, 0, 0), bg_vec3_make(0, 0, -1), 45);
}

/* A mirror floor seen towards the horizon: reflected rays start far out on the plane, where the
 * hit position carries few bits and depth steps are coarse. */
static bg_status mirror_floor_horizon(bg_scene *s)
{
    uint32_t m, red, green, blue;
    TRY(mat(s, 0.8, 0.8, 0.8, 0, 0, 1.5, &m));
    TRY(mat(s, 0.8, 0.2, 0.15, 1, 0, 1.5, &red));
    TRY(mat(s, 0.2, 0.7, 0.25, 1, 0, 1.5, &green));
    TRY(mat(s, 0.2, 0.35, 0.85, 1, 0, 1.5, &blue));
    TRY(floor_y(s, 0, m));
    TRY(ball(s, 0, 1, -5, 1, red));
    TRY(ball(s, 3, 1.5, -20, 1.5, green));
    TRY(ball(s, -8, 3, -60, 3, blue));
    TRY(two_lamps(s));
    return view(s, bg_vec3_make(0, 0.5, 3), bg_vec3_make(0, 0.3, -10), Y, 45);
}

/* The heightfield terrain (meshes.h, 8192 smooth triangles) at a scale, with its camera and a low
 * light scaled alike: every lit point sends its shadow segment across neighbouring triangles a few
 * ulps away, which shadow it (acne) unless a ray leaving a triangle starts off it by an amount that
 * scales with the point (docs/shading.md 2.10). The light has no attenuation, so the image is the
 * same at every scale. */
static bg_status terrain_at(bg_scene *s, double scale)
{
    mesh m;
    memset(&m, 0, sizeof m);
    mesh_heightfield_desc d = {64, 0.25, true, false};
    TRY(mesh_heightfield(&d, &m, NULL, 0));
    uint32_t ground = 0, id = 0;
    bg_status st = mat(s, 0.7, 0.65, 0.5, 1, 0, 1.5, &ground);
    bg_mesh_desc md = bg_mesh_desc_init(ground);
    md.positions = m.positions;
    md.vertex_count = m.vertex_count;
    md.indices = m.indices;
    md.triangle_count = m.triangle_count;
    md.normals = m.normals;
    md.transform = bg_mat4_scale(scale, scale, scale);
    if (st == BG_OK)
        st = bg_scene_add_mesh(s, &md, &id);
    mesh_free(&m);
    TRY(st);
    TRY(lamp(s, 2.0 * scale, 1.4 * scale, 1.0 * scale, 1.0, 1, 0, 0));
    const double amb[3] = {0.1, 0.1, 0.1};
    TRY(bg_scene_set_ambient(s, amb));
    /* Seen from above, the image all terrain: its outer edge, where float and double may split a
     * pixel between hit and miss, stays out of view. */
    return view(s, bg_vec3_make(0, 1.5 * scale, 0.9 * scale), bg_vec3_make(0, 0, 0.1 * scale), Y, 40);
}

static bg_status terrain_1em3(bg_scene *s) { return terrain_at(s, 1e-3); }
static bg_status terrain_1(bg_scene *s) { return terrain_at(s, 1.0); }
static bg_status terrain_1e4(bg_scene *s) { return terrain_at(s, 1e4); }

/* ---- the table ---- */

/* The offset directions (unit vectors): a diagonal, a mostly downward one, and straight along the
 * view axis of most scenes. */
static const double directions[3][3] = {{0.6, 0.48, -0.64}, {-0.36, -0.8, 0.48}, {0.0, 0.0, -1.0}};

#define SCALED(scene, label, s, cls, q) \
    {#scene " scale " label, "scale: float range and scale-relative rules", cls, q, scene, s, 0, 0, NULL, 0, 0, 0, false}
#define MOVED(scene, label, k, dir, cls, q)                                                                    \
    {#scene " offset " label, "offset: |p| large against the scene's size (ulp of |p|)", cls, q, scene, 1, k, \
     dir - 1, NULL, 0, 0, 0, false}
#define OWN(name, what, fn, cls, q, depth, minw, dmax) \
    {name, what, cls, q, SCENE_COUNT, 1, 0, 0, fn, depth, minw, dmax, false}
#define OWN_MESH(name, what, fn, cls, q) {name, what, cls, q, SCENE_COUNT, 1, 0, 0, fn, 0, 0, 0, true}

static const stress_case table[] = {
    /* scale of the paper scenes: must hold from 1e-3 to 1e4 */
    SCALED(SCENE_PAPER_EARTH, "1e-4", 1e-4, STRESS_SWEEP, true),
    SCALED(SCENE_PAPER_EARTH, "1e-3", 1e-3, STRESS_MUST_HOLD, true),
    SCALED(SCENE_PAPER_EARTH, "1e-2", 1e-2, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH, "1e-1", 1e-1, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH, "1e1", 1e1, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH, "1e2", 1e2, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH, "1e3", 1e3, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH, "1e4", 1e4, STRESS_MUST_HOLD, true),
    SCALED(SCENE_PAPER_EARTH, "1e5", 1e5, STRESS_SWEEP, false),
    SCALED(SCENE_PAPER_EARTH, "1e6", 1e6, STRESS_SWEEP, true),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e-4", 1e-4, STRESS_SWEEP, true),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e-3", 1e-3, STRESS_MUST_HOLD, true),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e-2", 1e-2, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e-1", 1e-1, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e1", 1e1, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e2", 1e2, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e3", 1e3, STRESS_MUST_HOLD, false),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e4", 1e4, STRESS_MUST_HOLD, true),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e5", 1e5, STRESS_SWEEP, false),
    SCALED(SCENE_PAPER_EARTH_SHADOW, "1e6", 1e6, STRESS_SWEEP, true),
    /* offset of the paper scenes: must hold up to 1e4 in three directions */
    MOVED(SCENE_PAPER_EARTH, "1e2 d1", 1e2, 1, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH, "1e3 d1", 1e3, 1, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH, "1e4 d1", 1e4, 1, STRESS_MUST_HOLD, true),
    MOVED(SCENE_PAPER_EARTH, "1e4 d2", 1e4, 2, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH, "1e4 d3", 1e4, 3, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH, "1e5 d1", 1e5, 1, STRESS_SWEEP, false),
    MOVED(SCENE_PAPER_EARTH, "1e6 d1", 1e6, 1, STRESS_SWEEP, true),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e2 d1", 1e2, 1, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e3 d1", 1e3, 1, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e4 d1", 1e4, 1, STRESS_MUST_HOLD, true),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e4 d2", 1e4, 2, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e4 d3", 1e4, 3, STRESS_MUST_HOLD, false),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e5 d1", 1e5, 1, STRESS_SWEEP, false),
    MOVED(SCENE_PAPER_EARTH_SHADOW, "1e6 d1", 1e6, 1, STRESS_SWEEP, true),
    /* the other shared scenes at the ends of the range */
    SCALED(SCENE_MIRROR, "1e-4", 1e-4, STRESS_SWEEP, false),
    SCALED(SCENE_MIRROR, "1e6", 1e6, STRESS_SWEEP, false),
    MOVED(SCENE_MIRROR, "1e4 d1", 1e4, 1, STRESS_SWEEP, true),
    SCALED(SCENE_GLASS, "1e-4", 1e-4, STRESS_SWEEP, false),
    SCALED(SCENE_GLASS, "1e6", 1e6, STRESS_SWEEP, false),
    MOVED(SCENE_GLASS, "1e4 d1", 1e4, 1, STRESS_SWEEP, true),
    SCALED(SCENE_ALL_PRIMITIVES, "1e-4", 1e-4, STRESS_SWEEP, false),
    SCALED(SCENE_ALL_PRIMITIVES, "1e6", 1e6, STRESS_SWEEP, false),
    MOVED(SCENE_ALL_PRIMITIVES, "1e4 d2", 1e4, 2, STRESS_SWEEP, true),
    SCALED(SCENE_TEXTURED_ANISO, "1e-4", 1e-4, STRESS_SWEEP, false),
    MOVED(SCENE_TEXTURED_ANISO, "1e4 d3", 1e4, 3, STRESS_SWEEP, false),
    MOVED(SCENE_MANY_LIGHTS, "1e4 d1", 1e4, 1, STRESS_SWEEP, false),
    /* high bounce depth */
    {"mirror depth 16", "16 bounce levels (error compounds per level)", STRESS_SWEEP, true, SCENE_MIRROR, 1, 0, 0,
     NULL, 16, 1e-4, 0, false},
    {"glass depth 16", "16 bounce levels through glass", STRESS_SWEEP, false, SCENE_GLASS, 1, 0, 0, NULL, 16, 1e-4, 0,
     false},
    OWN("mirror corridor depth 16", "facing mirrors, 16 levels", mirror_corridor, STRESS_SWEEP, true, 16, 1e-4, 0),
    /* grazing angles */
    OWN("grazing camera", "floor hits up to the horizon (plane grazing cut)", grazing_camera, STRESS_SWEEP, true, 0, 0, 0),
    OWN("grazing light", "light at a cosine of 1e-3 over the floor", grazing_light, STRESS_SWEEP, true, 0, 0, 0),
    OWN("mirror floor horizon", "secondary rays from far out on a plane", mirror_floor_horizon, STRESS_SWEEP, true, 0,
        0, 0),
    /* touching, intersecting, nested */
    OWN("touching spheres", "contact points: shadow segments graze a neighbour", touching, STRESS_SWEEP, true, 0, 0, 0),
    OWN("intersecting spheres", "depth ties along intersection curves", intersecting, STRESS_SWEEP, true, 0, 0, 0),
    OWN("nested spheres", "objects inside glass and inside opaque spheres", nested, STRESS_SWEEP, true, 0, 0, 0),
    OWN("glass in glass", "three media inside each other", glass_in_glass, STRESS_SWEEP, true, 8, 0, 0),
    OWN("thin boxes", "boxes 1e-4 thick (slab faces a few ulps apart)", thin_boxes, STRESS_SWEEP, true, 0, 0, 0),
    /* dmax */
    OWN("objects near dmax", "dmax just past the farthest sphere", depth_row, STRESS_SWEEP, true, 0, 0, 44.5),
    OWN("objects beyond dmax", "every sphere beyond dmax (compressed depth)", depth_row, STRESS_SWEEP, true, 0, 0, 5),
    OWN("objects far beyond dmax", "dmax 1e-3: depth 1 - dmax / 2t", depth_row, STRESS_SWEEP, false, 0, 0, 1e-3),
    /* lights */
    OWN("light 3e30, kq 1e29", "huge intensity over huge attenuation", light_huge, STRESS_SWEEP, true, 0, 0, 0),
    OWN("light 1e-30, kc 1e-30", "tiny intensity over tiny attenuation", light_tiny, STRESS_SWEEP, true, 0, 0, 0),
    OWN("light 3e-30, kq 1e-31", "tiny quadratic attenuation", attenuation_tiny, STRESS_SWEEP, false, 0, 0, 0),
    OWN("light 5e30, kl 1e30", "huge linear attenuation", attenuation_huge_linear, STRESS_SWEEP, false, 0, 0, 0),
    OWN("light 1e30 saturating", "radiance near float's range", light_saturating, STRESS_SWEEP, true, 0, 0, 0),
    /* cameras inside objects */
    OWN("camera inside sphere", "primary rays start inside a closed object", inside_sphere, STRESS_SWEEP, true, 0, 0, 0),
    OWN("camera inside box and glass", "camera in a box room and inside a glass sphere", inside_box_glass, STRESS_SWEEP,
        true, 0, 0, 0),
    /* degenerate but legal input */
    OWN("sphere radius 1e-6", "a 1e-6 sphere on a unit sphere, seen from 5e-6", tiny_sphere, STRESS_SWEEP, true, 0, 0, 0),
    /* must hold since shadow segments are open at the light's end (docs/shading.md 2.8) */
    OWN("light on a surface", "point lights exactly on a sphere and on the floor", light_on_surface, STRESS_MUST_HOLD,
        true, 0, 0, 0),
    /* a mesh's self-shadowing at the ends of the scale range */
    OWN_MESH("terrain scale 1e-3", "mesh self-shadowing: the leaving offset at small scales", terrain_1em3,
             STRESS_MUST_HOLD, true),
    OWN_MESH("terrain scale 1", "mesh self-shadowing: triangles shadowing their neighbours", terrain_1, STRESS_MUST_HOLD,
             false),
    OWN_MESH("terrain scale 1e4", "mesh self-shadowing: the leaving offset at large scales", terrain_1e4,
             STRESS_MUST_HOLD, true),
    OWN("pole of spherical UV", "the earth seen from above its pole (asin)", pole_uv, STRESS_SWEEP, true, 0, 0, 0),
};

size_t stress_case_count(void)
{
    return sizeof table / sizeof table[0];
}

const stress_case *stress_case_at(size_t i)
{
    return i < stress_case_count() ? &table[i] : NULL;
}

bool stress_case_is_placed(const stress_case *c)
{
    return c && c->scene < SCENE_COUNT && c->build == NULL &&
           ((c->scale != 0.0 && c->scale != 1.0) || c->offset != 0.0);
}

static scene_params params_of(const stress_case *c)
{
    scene_params p;
    memset(&p, 0, sizeof p);
    p.scale = c->scale;
    const double *d = directions[c->direction >= 0 && c->direction < 3 ? c->direction : 0];
    p.offset = bg_vec3_make(c->offset * d[0], c->offset * d[1], c->offset * d[2]);
    return p;
}

bg_status stress_case_build(const stress_case *c, bg_scene *scene)
{
    if (!c || !scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (c->build) {
        bg_status st = c->build(scene);
        return st != BG_OK ? st : bg_scene_commit(scene);
    }
    scene_params p = params_of(c);
    return scenes_build_ex(c->scene, &p, scene);
}

bg_status stress_case_build_origin(const stress_case *c, bg_scene *scene)
{
    if (!stress_case_is_placed(c) || !scene)
        return BG_ERR_INVALID_ARGUMENT;
    return scenes_build(c->scene, scene);
}

bg_render_settings stress_case_settings(const stress_case *c)
{
    bg_render_settings s = bg_render_settings_init();
    if (c->max_depth > 0)
        s.max_depth = c->max_depth;
    if (c->min_weight > 0.0)
        s.min_weight = c->min_weight;
    s.dmax = c->dmax;
    return s;
}
