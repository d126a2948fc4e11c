/* The distribution benchmark's scenes: see distribution_scenes.h. Placed like examples/scenes'
 * mirror and glass scenes (a floor at y = -1, the camera about 6 units away, 45 degrees), with the
 * same kind of materials, so that their frames cost what those scenes' do but for the effect. */
#include <math.h>

#include "distribution_scenes.h"

#include "scenes/scenes.h"

/* A scene under construction whose first failure sticks: every call after it does nothing, so a
 * builder reads as the list of what the scene holds, with one status to return at the end. */
typedef struct builder {
    bg_scene *scene;
    bg_status status;
    bool effect; /* false: the scene's plain twin (distribution_scenes.h) */
} builder;

static bg_material diffuse(double r, double g, double b)
{
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){r, g, b, 0};
    return m;
}

/* A metal: its colour as reflectance, no ambient (as the examples' chrome). Roughness 0 is a mirror;
 * below 1/2 the specular share 1 - 4 r (1 - r) is traced (docs/shading.md 6.3), through the lobe of r
 * where glossy is set. */
static bg_material metal(double r, double g, double b, double roughness, bool glossy)
{
    bg_material m = diffuse(r, g, b);
    m.base.roughness.value = roughness;
    m.ambient = (bg_color_param){0, 0, 0, 0};
    m.glossy = glossy;
    return m;
}

static uint32_t material(builder *b, bg_material m)
{
    uint32_t id = 0;
    m.glossy = m.glossy && b->effect;
    if (b->status == BG_OK)
        b->status = bg_scene_add_material(b->scene, &m, &id);
    return id;
}

/* A diffuse material of a checker texture (examples/scenes: 64x64 texels, 8x8 per cell). */
static uint32_t checker(builder *b, const unsigned char light[3], const unsigned char dark[3])
{
    uint32_t texture = 0;
    if (b->status == BG_OK)
        b->status = scenes_add_checker_texture(b->scene, light, dark, &texture);
    bg_material m = diffuse(1, 1, 1);
    m.base.reflectance.texture = texture;
    return material(b, m);
}

static void object(builder *b, bg_shape shape, bg_mat4 transform, uint32_t material_id, double uv_scale)
{
    bg_object_desc d = bg_object_desc_init(shape, material_id);
    d.transform = transform;
    d.uv_scale[0] = d.uv_scale[1] = uv_scale;
    uint32_t id;
    if (b->status == BG_OK)
        b->status = bg_scene_add_object(b->scene, &d, &id);
}

static void sphere(builder *b, double x, double y, double z, double r, uint32_t material_id)
{
    uint32_t id;
    if (b->status == BG_OK)
        b->status = bg_scene_add_sphere(b->scene, bg_vec3_make(x, y, z), r, material_id, &id);
}

/* The floor y = -1 (planar UV: an eighth of a checker texture, one cell, per unit, as in glass). */
static void floor_plane(builder *b, uint32_t material_id)
{
    object(b, BG_SHAPE_PLANE, bg_mat4_translate(0, -1, 0), material_id, 0.25);
}

/* The plain twin's lights are point lights: a sphere light at its centre, a rectangle light at its
 * middle (the rectangle's cosine falloff goes with its shape). */
static void light(builder *b, bg_light l)
{
    if (!b->effect && l.type == BG_LIGHT_RECTANGLE)
        l.position = bg_vec3_make(l.position.x + 0.5 * (l.edge_u.x + l.edge_v.x), l.position.y + 0.5 * (l.edge_u.y + l.edge_v.y),
                                  l.position.z + 0.5 * (l.edge_u.z + l.edge_v.z));
    if (!b->effect && (l.type == BG_LIGHT_SPHERE || l.type == BG_LIGHT_RECTANGLE))
        l.type = BG_LIGHT_POINT;
    uint32_t id;
    if (b->status == BG_OK)
        b->status = bg_scene_add_light(b->scene, &l, &id);
}

static void point_light(builder *b, double x, double y, double z, double intensity)
{
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(x, y, z);
    l.intensity = intensity;
    light(b, l);
}

static void ambient(builder *b, double v)
{
    double rgb[3] = {v, v, v};
    if (b->status == BG_OK)
        b->status = bg_scene_set_ambient(b->scene, rgb);
}

static void camera(builder *b, bg_camera c)
{
    if (!b->effect)
        c.aperture_radius = 0.0;
    if (b->status == BG_OK)
        b->status = bg_scene_set_camera(b->scene, &c);
}

static bg_camera camera_at(bg_vec3 position, bg_vec3 look_at)
{
    bg_camera c = bg_camera_init();
    c.position = position;
    c.look_at = look_at;
    return c;
}

