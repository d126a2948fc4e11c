/* The diffuse spheres scene: see diffuse_spheres.h.
 *
 * The spheres sit in a grid of side ceil(cbrt(N)) cells inside the cube [-CUBE_HALF, CUBE_HALF]^3
 * (a cloud), or of side ceil(sqrt(N)) in the square of that half side at z = 0 (a layer), N of its
 * cells chosen evenly through it, each sphere jittered inside its cell. The radius is a
 * fixed share of the cell, so a ray crossing the cube meets about the same number of spheres per
 * cell at every N and the image stays about as covered; radius plus jitter stays under half a
 * cell, so no two spheres touch and every silhouette is one sphere's own. There is no ground plane:
 * a plane is unbounded, so it stays outside the object tree and every ray tests it, a cost that
 * does not grow with N and would only blur what the series measures. */
#include "diffuse_spheres.h"

#include <stdint.h>

#define CUBE_HALF 1.2
#define RADIUS_SHARE 0.28 /* of the cell side */
#define JITTER_SHARE 0.2  /* largest offset from the cell centre per axis, of the cell side */
/* A layer's spheres are larger and less jittered (0.4 + 0.08 < 1/2: still apart), so that the
 * square looks covered from its oblique camera. */
#define LAYER_RADIUS_SHARE 0.4
#define LAYER_JITTER_SHARE 0.08
#define JITTER_SEED 0x5eed2024u
#define MATERIAL_SEED 0xc0102u
#define MATERIAL_COUNT 4

/* MurmurHash3's 32-bit finaliser: every input bit reaches every output bit, so consecutive cell
 * numbers give unrelated jitters without any random-number state. */
static uint32_t hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x85ebca6bu;
    x ^= x >> 13;
    x *= 0xc2b2ae35u;
    x ^= x >> 16;
    return x;
}

/* A jitter in [-1, 1) for one axis of one cell. */
static double jitter(uint32_t cell, int axis)
{
    return hash32(JITTER_SEED ^ (cell * 3u + (uint32_t)axis)) / 2147483648.0 - 1.0;
}

/* The cell's material: hashed rather than k % MATERIAL_COUNT, which would paint whole columns of
 * the grid one colour wherever the side is a multiple of the material count. */
static uint32_t material_of(uint32_t cell)
{
    return hash32(MATERIAL_SEED ^ cell) % MATERIAL_COUNT;
}

/* The smallest side whose square or cube of cells holds n, in integers (sqrt and cbrt may round
 * below an exact power). */
static int grid_side(int n, int dimensions)
{
    int side = 1;
    while ((dimensions == 3 ? (int64_t)side * side * side : (int64_t)side * side) < n)
        side++;
    return side;
}

static bg_status add_materials(bg_scene *scene, uint32_t materials[MATERIAL_COUNT])
{
    /* Roughness stays 1 (Lambertian), opaque, no coat: bgi_gpu_material_may_bounce is false for each,
     * so neither renderer spawns a secondary ray. */
    static const double colors[MATERIAL_COUNT][3] = {
        {0.80, 0.25, 0.20}, {0.25, 0.70, 0.30}, {0.25, 0.40, 0.85}, {0.85, 0.75, 0.30}};
    for (int i = 0; i < MATERIAL_COUNT; i++) {
        bg_material m = bg_material_init();
        m.base.reflectance.r = colors[i][0];
        m.base.reflectance.g = colors[i][1];
        m.base.reflectance.b = colors[i][2];
        bg_status st = bg_scene_add_material(scene, &m, &materials[i]);
        if (st != BG_OK)
            return st;
    }
    return BG_OK;
}

/* Sphere k of n takes cell floor(k * cells / n): distinct cells (n <= cells), spread through the
 * whole cube rather than filling its first layers, so a partial grid covers the same region. */
static bg_status add_spheres(bg_scene *scene, int n, diffuse_layout layout, const uint32_t materials[MATERIAL_COUNT])
{
    const int dimensions = layout == DIFFUSE_CLOUD ? 3 : 2;
    const int side = grid_side(n, dimensions);
    const int64_t cells = dimensions == 3 ? (int64_t)side * side * side : (int64_t)side * side;
    const double spacing = 2.0 * CUBE_HALF / side;
    const double radius = (dimensions == 3 ? RADIUS_SHARE : LAYER_RADIUS_SHARE) * spacing;
    const double spread = dimensions == 3 ? JITTER_SHARE : LAYER_JITTER_SHARE;
    for (int k = 0; k < n; k++) {
        uint32_t cell = (uint32_t)((int64_t)k * cells / n);
        int index[3] = {(int)(cell % (uint32_t)side), (int)(cell / (uint32_t)side % (uint32_t)side),
                        (int)(cell / ((uint32_t)side * (uint32_t)side))};
        double c[3];
        for (int a = 0; a < 3; a++)
            c[a] = -CUBE_HALF + (index[a] + 0.5 + spread * jitter(cell, a)) * spacing;
        /* A layer's third axis is its one cell around z = 0, jittered like the others. */
        if (dimensions == 2)
            c[2] = spread * jitter(cell, 2) * spacing;
        uint32_t object;
        bg_status st = bg_scene_add_sphere(scene, bg_vec3_make(c[0], c[1], c[2]), radius,
                                           materials[material_of(cell)], &object);
        if (st != BG_OK)
            return st;
    }
    return BG_OK;
}

/* A key light and a dimmer fill, both well off the view axis, so the shadow rays of visible points
 * cross other spheres: for the cloud above left and to the right of the camera, for the layer low
 * over its plane, where they graze the neighbours. */
static bg_status add_lights(bg_scene *scene, diffuse_layout layout)
{
    static const double places[2][2][4] = {{{-3.0, 1.0, 0.9, 0.8}, {2.5, 3.0, 1.1, 0.4}},
                                           {{-3.0, 4.0, 4.0, 0.8}, {4.0, 1.5, 2.0, 0.4}}};
    for (int i = 0; i < 2; i++) {
        const double *place = places[layout == DIFFUSE_CLOUD][i];
        bg_light l = bg_light_init();
        l.position = bg_vec3_make(place[0], place[1], place[2]);
        l.intensity = place[3];
        uint32_t light;
        bg_status st = bg_scene_add_light(scene, &l, &light);
        if (st != BG_OK)
            return st;
    }
    return BG_OK;
}

/* For the cloud a little above and to the right, so the cube shows three faces and its depth; for
 * the layer below it and closer, looking up at the square so that it fills most of the image. */
static bg_status set_camera(bg_scene *scene, diffuse_layout layout)
{
    bg_camera camera = bg_camera_init();
    camera.position = layout == DIFFUSE_CLOUD ? bg_vec3_make(1.2, 1.5, 5.5) : bg_vec3_make(0.4, -1.6, 2.6);
    camera.look_at = bg_vec3_make(0.0, 0.0, 0.0);
    return bg_scene_set_camera(scene, &camera);
}

bg_status diffuse_spheres_build(bg_scene *scene, int n, diffuse_layout layout)
{
    if (!scene || n < 1 || n > DIFFUSE_SPHERES_MAX || (layout != DIFFUSE_LAYER && layout != DIFFUSE_CLOUD))
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t materials[MATERIAL_COUNT];
    bg_status st = add_materials(scene, materials);
    if (st == BG_OK)
        st = add_spheres(scene, n, layout, materials);
    if (st == BG_OK)
        st = add_lights(scene, layout);
    if (st == BG_OK)
        st = set_camera(scene, layout);
    return st;
}
