/* The shared scenes. Each builder fills an empty scene; scenes_build_ex commits it. */
#include "scenes.h"
#include "scene_try.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* Where a scene is put in the world: p -> s p + offset (scene_params.scale, .offset). Every position
 * the builders write goes through it, so one scene exists at any size and place with the same ideal
 * image; the stress program (bench/stress.c) measures what float32 makes of that. */
typedef struct placement {
    double s;
    bg_vec3 offset;
} placement;

static bg_vec3 placed_point(const placement *at, bg_vec3 p)
{
    return bg_vec3_make(at->s * p.x + at->offset.x, at->s * p.y + at->offset.y, at->s * p.z + at->offset.z);
}

/* The similarity prefixed to an object transform: the prototype, and so every UV, stays the same.
 * For scale 1 and offset 0 both factors are exact identities in double, so the default scenes keep
 * their bits. */
static bg_mat4 placed(const placement *at, bg_mat4 transform)
{
    return bg_mat4_mul(bg_mat4_translate(at->offset.x, at->offset.y, at->offset.z),
                       bg_mat4_mul(bg_mat4_scale(at->s, at->s, at->s), transform));
}

/* A light moved with the scene. Attenuation 1 / (kc + kl d + kq d^2) sees distances s times longer,
 * so kl / s and kq / s^2 keep the arriving radiance, and with it the image, unchanged. Directions
 * (spot axis, sun) do not change under a similarity. */
static bg_light placed_light(const placement *at, bg_light l)
{
    l.position = placed_point(at, l.position);
    l.attenuation[1] /= at->s;
    l.attenuation[2] /= at->s * at->s;
    return l;
}

static const char *const names[SCENE_COUNT] = {
    "paper_earth", "paper_earth_shadow", "mirror", "glass",
    "many_spheres", "many_lights", "all_primitives", "textured_aniso",
};

const char *scenes_name(scene_id id)
{
    return (int)id >= 0 && id < SCENE_COUNT ? names[id] : NULL;
}

bool scenes_find(const char *name, scene_id *out_id)
{
    for (int i = 0; name && i < SCENE_COUNT; i++)
        if (strcmp(name, names[i]) == 0) {
            *out_id = (scene_id)i;
            return true;
        }
    return false;
}

/* ---- textures ---- */

static unsigned char mix8(double a, double b, double t)
{
    double v = a + (b - a) * (t < 0 ? 0 : t > 1 ? 1 : t);
    return (unsigned char)(v + 0.5);
}

/* Continents are where a few sums of sines exceed a threshold; integer frequencies in longitude
 * keep the date line seamless. Ice where |latitude| passes a wavy 65 degrees. */
void scenes_earth_pixels(int width, int height, unsigned char *pixels)
{
    for (int y = 0; y < height; y++) {
        double lat = PI / 2 - (y + 0.5) / height * PI;
        for (int x = 0; x < width; x++) {
            double lon = (x + 0.5) / width * 2 * PI - PI;
            double f = sin(2 * lon + 0.4) * cos(2.1 * lat - 0.3) +
                       0.6 * sin(3 * lon - 1.2 + 1.5 * sin(2 * lat)) * cos(3.7 * lat + 0.8) +
                       0.35 * sin(5 * lon + 2.9 * lat + 0.5) + 0.2 * sin(9 * lon - 6.1 * lat);
            double ice = 65.0 + 6.0 * sin(4 * lon) + 3.0 * sin(11 * lon);
            unsigned char *p = pixels + ((size_t)y * width + x) * 4;
            if (fabs(lat) * 180 / PI > ice) {
                p[0] = 236; p[1] = 240; p[2] = 246;
            } else if (f > 0.25) {
                /* Land: green, turning to desert brown near the subtropics. */
                double dry = exp(-pow((fabs(lat) * 180 / PI - 25) / 10, 2)) * (0.5 + 0.5 * sin(7 * lon));
                p[0] = mix8(52, 170, dry);
                p[1] = mix8(118, 140, dry);
                p[2] = mix8(46, 84, dry);
            } else {
                /* Ocean: lighter towards the coast. */
                double coast = (f + 1.2) / 1.45;
                p[0] = mix8(12, 40, coast);
                p[1] = mix8(38, 96, coast);
                p[2] = mix8(100, 168, coast);
            }
            p[3] = 255;
        }
    }
}

