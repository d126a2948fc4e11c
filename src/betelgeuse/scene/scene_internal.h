/* The committed scene as both renderers read it. scene.c owns it; renderers never see the
 * pending (uncommitted) state. Everything here is validated and finite. Arrays are dense: the live
 * items in the order of their slots (scene_private.h), so removed items leave no holes, and every
 * index below is into these arrays, never an API handle. */
#ifndef BG_SCENE_INTERNAL_H
#define BG_SCENE_INTERNAL_H

#include "betelgeuse.h"
#include "../common/bvh.h"

/* A texture as stored in the scene, at its image's precision, rows in GL order (row 0 is v = 0, the
 * bottom of the source image; PNG and bg_image rows are flipped on add): an RGBA8 image keeps its
 * bytes (4 a texel), decoded where it is sampled; an RGBA32F image its linear floats (16 a texel).
 * Exactly one of texels and bytes is set. */
typedef struct bg_texture_data {
    int width, height;
    bg_texture_wrap wrap;
    bg_texture_filter filter;
    float *texels;        /* RGBA32F: width * height * 4 linear floats; NULL for RGBA8 */
    unsigned char *bytes; /* RGBA8: width * height * 4 bytes as the image held them; NULL for RGBA32F */
    bool srgb;            /* RGBA8 only: R, G and B are sRGB-encoded (bgi_srgb_table decodes them);
                             else every channel is k / 255. Alpha is always k / 255 */
} bg_texture_data;

/* Texel k (index j * width + i) of t as linear RGBA in double: floats as stored, bytes decoded
 * (scene/texture.c). Both renderers read 8-bit texels through this one rule. */
void bgi_texture_texel(const bg_texture_data *t, size_t k, double rgba[4]);
/* Channel c of texel k as bgi_texture_texel gives it. */
double bgi_texture_channel(const bg_texture_data *t, size_t k, int c);
/* The bytes t's texels take on the host (and, uploaded at their precision, on the GPU). */
size_t bgi_texture_bytes(const bg_texture_data *t);

/* The shape value of a mesh object in bg_object_data (never a bg_shape of the API): past every
 * table indexed by bg_shape, so that no shape table can take a mesh for an analytic shape; such
 * tables guard their index (bg_shape_thin gives false, the CPU's prototype intersector a miss). */
#define BGI_SHAPE_MESH ((bg_shape)BG_SHAPE_COUNT_)

/* A mesh's geometry (scene/mesh.c): immutable once added, shared by every object that shows it
 * (bg_scene_add_mesh_instance), freed when the last pending object using it is removed and no
 * committed state can still read it (the next successful commit, or the scene's destruction). */
typedef struct bg_mesh_data {
    uint32_t vertex_count, triangle_count;
    float *positions;   /* 3 per vertex, as given */
    uint32_t *indices;  /* 3 per triangle, each < vertex_count */
    float *normals;     /* 3 per vertex or NULL */
    float *uvs;         /* 2 per vertex or NULL */
    double box_min[3], box_max[3]; /* object-space box of the vertices the triangles use */
    bg_bvh tree;        /* over the triangles' object-space boxes: primitive i is triangle i */
    uint32_t refs;      /* live pending objects that show it */
    uint64_t serial;    /* unique in the process (bgi_scene_next_serial): a GPU copy's key */
    struct bg_mesh_data *next_retired; /* on the scene's retired list once refs is 0 */
} bg_mesh_data;

/* An object with everything derived at commit (scene/object_data.c). */
typedef struct bg_object_data {
    bg_shape shape;              /* BGI_SHAPE_MESH for a mesh object */
    const bg_mesh_data *mesh;    /* the mesh of a mesh object, NULL for the analytic shapes */
    double to_world[4][4];       /* the object's transform */
    double to_object[4][4];      /* its inverse, computed in double */
    double normal_to_world[3][3];/* inverse transpose of the linear part */
    uint32_t material;           /* index into materials (not the API handle) */
    bg_uv_mapping uv_mapping;    /* resolved: never BG_UV_DEFAULT */
    double uv_scale[2];
    bool casts_shadows;
    bool bounded;                /* false for planes */
    double bounds_min[3], bounds_max[3]; /* world-space box; meaningful when bounded */
    uint32_t light;              /* a visible area light's object: 1 + the light's index; else 0 */
} bg_object_data;

