/* The scene object: pending state (what the API calls fill) and committed state (what the
 * renderers read, through scene_internal.h). Only the files of scene/ and io/png.c see this. */
#ifndef BG_SCENE_PRIVATE_H
#define BG_SCENE_PRIVATE_H

#include "../../macs/first_error.h"
#include "scene_internal.h"

/* Handles fit comfortably in 32 bits and array sizes in size_t. */
#define BG_MAX_ITEMS (1u << 24)
/* Every message Betelgeuse formats fits the size of the one the scene keeps. */
#define BG_MESSAGE_SIZE MACS_MESSAGE_SIZE

/* A growable array of elem-sized items; storage is kept across commits for reuse. */
typedef struct bg_array {
    void *data;
    uint32_t count, capacity;
} bg_array;

struct bg_scene {
    bg_allocator allocator;
    bg_logger logger;
    macs_first_error error; /* status is a bg_status */

    /* Pending state. Textures are immutable once added, so the committed state shares their
     * texels; the pending texture array owns them. */
    bg_camera camera;
    double ambient[3];
    bg_array objects;   /* bg_object_desc */
    bg_array materials; /* bg_material */
    bg_array lights;    /* bg_light */
    bg_array textures;  /* bg_texture_data */

    /* Committed state and the storage behind its arrays. */
    bool committed;
    bg_scene_state state;
    bg_array c_objects;   /* bg_object_data */
    bg_array c_materials; /* bg_material */
    bg_array c_lights;    /* bg_light */
    bg_array c_textures;  /* bg_texture_data (texels shared with the pending array) */

    /* The object tree: the committed one, the lists behind the committed state's tree fields
     * (c_), and the commit in progress's boxes and lists (p_), swapped in when it succeeds. */
    bg_bvh tree;
    bg_bvh rebuilt;        /* a tree built aside by bgi_scene_tree_prepare, empty otherwise */
    int tree_action;       /* what bgi_scene_tree_install does (tree.c) */
    bg_array c_boxes, p_boxes;               /* bg_bvh_box, one per tree primitive */
    bg_array c_tree_objects, p_tree_objects; /* uint32_t */
    bg_array c_always, p_always;             /* uint32_t */
};

/* Makes room for need items (keeping the contents); BG_ERR_LIMIT past BG_MAX_ITEMS, and
 * BG_ERR_OUT_OF_MEMORY leaves the array as it was. Records errors on the scene as from `where`. */
bg_status bgi_array_reserve(bg_scene *scene, bg_array *array, uint32_t need, size_t elem,
                           const char *where);
/* Frees the storage of an array. */
void bgi_array_release(bg_scene *scene, bg_array *array);

/* Checks a 1-based handle against a count and returns the 0-based index, or fails naming kind. */
bg_status bgi_scene_handle(bg_scene *scene, const char *where, const char *kind, uint32_t handle,
                          uint32_t count, uint32_t *out_index);

/* Field validators used both by the API calls and by commit. where is the message prefix
 * ("bg_scene_add_material" or "bg_scene_commit: material 2"). */
bg_status bgi_validate_camera(bg_scene *scene, const char *where, const bg_camera *camera);
bg_status bgi_validate_color3(bg_scene *scene, const char *where, const char *field,
                             const double rgb[3]);
bg_status bgi_validate_material(bg_scene *scene, const char *where, const bg_material *m,
                               uint32_t texture_count);
bg_status bgi_validate_light(bg_scene *scene, const char *where, const bg_light *light);
bg_status bgi_validate_object(bg_scene *scene, const char *where, const bg_object_desc *desc,
                             uint32_t material_count);
bg_status bgi_validate_transform(bg_scene *scene, const char *where, const bg_mat4 *transform);

/* The world box of an object about to be committed; false for an unbounded shape (tree.c reads
 * it through commit.c, which owns the shapes' extents). */
bool bgi_object_world_box(const bg_object_desc *desc, double lo[3], double hi[3]);

/* Plans the committed object tree for the pending objects (boxes from bgi_object_world_box): kept
 * when no tree box changed, refitted when only boxes changed, rebuilt aside otherwise. Allocates
 * everything it needs, so a failure leaves the committed state as it was. */
bg_status bgi_scene_tree_prepare(bg_scene *scene);
/* Puts the prepared tree into the committed state; cannot fail. */
void bgi_scene_tree_install(bg_scene *scene);
/* Frees the trees and their lists. */
void bgi_scene_tree_release(bg_scene *scene);

/* Adds an RGBA8 or RGBA32F image as a texture (texture.c); where names the API call. */
bg_status bgi_texture_add(bg_scene *scene, const char *where, const bg_image *image,
                         const bg_texture_desc *desc, uint32_t *out_texture);

#endif