bg_status scenes_add_earth_texture(bg_scene *scene, uint32_t *out_texture)
{
    enum { W = 256, H = 128 };
    unsigned char *pixels = malloc((size_t)W * H * 4);
    if (!pixels)
        return BG_ERR_OUT_OF_MEMORY;
    scenes_earth_pixels(W, H, pixels);
    bg_image image = {W, H, BG_PIXEL_RGBA8, 0, pixels};
    bg_texture_desc desc = {BG_WRAP_REPEAT, BG_TEXTURE_SRGB, BG_FILTER_LINEAR};
    bg_status st = bg_scene_add_texture(scene, &image, &desc, out_texture);
    free(pixels);
    return st;
}

bg_status scenes_add_checker_texture(bg_scene *scene, const unsigned char a[3], const unsigned char b[3],
                                     uint32_t *out_texture)
{
    enum { N = 64, CELL = 8 };
    unsigned char pixels[N * N * 4];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            const unsigned char *c = ((x / CELL + y / CELL) % 2) ? b : a;
            unsigned char *p = pixels + (y * N + x) * 4;
            p[0] = c[0]; p[1] = c[1]; p[2] = c[2]; p[3] = 255;
        }
    bg_image image = {N, N, BG_PIXEL_RGBA8, 0, pixels};
    return bg_scene_add_texture(scene, &image, NULL, out_texture);
}

/* ---- materials, objects and lights ---- */

static bg_material diffuse(double r, double g, double b)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    return m;
}

static bg_material mirror(double c)
{
    bg_material m = diffuse(c, c, c);
    m.base.roughness.value = 0.0;
    m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    return m;
}

static bg_material glass(void)
{
    bg_material m = diffuse(0.04, 0.04, 0.04);
    m.base.roughness.value = 0.0;
    m.transparency.value = 1.0;
    m.ior = 1.5;
    m.ambient.r = m.ambient.g = m.ambient.b = 0.0;
    return m;
}

/* A glossy, coated or anisotropic variant of a colour, for variety in the grid scenes. */
static bg_material glossy(double r, double g, double b, double roughness, double isotropy)
{
    bg_material m = diffuse(r, g, b);
    m.base.roughness.value = roughness;
    m.base.isotropy.value = isotropy;
    return m;
}

static bg_material coated(double r, double g, double b)
{
    bg_material m = diffuse(r, g, b);
    m.has_coat = true;
    m.coat.reflectance.r = m.coat.reflectance.g = m.coat.reflectance.b = 0.05;
    m.coat.roughness.value = 0.05;
    return m;
}

static bg_status material(bg_scene *scene, bg_material m, uint32_t *out)
{
    return bg_scene_add_material(scene, &m, out);
}

static bg_status object(bg_scene *scene, const placement *at, bg_shape shape, bg_mat4 transform, uint32_t mat)
{
    bg_object_desc d = bg_object_desc_init(shape, mat);
    d.transform = placed(at, transform);
    uint32_t id;
    return bg_scene_add_object(scene, &d, &id);
}

/* The transform bg_scene_add_sphere makes, placed. */
static bg_status sphere(bg_scene *scene, const placement *at, double x, double y, double z, double r, uint32_t mat)
{
    return object(scene, at, BG_SHAPE_SPHERE, bg_mat4_mul(bg_mat4_translate(x, y, z), bg_mat4_scale(r, r, r)), mat);
}

/* A plane through point facing +y or +z, with the frame bg_scene_add_plane gives those normals
 * (plane_frame in src/betelgeuse/object.c: the identity for +y; x, z, -y as the columns for +z),
 * written out so that the placement can prefix it and leave the planar UVs unchanged. */
static bg_status plane(bg_scene *scene, const placement *at, bg_vec3 point, bool facing_z, uint32_t mat)
{
    bg_mat4 frame = bg_mat4_identity();
    if (facing_z) {
        frame.m[1][1] = 0.0; frame.m[1][2] = -1.0;
        frame.m[2][1] = 1.0; frame.m[2][2] = 0.0;
    }
    return object(scene, at, BG_SHAPE_PLANE, bg_mat4_mul(bg_mat4_translate(point.x, point.y, point.z), frame), mat);
}

static bg_status point_light(bg_scene *scene, const placement *at, double x, double y, double z, double r, double g,
                             double b, double intensity)
{
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(x, y, z);
    l.color[0] = r; l.color[1] = g; l.color[2] = b;
    l.intensity = intensity;
    l = placed_light(at, l);
    uint32_t id;
    return bg_scene_add_light(scene, &l, &id);
}