/* The camera with its derived orthonormal basis (forward, right, up: right-handed). */
typedef struct bg_camera_data {
    bg_camera camera;
    double forward[3], right[3], up[3];
    bool orthographic; /* camera.projection is BG_PROJECTION_ORTHOGRAPHIC */
    double half_y;     /* the view's half-height: at unit distance ahead (tan(fov_y / 2), perspective),
                          or in world units (half_height, orthographic) */
    double focus; /* the distance to the plane in focus, along forward (camera.focus_distance, or
                     |look_at - position| for 0); used with camera.aperture_radius > 0 only */
} bg_camera_data;

/* The committed environment (docs/shading.md 7.1). The importance tables are the cumulative sums,
 * normalised to end at 1, of the texel weights w(i, j) = luminance x sin(theta of row j): marginal[j]
 * over whole rows (height entries), conditional[j * width + i] along row j (width entries per row;
 * a row of weight 0 is never drawn). NULL tables: uniform sampling (asked for, or a black image). */
typedef struct bg_environment_data {
    bool on;
    uint32_t texture; /* dense 1-based index into textures */
    double intensity;
    bool lights;
    bg_environment_sampling sampling;
    const double *marginal, *conditional;
    uint64_t tables_id; /* which tables these are: the GPU renderer uploads them once per id */
} bg_environment_data;

/* What a commit produces. Lights' directions are normalised; materials keep their public form
 * except that each texture field holds a dense 1-based index (textures[t - 1]; 0 none), not the
 * API handle. */
#define BGI_GPU_RANGE_NOTE_SIZE 256

typedef struct bg_scene_state {
    bg_camera_data camera;
    double ambient[3];
    bg_environment_data environment;
    /* The scene spends camera samples on a distribution effect: a lens, an area light, a glossy
     * material or the environment's light (docs/shading.md 1.3). Without one the CPU reference does
     * not compute the sample points at all. */
    bool distribution;
    uint32_t object_count, material_count, texture_count, light_count;
    const bg_object_data *objects;
    const bg_material *materials;
    const bg_texture_data *textures;
    const bg_light *lights;
    uint32_t mesh_object_count;  /* objects whose mesh is not NULL */
    bool has_bounded_objects;
    double bounds_min[3], bounds_max[3]; /* union of the bounded objects' boxes */
    /* The object tree (common/bvh.h) over every object whose world box fits the float range: the
     * tree's primitive i is object tree_objects[i]. Every other object (the unbounded ones, and
     * any whose box no float box can hold) is in always_objects, for every ray to test. Both lists
     * ascend, so a renderer that applies "equal distance: lower index wins" stays exact. */
    const bg_bvh *tree;
    const uint32_t *tree_objects, *always_objects;
    uint32_t tree_count, always_count;
    uint64_t tree_builds, tree_refits; /* commits that rebuilt or refitted the tree */
    uint64_t commit_count;
    /* A number no other commit in the process had, of this scene or another (never 0): a renderer's
     * cache keyed by it stays right when a scene is freed and another made at the same address. */
    uint64_t serial;
    /* Empty, or why the GPU renderer refuses this commit: the first object, light or camera value
     * beyond the lengths it resolves in float, by handle (scene/gpu_range.c). */
    char gpu_range[BGI_GPU_RANGE_NOTE_SIZE];
} bg_scene_state;

/* The committed state, or NULL when the scene was never committed successfully. */
const bg_scene_state *bgi_scene_committed(const bg_scene *scene);
/* A number no earlier call in the process returned (commits and meshes are keyed by it). */
uint64_t bgi_scene_next_serial(void);

/* Records an error on the scene (first one sticks) and sends it to the logger; returns status. */
bg_status bgi_scene_fail(bg_scene *scene, bg_status status, const char *format, ...);

#endif
