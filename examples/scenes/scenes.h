/* Shared scenes for tests, benchmarks and examples: each builds into an empty scene and commits. */
#ifndef SCENES_H
#define SCENES_H

#include "betelgeuse.h"

typedef enum scene_id {
    SCENE_PAPER_EARTH = 0,   /* the paper's figure 1: an earth-textured sphere, two point lights */
    SCENE_PAPER_EARTH_SHADOW,/* the same sphere in front of a white plane that catches its shadow */
    SCENE_MIRROR,            /* a mirror sphere among coloured diffuse spheres over a plane */
    SCENE_GLASS,             /* a glass sphere and a mirror sphere over a checkered plane */
    SCENE_MANY_SPHERES,      /* a grid of spheres (params.spheres) of varied materials */
    SCENE_MANY_LIGHTS,       /* a few objects lit by params.lights coloured point lights */
    SCENE_ALL_PRIMITIVES,    /* one of every shape, some rotated */
    SCENE_TEXTURED_ANISO,    /* textured, anisotropic and coated materials; spot and sun lights */
    SCENE_COUNT
} scene_id;

/* Parameters of the scaling scenes; zero means the default. scale and offset place any scene at
 * p -> scale p + offset: camera, objects (the similarity prefixed to each transform, so UVs stay)
 * and point lights move, linear and quadratic attenuation are divided by scale and scale^2, so the
 * ideal image is the same at every size and place (the float32 stress cases, bench/stress.c). */
typedef struct scene_params {
    int spheres;    /* SCENE_MANY_SPHERES: 1 .. 4096, default 16 */
    int lights;     /* SCENE_MANY_LIGHTS: 1 .. 256, default 4 */
    double scale;   /* > 0, finite; 0 means 1 */
    bg_vec3 offset; /* finite; default (0, 0, 0) */
} scene_params;

/* The scene's short name ("paper_earth"), or NULL for an unknown id. */
const char *scenes_name(scene_id id);
/* Looks a scene up by its short name; false if there is none. */
bool scenes_find(const char *name, scene_id *out_id);
/* Builds the scene with default parameters into an empty scene and commits it. */
bg_status scenes_build(scene_id id, bg_scene *scene);
/* Builds the scene with the given parameters (NULL for defaults) and commits it. */
bg_status scenes_build_ex(scene_id id, const scene_params *params, bg_scene *scene);

/* The procedural earth as sRGB-encoded RGBA8, lat-long layout, top row the north pole.
 * pixels holds width * height * 4 bytes. Deterministic. */
void scenes_earth_pixels(int width, int height, unsigned char *pixels);
/* Adds the procedural earth (256x128) to a scene as an sRGB texture. */
bg_status scenes_add_earth_texture(bg_scene *scene, uint32_t *out_texture);
/* Adds a 64x64 two-colour checker (8x8 texels per cell) as an sRGB texture. */
bg_status scenes_add_checker_texture(bg_scene *scene, const unsigned char a[3], const unsigned char b[3],
                                     uint32_t *out_texture);

#endif