static bg_status camera(bg_scene *scene, const placement *at, bg_vec3 position, bg_vec3 look_at, double fov)
{
    bg_camera c = bg_camera_init();
    c.position = placed_point(at, position);
    c.look_at = placed_point(at, look_at);
    c.fov_y_degrees = fov;
    return bg_scene_set_camera(scene, &c);
}

static bg_status ambient(bg_scene *scene, double v)
{
    double rgb[3] = {v, v, v};
    return bg_scene_set_ambient(scene, rgb);
}

/* ---- scenes ---- */

/* The earth, tilted by 23.4 degrees and turned so Atlantic-like ocean and two continents face the
 * camera; it fills about 85% of the frame height. Used by both paper scenes. */
static bg_status earth(bg_scene *scene, const placement *at, double z)
{
    uint32_t tex, mat;
    TRY(scenes_add_earth_texture(scene, &tex));
    bg_material m = diffuse(1, 1, 1);
    m.base.reflectance.texture = tex;
    m.base.roughness.value = 0.7;
    m.ambient.texture = tex;
    TRY(material(scene, m, &mat));
    bg_mat4 t = bg_mat4_mul(bg_mat4_translate(0, 0, z),
                            bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 0, 1), 23.4),
                                        bg_mat4_rotate(bg_vec3_make(0, 1, 0), -30)));
    return object(scene, at, BG_SHAPE_SPHERE, t, mat);
}

static bg_status paper_earth(bg_scene *scene, const placement *at)
{
    TRY(earth(scene, at, 0));
    TRY(point_light(scene, at, 4, 3, 5, 1, 1, 1, 1.0));
    TRY(point_light(scene, at, -5, 1, 3, 0.8, 0.85, 1, 0.4));
    TRY(ambient(scene, 0.5));
    return camera(scene, at, bg_vec3_make(0, 0, 3.1), bg_vec3_make(0, 0, 0), 45);
}

/* The lights sit up and to the right in front, so the shadow falls down-left on the wall, clear
 * of the sphere's own silhouette. */
static bg_status paper_earth_shadow(bg_scene *scene, const placement *at)
{
    uint32_t white;
    TRY(earth(scene, at, 0));
    TRY(material(scene, diffuse(0.9, 0.9, 0.9), &white));
    TRY(plane(scene, at, bg_vec3_make(0, 0, -1.6), true, white));
    TRY(point_light(scene, at, 5, 4, 6, 1, 1, 1, 0.9));
    TRY(point_light(scene, at, 3, 5, 3, 1, 0.95, 0.9, 0.4));
    TRY(ambient(scene, 0.4));
    return camera(scene, at, bg_vec3_make(0, 0, 4.5), bg_vec3_make(-0.4, -0.3, 0), 45);
}

static bg_status mirror_scene(bg_scene *scene, const placement *at)
{
    uint32_t floor, chrome, red, green, blue, yellow;
    TRY(material(scene, diffuse(0.7, 0.7, 0.7), &floor));
    TRY(material(scene, mirror(0.9), &chrome));
    TRY(material(scene, diffuse(0.8, 0.15, 0.1), &red));
    TRY(material(scene, diffuse(0.15, 0.7, 0.2), &green));
    TRY(material(scene, diffuse(0.1, 0.25, 0.85), &blue));
    TRY(material(scene, diffuse(0.85, 0.75, 0.1), &yellow));
    TRY(plane(scene, at, bg_vec3_make(0, -1, 0), false, floor));
    TRY(sphere(scene, at, 0, 0, 0, 1, chrome));
    TRY(sphere(scene, at, -2.1, -0.5, 0.6, 0.5, red));
    TRY(sphere(scene, at, 2.1, -0.5, 0.6, 0.5, green));
    TRY(sphere(scene, at, 0.3, -0.5, -2.2, 0.5, blue));
    TRY(sphere(scene, at, -1.0, -0.6, 1.9, 0.4, yellow));
    TRY(point_light(scene, at, 4, 6, 5, 1, 1, 1, 0.8));
    TRY(point_light(scene, at, -5, 4, 2, 1, 1, 1, 0.4));
    TRY(ambient(scene, 0.5));
    return camera(scene, at, bg_vec3_make(0, 1.8, 6.6), bg_vec3_make(0, -0.3, 0), 45);
}

