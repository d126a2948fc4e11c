/* The scene object: pending state (what the API calls fill) and committed state (what the
 * renderers read, through scene_internal.h). Only the files of scene/ and io/png.c see this. */
#ifndef BG_SCENE_PRIVATE_H
#define BG_SCENE_PRIVATE_H

#include "../../macs/first_error.h"
#include "scene_internal.h"

/* Array sizes fit comfortably in 32 bits and in size_t. */
#define BG_MAX_ITEMS (1u << 24)
/* Every message Betelgeuse formats fits the size of the one the scene keeps. */
#define BG_MESSAGE_SIZE MACS_MESSAGE_SIZE

/* A growable array of elem-sized items; storage is kept across commits for reuse. */
/* An environment texture's importance tables (environment.c); texture is the API handle they were
 * built from. */
typedef struct bgi_environment_tables {
    uint32_t texture;
    uint64_t id;
    double *marginal, *conditional;
} bgi_environment_tables;

typedef struct bg_array {
    void *data;
    uint32_t count, capacity;
} bg_array;

/* What the object pool holds: the description, and for a mesh object (desc.shape BGI_SHAPE_MESH)
 * the mesh it shows, one of mesh's refs. */
typedef struct bg_object_item {
    bg_object_desc desc;
    bg_mesh_data *mesh;
} bg_object_item;

/* Handles (pool.c), as sokol_gfx's pools make them: an item's id is (slot + 1) | (generation << 24).
 * A fresh slot has generation 0, so a scene that never removes hands out 1, 2, 3, ...; removal bumps
 * the slot's generation and frees the slot for reuse, and a slot whose generation would pass 255 is
 * retired instead (never reused), so an id of a removed item can never name a later one. */
#define BG_HANDLE_SLOT_BITS 24
#define BG_HANDLE_SLOT_MASK ((1u << BG_HANDLE_SLOT_BITS) - 1u)
#define BG_HANDLE_LAST_GENERATION 255u
/* slot + 1 must fit the slot bits. */
#define BG_MAX_SLOTS BG_HANDLE_SLOT_MASK
/* Room for bgi_handle_text's longest output ("0xFFFFFFFF"). */
#define BG_HANDLE_TEXT_SIZE 16

/* The slot an id names (past every pool for 0, whose slot bits are 0). */
static inline uint32_t bgi_handle_slot(uint32_t id)
{
    return (id & BG_HANDLE_SLOT_MASK) - 1u;
}

typedef enum { BG_SLOT_FREE = 0, BG_SLOT_LIVE, BG_SLOT_RETIRED } bg_slot_state;

typedef struct bg_slot {
    uint8_t generation;
    uint8_t state; /* bg_slot_state */
} bg_slot;

/* Items of one kind in slots. items and slots have one entry per slot ever used; free_slots can
 * always hold every slot, so that removal never allocates. */
typedef struct bg_pool {
    const char *kind;   /* "object", for messages */
    const char *a_kind; /* "an object" */
    size_t elem;        /* bytes per item */
    bg_array items;
    bg_array slots;      /* bg_slot */
    bg_array free_slots; /* uint32_t, reused last-freed first */
    uint32_t live;       /* slots holding an item */
} bg_pool;

struct bg_scene {
    bg_allocator allocator;
    bg_logger logger;
    macs_first_error error; /* status is a bg_status */

    /* Pending state. Textures are immutable once added, so the committed state shares their
     * texels; the pending texture pool owns them. A removed texture's texels may still be in the
     * committed state, so they wait in retired_texels until the next successful commit. */
    bg_camera camera;
    double ambient[3];
    /* The environment as set, and its importance tables: the pending ones (built by
     * bg_scene_set_environment) and the committed ones, freed when no state holds them. */
    bg_environment environment;
    bgi_environment_tables *env_pending, *env_committed;
    bg_pool objects;   /* bg_object_item */
    bg_pool materials; /* bg_material */
    bg_pool lights;    /* bg_light */
    bg_pool textures;  /* bg_texture_data */
    bg_array retired_texels; /* float * or unsigned char * (texels or bytes), freed at the next successful commit */
    bg_mesh_data *retired_meshes; /* meshes no pending object shows, freed like retired_texels */