bg_status distribution_area_lights(bg_scene *scene, bool effect)
{
    builder b = {scene, BG_OK, effect};
    floor_plane(&b, material(&b, diffuse(0.75, 0.75, 0.75)));
    sphere(&b, -1.4, 0, -0.6, 1, material(&b, diffuse(0.8, 0.15, 0.1)));
    sphere(&b, 2.2, -0.55, 1.2, 0.45, material(&b, diffuse(0.85, 0.75, 0.1)));
    /* A box turned 30 degrees, so its edges cast slanted penumbras, and a cylinder standing on the floor. */
    object(&b, BG_SHAPE_BOX,
           bg_mat4_mul(bg_mat4_translate(1.2, -0.4, -0.4),
                       bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 30), bg_mat4_scale(0.6, 0.6, 0.6))),
           material(&b, diffuse(0.15, 0.7, 0.2)), 1);
    object(&b, BG_SHAPE_CYLINDER, bg_mat4_mul(bg_mat4_translate(-0.2, -0.4, 1.5), bg_mat4_scale(0.35, 0.6, 0.35)),
           material(&b, diffuse(0.1, 0.25, 0.85)), 1);
    /* The key: a ball up and to the right, wide enough for penumbras a few tens of pixels across. */
    bg_light key = bg_light_init();
    key.type = BG_LIGHT_SPHERE;
    key.position = bg_vec3_make(3, 5, 3);
    key.radius = 0.8;
    key.intensity = 0.8;
    light(&b, key);
    /* The fill: a warm 1.5 x 1.5 panel up and to the left, facing down (edge_u x edge_v = -y). */
    bg_light panel = bg_light_init();
    panel.type = BG_LIGHT_RECTANGLE;
    panel.position = bg_vec3_make(-4, 4, -1);
    panel.edge_u = bg_vec3_make(1.5, 0, 0);
    panel.edge_v = bg_vec3_make(0, 0, 1.5);
    panel.color[1] = 0.9;
    panel.color[2] = 0.75;
    panel.intensity = 0.5;
    light(&b, panel);
    ambient(&b, 0.3);
    camera(&b, camera_at(bg_vec3_make(0, 1.8, 6.6), bg_vec3_make(0, -0.3, 0)));
    return b.status;
}

bg_status distribution_depth_of_field(bg_scene *scene, bool effect)
{
    static const unsigned char light_cell[3] = {230, 230, 230}, dark_cell[3] = {40, 40, 40};
    builder b = {scene, BG_OK, effect};
    floor_plane(&b, checker(&b, light_cell, dark_cell));
    uint32_t earth_texture = 0;
    if (b.status == BG_OK)
        b.status = scenes_add_earth_texture(scene, &earth_texture);
    bg_material earth = diffuse(1, 1, 1);
    earth.base.reflectance.texture = earth_texture;
    earth.ambient.texture = earth_texture;
    /* A diagonal row 2 units apart in depth; the earth in the middle is the plane in focus. */
    sphere(&b, -1.8, -0.4, 2, 0.6, material(&b, diffuse(0.8, 0.15, 0.1)));
    sphere(&b, -0.9, -0.4, 0, 0.6, material(&b, metal(0.85, 0.85, 0.85, 0, false)));
    sphere(&b, 0, -0.4, -2, 0.6, material(&b, earth));
    sphere(&b, 0.9, -0.4, -4, 0.6, material(&b, diffuse(0.15, 0.7, 0.2)));
    sphere(&b, 1.8, -0.4, -6, 0.6, material(&b, diffuse(0.1, 0.25, 0.85)));
    point_light(&b, 3, 6, 4, 0.9);
    point_light(&b, -4, 5, -2, 0.3);
    ambient(&b, 0.5);
    /* Focus 8.1 units ahead (focus_distance 0: the distance to look_at). A point at distance z blurs
     * over a disc of radius A |z - f| / (z f) at the image plane (docs/shading.md 1.4): about 19
     * pixels at 512x512 for the nearest sphere (z about 4), 7 for the farthest (about 12). */
    bg_camera lens = camera_at(bg_vec3_make(0, 0.6, 6), bg_vec3_make(0, -0.4, -2));
    lens.aperture_radius = 0.25;
    camera(&b, lens);
    return b.status;
}

bg_status distribution_glossy(bg_scene *scene, bool effect)
{
    static const unsigned char light_cell[3] = {230, 230, 230}, dark_cell[3] = {40, 40, 40};
    static const unsigned char orange[3] = {230, 140, 40}, teal[3] = {30, 110, 130};
    builder b = {scene, BG_OK, effect};
    floor_plane(&b, checker(&b, light_cell, dark_cell));
    /* A wall behind, facing the camera (the plane's prototype turned to face +z), for the spheres to
     * reflect a pattern rather than the black background. */
    object(&b, BG_SHAPE_PLANE,
           bg_mat4_mul(bg_mat4_translate(0, 0, -4), bg_mat4_rotate(bg_vec3_make(1, 0, 0), 90)),
           checker(&b, orange, teal), 0.5);
    sphere(&b, -1.4, 0, 0, 1, material(&b, metal(0.9, 0.9, 0.9, 0.1, true)));
    sphere(&b, 1.4, 0, -0.3, 1, material(&b, metal(0.95, 0.75, 0.35, 0.25, true)));
    /* Red varnish: a Lambertian base under a clear coat whose reflection is the glossy one. */
    bg_material varnish = diffuse(0.8, 0.1, 0.1);
    varnish.has_coat = true;
    varnish.coat.reflectance = (bg_color_param){0.08, 0.08, 0.08, 0};
    varnish.coat.roughness.value = 0.1;
    varnish.glossy = true;
    sphere(&b, 0, -0.5, 1.6, 0.5, material(&b, varnish));
    sphere(&b, -0.1, -0.6, -1.6, 0.4, material(&b, diffuse(0.1, 0.25, 0.85)));
    sphere(&b, 2.3, -0.6, 1.8, 0.4, material(&b, diffuse(0.15, 0.7, 0.2)));
    point_light(&b, 4, 6, 5, 0.8);
    point_light(&b, -5, 4, 2, 0.4);
    ambient(&b, 0.5);
    camera(&b, camera_at(bg_vec3_make(0, 1.4, 6.2), bg_vec3_make(0, -0.2, 0)));
    return b.status;
}