static bg_status glass_scene(bg_scene *scene, const placement *at)
{
    static const unsigned char light[3] = {230, 230, 230}, dark[3] = {40, 40, 40};
    uint32_t checker, floor, glass_m, chrome;
    TRY(scenes_add_checker_texture(scene, light, dark, &checker));
    bg_material f = diffuse(1, 1, 1);
    f.base.reflectance.texture = checker;
    TRY(material(scene, f, &floor));
    TRY(material(scene, glass(), &glass_m));
    TRY(material(scene, mirror(0.85), &chrome));
    /* Planar u = (x + 1) / 2 * uv_scale: an eighth of the texture, one checker cell, per unit. */
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_PLANE, floor);
    d.transform = placed(at, bg_mat4_translate(0, -1, 0));
    d.uv_scale[0] = d.uv_scale[1] = 0.25;
    uint32_t id;
    TRY(bg_scene_add_object(scene, &d, &id));
    TRY(sphere(scene, at, -1.1, 0, 0.4, 1, glass_m));
    TRY(sphere(scene, at, 1.2, 0, -0.8, 1, chrome));
    TRY(point_light(scene, at, 3, 6, 4, 1, 1, 1, 0.9));
    TRY(point_light(scene, at, -4, 5, -2, 1, 1, 1, 0.3));
    TRY(ambient(scene, 0.5));
    return camera(scene, at, bg_vec3_make(0, 1.4, 5.5), bg_vec3_make(0, -0.2, 0), 45);
}

/* A wall of spheres facing the camera, in a near-square grid, with a white wall behind. */
static bg_status many_spheres(bg_scene *scene, const placement *at, int n)
{
    uint32_t mats[6], wall;
    TRY(material(scene, diffuse(0.8, 0.2, 0.15), &mats[0]));
    TRY(material(scene, glossy(0.2, 0.5, 0.8, 0.3, 1.0), &mats[1]));
    TRY(material(scene, mirror(0.8), &mats[2]));
    TRY(material(scene, glass(), &mats[3]));
    TRY(material(scene, coated(0.2, 0.7, 0.25), &mats[4]));
    TRY(material(scene, glossy(0.85, 0.65, 0.2, 0.6, 0.2), &mats[5]));
    TRY(material(scene, diffuse(0.85, 0.85, 0.85), &wall));
    int side = (int)ceil(sqrt((double)n));
    int rows = (n + side - 1) / side;
    const double spacing = 2.2;
    for (int i = 0; i < n; i++) {
        double x = (i % side - (side - 1) / 2.0) * spacing;
        double y = ((rows - 1) / 2.0 - i / side) * spacing;
        TRY(sphere(scene, at, x, y, 0, 0.9, mats[i % 6]));
    }
    TRY(plane(scene, at, bg_vec3_make(0, 0, -2), true, wall));
    double half = 0.5 * side * spacing;
    TRY(point_light(scene, at, half, half, half + 6, 1, 1, 1, 0.8));
    TRY(point_light(scene, at, -half, 0.3 * half, half + 4, 1, 1, 1, 0.3));
    TRY(ambient(scene, 0.5));
    double distance = 1.15 * half / tan(22.5 * PI / 180) + 1.0;
    return camera(scene, at, bg_vec3_make(0, 0, distance), bg_vec3_make(0, 0, 0), 45);
}

/* Lights of different hues on a circle above the objects; total intensity independent of L. */
static bg_status many_lights(bg_scene *scene, const placement *at, int lights)
{
    uint32_t floor, white, box, cyl;
    TRY(material(scene, diffuse(0.8, 0.8, 0.8), &floor));
    TRY(material(scene, glossy(0.9, 0.9, 0.9, 0.6, 1.0), &white));
    TRY(material(scene, diffuse(0.7, 0.7, 0.7), &box));
    TRY(material(scene, coated(0.6, 0.6, 0.6), &cyl));
    TRY(plane(scene, at, bg_vec3_make(0, -1, 0), false, floor));
    TRY(sphere(scene, at, 0, 0, 0, 1, white));
    TRY(object(scene, at, BG_SHAPE_BOX,
               bg_mat4_mul(bg_mat4_translate(-2.4, -0.4, -0.5),
                           bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 35), bg_mat4_scale(0.6, 0.6, 0.6))),
               box));
    TRY(object(scene, at, BG_SHAPE_CYLINDER,
               bg_mat4_mul(bg_mat4_translate(2.4, -0.3, -0.5), bg_mat4_scale(0.6, 0.7, 0.6)), cyl));
    for (int i = 0; i < lights; i++) {
        double a = 2 * PI * (i + 0.25) / lights;
        /* Hue around the colour wheel, as three shifted cosines in [0, 1]. */
        double r = 0.5 + 0.5 * cos(a), g = 0.5 + 0.5 * cos(a - 2 * PI / 3), b = 0.5 + 0.5 * cos(a + 2 * PI / 3);
        TRY(point_light(scene, at, 5 * cos(a), 4, 5 * sin(a) + 1, r, g, b, 2.0 / lights));
    }
    TRY(ambient(scene, 0.3));
    return camera(scene, at, bg_vec3_make(0, 2.5, 7.5), bg_vec3_make(0, -0.3, 0), 45);
}