    /* Committed state and the storage behind its arrays: dense (live items in slot order), with
     * objects' materials and materials' textures translated to dense indices. */
    bool committed;
    bg_scene_state state;
    bg_array c_objects;   /* bg_object_data */
    bg_array c_materials; /* bg_material */
    bg_array c_lights;    /* bg_light */
    bg_array c_textures;  /* bg_texture_data (texels shared with the pending pool) */

    /* A commit in progress derives everything here first (p_ like the tree's lists), so that a
     * failure leaves the committed arrays untouched; success copies it over them. The maps take
     * a material or texture slot to its dense index. */
    bg_array p_objects, p_materials, p_lights, p_textures;
    bg_array material_map, texture_map; /* uint32_t per slot */
    uint32_t p_mesh_objects;            /* mesh objects among p_objects */

    /* The object tree: the committed one, the lists behind the committed state's tree fields
     * (c_), and the commit in progress's boxes and lists (p_), swapped in when it succeeds. */
    bg_bvh tree;
    bg_bvh rebuilt;        /* a tree built aside by bgi_scene_tree_prepare, empty otherwise */
    int tree_action;       /* what bgi_scene_tree_install does (tree.c) */
    bg_array c_boxes, p_boxes;               /* bg_bvh_box, one per tree primitive */
    bg_array c_tree_objects, p_tree_objects; /* uint32_t */
    bg_array c_always, p_always;             /* uint32_t */
};

/* Writes into note (empty when none) the first length of the commit in progress (p_objects, p_lights
 * and camera) that the GPU renderer cannot resolve in float, naming the item by handle. */
void bgi_gpu_range_note(const bg_scene *s, const bg_camera_data *camera, char *note, size_t size);

/* Makes room for need items (keeping the contents); BG_ERR_LIMIT past BG_MAX_ITEMS, and
 * BG_ERR_OUT_OF_MEMORY leaves the array as it was. Records errors on the scene as from `where`. */
bg_status bgi_array_reserve(bg_scene *scene, bg_array *array, uint32_t need, size_t elem,
                           const char *where);
/* Frees the storage of an array. */
void bgi_array_release(bg_scene *scene, bg_array *array);

/* ---- environment.c ---- */

/* Whether the environment uses texture (a handle), for removal. */
bool bgi_environment_uses(const bg_scene *scene, uint32_t texture);
/* Fills the committed environment of the pending one (texture_map translates its handle). */
void bgi_environment_commit(bg_scene *scene, const uint32_t *texture_map, bg_environment_data *out);
/* Frees the tables at scene destruction. */
void bgi_environment_release(bg_scene *scene);

/* ---- pool.c ---- */

/* An empty pool of elem-sized items; kind ("object") and a_kind ("an object") name them in messages. */
void bgi_pool_init(bg_pool *pool, const char *kind, const char *a_kind, size_t elem);
/* Frees the pool's storage (not what its items point to). */
void bgi_pool_release(bg_scene *scene, bg_pool *pool);
/* Makes sure the next bgi_pool_add cannot fail: BG_ERR_LIMIT when every slot a handle can name is
 * used or retired, BG_ERR_OUT_OF_MEMORY; the pool is unchanged on failure. */
bg_status bgi_pool_reserve(bg_scene *scene, bg_pool *pool, const char *where);
/* Copies item into a free slot (the last freed, else a new one) and hands out its id. */
bg_status bgi_pool_add(bg_scene *scene, bg_pool *pool, const char *where, const void *item, uint32_t *out_id);
/* The one handle lookup every call taking a handle goes through: the slot of a live id, or
 * BG_ERR_INVALID_ARGUMENT with "where: field = id is not an object of this scene (n in use)", or
 * "where: field = id was removed" for the id of a removed item. */
bg_status bgi_pool_lookup(bg_scene *scene, const bg_pool *pool, const char *where, const char *field, uint32_t id,
                         uint32_t *out_slot);
/* Frees a live slot: its generation moves on (or the slot retires), its ids stop working. */
void bgi_pool_remove(bg_pool *pool, uint32_t slot);
/* Slots ever used (live, free or retired): the range to walk with bgi_pool_live. */
uint32_t bgi_pool_slot_count(const bg_pool *pool);
bool bgi_pool_live(const bg_pool *pool, uint32_t slot);
/* The item in a slot. */
void *bgi_pool_item(const bg_pool *pool, uint32_t slot);
/* The id of a slot's current generation. */
uint32_t bgi_pool_id(const bg_pool *pool, uint32_t slot);
/* An id as messages write it: decimal in generation 0 (the ids of a scene that never removed
 * anything), hexadecimal otherwise, where the generation byte is then readable. */