/* The sun's direction: 55 degrees from the zenith, 40 degrees round from -z. */
#define SUN_THETA_DEGREES 55.0
#define SUN_PHI_DEGREES 40.0

/* A 128 x 64 equirectangular sky (linear floats): a blue gradient over a dark ground and a sun of
 * radiance 400 and 3 degrees' radius, 35 degrees up: most of the light in one small spot, the case
 * importance sampling is for. Rows top first, as a caller's image has them. */
static uint32_t sky(builder *b)
{
    enum { W = 128, H = 64 };
    static float texels[W * H * 4];
    const double pi = 3.14159265358979323846, sun_theta = SUN_THETA_DEGREES * pi / 180.0,
                 sun_phi = SUN_PHI_DEGREES * pi / 180.0;
    double s[3] = {sin(sun_theta) * sin(sun_phi), cos(sun_theta), -sin(sun_theta) * cos(sun_phi)};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double theta = pi * (y + 0.5) / H, phi = 2.0 * pi * ((x + 0.5) / W - 0.5), up = cos(theta);
            double d[3] = {sin(theta) * sin(phi), up, -sin(theta) * cos(phi)};
            float *t = texels + ((size_t)y * W + x) * 4;
            bool sun = d[0] * s[0] + d[1] * s[1] + d[2] * s[2] > cos(3.0 * pi / 180.0);
            t[0] = sun ? 400.0f : up > 0.0 ? (float)(0.25 + 0.35 * (1.0 - up)) : 0.12f;
            t[1] = sun ? 380.0f : up > 0.0 ? (float)(0.45 + 0.3 * (1.0 - up)) : 0.09f;
            t[2] = sun ? 340.0f : up > 0.0 ? 0.95f : 0.06f;
            t[3] = 1.0f;
        }
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, texels};
    uint32_t id = 0;
    if (b->status == BG_OK)
        b->status = bg_scene_add_texture(b->scene, &img, NULL, &id);
    return id;
}

static bg_status environment_scene(bg_scene *scene, bg_environment_sampling sampling, bool effect)
{
    builder b = {scene, BG_OK, effect};
    floor_plane(&b, material(&b, diffuse(0.6, 0.6, 0.55)));
    sphere(&b, -1.4, 0, 0, 1, material(&b, diffuse(0.75, 0.3, 0.2)));
    sphere(&b, 1.4, 0, -0.3, 1, material(&b, metal(0.9, 0.75, 0.5, 0.12, true)));
    sphere(&b, 0.2, -0.5, 1.6, 0.5, material(&b, diffuse(0.2, 0.5, 0.8)));
    if (effect) {
        bg_environment e = bg_environment_init();
        e.texture = sky(&b);
        e.lights = true;
        e.sampling = sampling;
        if (b.status == BG_OK)
            b.status = bg_scene_set_environment(scene, &e);
        ambient(&b, 0.0);
    } else {
        /* The sun as a directional light and an ambient term for the sky (misses see the settings'
         * background, a constant). */
        const double pi = 3.14159265358979323846, sun_theta = SUN_THETA_DEGREES * pi / 180.0,
                     sun_phi = SUN_PHI_DEGREES * pi / 180.0;
        bg_light sun = bg_light_init();
        sun.type = BG_LIGHT_DIRECTIONAL;
        sun.direction = bg_vec3_make(-sin(sun_theta) * sin(sun_phi), -cos(sun_theta), sin(sun_theta) * cos(sun_phi));
        light(&b, sun);
        ambient(&b, 0.3);
    }
    camera(&b, camera_at(bg_vec3_make(0, 1.4, 6.2), bg_vec3_make(0, -0.2, 0)));
    return b.status;
}

bg_status distribution_environment_importance(bg_scene *scene, bool effect)
{
    return environment_scene(scene, BG_ENVIRONMENT_IMPORTANCE, effect);
}

bg_status distribution_environment_uniform(bg_scene *scene, bool effect)
{
    return environment_scene(scene, BG_ENVIRONMENT_UNIFORM, effect);
}