static bg_status all_primitives(bg_scene *scene, const placement *at)
{
    uint32_t floor, red, green, blue, yellow;
    TRY(material(scene, diffuse(0.75, 0.75, 0.75), &floor));
    TRY(material(scene, diffuse(0.8, 0.2, 0.15), &red));
    TRY(material(scene, glossy(0.2, 0.7, 0.3, 0.6, 1.0), &green));
    TRY(material(scene, diffuse(0.2, 0.35, 0.85), &blue));
    TRY(material(scene, diffuse(0.9, 0.75, 0.2), &yellow));
    bg_vec3 y = bg_vec3_make(0, 1, 0);
    TRY(plane(scene, at, bg_vec3_make(0, -1, 0), false, floor));
    TRY(sphere(scene, at, -3, 0, 0, 1, red));
    TRY(object(scene, at, BG_SHAPE_BOX,
               bg_mat4_mul(bg_mat4_translate(-0.9, -0.2, 0),
                           bg_mat4_mul(bg_mat4_rotate(y, 30), bg_mat4_scale(0.8, 0.8, 0.8))),
               green));
    TRY(object(scene, at, BG_SHAPE_CYLINDER,
               bg_mat4_mul(bg_mat4_translate(1.1, 0, 0),
                           bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 0, 1), 20), bg_mat4_scale(0.7, 1, 0.7))),
               blue));
    /* The rectangle stands up, tilted 70 degrees towards the camera and turned a little. */
    TRY(object(scene, at, BG_SHAPE_RECTANGLE,
               bg_mat4_mul(bg_mat4_translate(3.1, 0, 0),
                           bg_mat4_mul(bg_mat4_rotate(y, -20),
                                       bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(1, 0, 0), 70), bg_mat4_scale(0.9, 1, 0.9)))),
               yellow));
    TRY(point_light(scene, at, 3, 6, 6, 1, 1, 1, 0.8));
    TRY(point_light(scene, at, -6, 4, 3, 1, 1, 1, 0.35));
    TRY(ambient(scene, 0.4));
    return camera(scene, at, bg_vec3_make(0, 2.4, 11.5), bg_vec3_make(0, -0.2, 0), 45);
}

/* A coated earth, an anisotropic box and cylinder (the box's roughness from a stripe texture),
 * on a checkered floor under a spot light and a sun. */