const char *bgi_handle_text(uint32_t id, char text[BG_HANDLE_TEXT_SIZE]);

/* ---- validate.c: field validators used both by the API calls and by commit ---- */

/* where is the message prefix ("bg_scene_add_material" or "bg_scene_commit: material 2"). The
 * camera and light checks are reached through bgi_camera_derive and bgi_light_derive below. */
bg_status bgi_validate_camera(bg_scene *scene, const char *where, const bg_camera *camera);
bg_status bgi_validate_light(bg_scene *scene, const char *where, const bg_light *light);
bg_status bgi_validate_color3(bg_scene *scene, const char *where, const char *field,
                             const double rgb[3]);
/* Values and texture references (through bgi_pool_lookup). */
bg_status bgi_validate_material(bg_scene *scene, const char *where, const bg_material *m);
/* Everything but the transform and what is derived from it (object_data.c); writes the material's
 * slot. mesh: the object is a mesh object (shape BGI_SHAPE_MESH, which is refused otherwise). */
bg_status bgi_validate_object_fields(bg_scene *scene, const char *where, const bg_object_desc *desc, bool mesh,
                                    uint32_t *out_material_slot);

/* Every texture reference of a material, one row each: X(field) with m->field.texture the handle. */
#define BG_MATERIAL_TEXTURES(X)                                                                  \
    X(base.reflectance) X(base.roughness) X(base.isotropy) X(coat.reflectance) X(coat.roughness) \
    X(coat.isotropy) X(ambient) X(emission) X(transparency) X(coverage)

/* ---- derivation: the one check of each item that both its API calls and commit run ---- */

/* Validates a camera and derives its basis (commit.c). */
bg_status bgi_camera_derive(bg_scene *scene, const char *where, const bg_camera *camera, bg_camera_data *out);
/* Validates a light and derives its committed form (normalised direction) (commit.c). */
bg_status bgi_light_derive(bg_scene *scene, const char *where, const bg_light *light, bg_light *out);
/* Validates an object and derives everything a commit stores for it (object_data.c): inverse,
 * normal matrix, resolved UV mapping, world box, each checked finite. out->material is the
 * material's slot (commit translates it). transform_field names the transform in messages
 * ("transform", or what a shorthand built it from). */
bg_status bgi_object_derive(bg_scene *scene, const char *where, const char *transform_field,
                           const bg_object_item *item, bg_object_data *out);
/* The same without the fields' checks and the material (left to the caller): for objects the scene
 * makes itself, such as a visible light's shape. */
bg_status bgi_object_derive_shape(bg_scene *scene, const char *where, const char *transform_field,
                                  const bg_object_item *item, bg_object_data *out);

/* ---- mesh.c ---- */

/* Drops one object's reference to its mesh (NULL ignored); the last one moves the mesh to the
 * retired list, which never allocates, so removal cannot fail. */
void bgi_mesh_unref(bg_scene *scene, bg_mesh_data *mesh);
/* Frees the retired meshes (after a successful commit: no committed state shows them any more). */
void bgi_mesh_free_retired(bg_scene *scene);

/* ---- tree.c ---- */

/* Plans the committed object tree for the objects the commit in progress derived (p_objects):
 * kept when no tree box changed, refitted when only boxes changed, rebuilt aside otherwise.
 * Allocates everything it needs, so a failure leaves the committed state as it was. */
bg_status bgi_scene_tree_prepare(bg_scene *scene);
/* Puts the prepared tree into the committed state; cannot fail. */
void bgi_scene_tree_install(bg_scene *scene);
/* Frees the trees and their lists. */
void bgi_scene_tree_release(bg_scene *scene);

/* Adds an RGBA8 or RGBA32F image as a texture (texture.c); where names the API call. */
bg_status bgi_texture_add(bg_scene *scene, const char *where, const bg_image *image,
                         const bg_texture_desc *desc, uint32_t *out_texture);

#endif