static bg_status textured_aniso(bg_scene *scene, const placement *at)
{
    static const unsigned char a[3] = {200, 190, 170}, b[3] = {90, 60, 40};
    uint32_t earth_tex, checker, stripes, mat_earth, mat_floor, mat_box, mat_cyl;
    TRY(scenes_add_earth_texture(scene, &earth_tex));
    TRY(scenes_add_checker_texture(scene, a, b, &checker));
    enum { S = 32 };
    unsigned char px[S * S * 4];
    for (int i = 0; i < S * S; i++) {
        unsigned char v = (unsigned char)((i % S) / 4 % 2 ? 230 : 60); /* roughness stripes in red */
        px[4 * i] = v; px[4 * i + 1] = v; px[4 * i + 2] = v; px[4 * i + 3] = 255;
    }
    bg_image img = {S, S, BG_PIXEL_RGBA8, 0, px};
    bg_texture_desc lin = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR, BG_FILTER_LINEAR};
    TRY(bg_scene_add_texture(scene, &img, &lin, &stripes));

    bg_material m = coated(1, 1, 1);
    m.base.reflectance.texture = earth_tex;
    m.ambient.texture = earth_tex;
    TRY(material(scene, m, &mat_earth));
    m = diffuse(1, 1, 1);
    m.base.reflectance.texture = checker;
    TRY(material(scene, m, &mat_floor));
    m = glossy(0.9, 0.6, 0.3, 1.0, 0.15);
    m.base.roughness.texture = stripes;
    m.base.roughness.channel = 0;
    TRY(material(scene, m, &mat_box));
    m = glossy(0.7, 0.75, 0.8, 0.55, 0.1);
    m.has_coat = true;
    m.coat.reflectance.r = m.coat.reflectance.g = m.coat.reflectance.b = 0.04;
    m.coat.roughness.value = 0.2;
    TRY(material(scene, m, &mat_cyl));

    bg_object_desc d = bg_object_desc_init(BG_SHAPE_PLANE, mat_floor);
    d.transform = placed(at, bg_mat4_translate(0, -1, 0));
    d.uv_scale[0] = d.uv_scale[1] = 0.25;
    uint32_t id;
    TRY(bg_scene_add_object(scene, &d, &id));
    TRY(object(scene, at, BG_SHAPE_SPHERE,
               bg_mat4_mul(bg_mat4_translate(0, 0, 0), bg_mat4_rotate(bg_vec3_make(0, 0, 1), 23.4)), mat_earth));
    TRY(object(scene, at, BG_SHAPE_BOX,
               bg_mat4_mul(bg_mat4_translate(-2.3, -0.3, 0.2),
                           bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 25), bg_mat4_scale(0.7, 0.7, 0.7))),
               mat_box));
    d = bg_object_desc_init(BG_SHAPE_CYLINDER, mat_cyl);
    d.transform = placed(at, bg_mat4_mul(bg_mat4_translate(2.3, -0.2, 0.2), bg_mat4_scale(0.7, 0.8, 0.7)));
    d.uv_scale[0] = 2;
    TRY(bg_scene_add_object(scene, &d, &id));

    bg_light spot = bg_light_init();
    spot.position = bg_vec3_make(0, 6, 4);
    spot.direction = bg_vec3_make(0, -6, -4);
    spot.spot_cutoff_degrees = 40;
    spot.spot_exponent = 6;
    spot.intensity = 1.0;
    spot = placed_light(at, spot);
    TRY(bg_scene_add_light(scene, &spot, &id));
    bg_light sun = bg_light_init();
    sun.type = BG_LIGHT_DIRECTIONAL;
    sun.direction = bg_vec3_make(-0.5, -1, -0.4);
    sun.color[0] = 1; sun.color[1] = 0.95; sun.color[2] = 0.85;
    sun.intensity = 0.5;
    sun = placed_light(at, sun);
    TRY(bg_scene_add_light(scene, &sun, &id));
    TRY(ambient(scene, 0.3));
    return camera(scene, at, bg_vec3_make(0, 2.2, 8.2), bg_vec3_make(0, -0.3, 0), 45);
}

bg_status scenes_build_ex(scene_id id, const scene_params *params, bg_scene *scene)
{
    scene_params p;
    memset(&p, 0, sizeof p);
    if (params)
        p = *params;
    if (p.scale == 0.0)
        p.scale = 1.0;
    if (!isfinite(p.scale) || p.scale < 0.0 || !isfinite(p.offset.x) || !isfinite(p.offset.y) ||
        !isfinite(p.offset.z))
        return BG_ERR_INVALID_ARGUMENT;
    const placement at_ = {p.scale, p.offset}, *at = &at_;
    if (p.spheres == 0)
        p.spheres = 16;
    if (p.lights == 0)
        p.lights = 4;
    if (!scene || p.spheres < 1 || p.spheres > 4096 || p.lights < 1 || p.lights > 256)
        return BG_ERR_INVALID_ARGUMENT;
    bg_status st;
    switch (id) {
    case SCENE_PAPER_EARTH: st = paper_earth(scene, at); break;
    case SCENE_PAPER_EARTH_SHADOW: st = paper_earth_shadow(scene, at); break;
    case SCENE_MIRROR: st = mirror_scene(scene, at); break;
    case SCENE_GLASS: st = glass_scene(scene, at); break;
    case SCENE_MANY_SPHERES: st = many_spheres(scene, at, p.spheres); break;
    case SCENE_MANY_LIGHTS: st = many_lights(scene, at, p.lights); break;
    case SCENE_ALL_PRIMITIVES: st = all_primitives(scene, at); break;
    case SCENE_TEXTURED_ANISO: st = textured_aniso(scene, at); break;
    default: return BG_ERR_INVALID_ARGUMENT;
    }
    return st != BG_OK ? st : bg_scene_commit(scene);
}

bg_status scenes_build(scene_id id, bg_scene *scene)
{
    return scenes_build_ex(id, NULL, scene);
}
