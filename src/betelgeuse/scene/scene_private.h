/* The scene object: pending state (what the API calls fill) and committed state (what the
 * renderers read, through scene_internal.h). Only the scene_*.c, object.c, material.c, light.c,
 * texture.c and png_io.c files see this. */
#ifndef BG_SCENE_PRIVATE_H
#define BG_SCENE_PRIVATE_H

#include "scene_internal.h"

/* Handles fit comfortably in 32 bits and array sizes in size_t. */
#define BG_MAX_ITEMS (1u << 24)
#define BG_MESSAGE_SIZE 512

/* A growable array of elem-sized items; storage is kept across commits for reuse. */
typedef struct bg_array {
    void *data;
    uint32_t count, capacity;
} bg_array;

struct bg_scene {
    bg_allocator allocator;
    bg_log_fn log;
    void *log_user;
    bg_status error;
    char message[BG_MESSAGE_SIZE];

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
};

/* Makes room for need items (keeping the contents); BG_ERR_LIMIT past BG_MAX_ITEMS, and
 * BG_ERR_OUT_OF_MEMORY leaves the array as it was. Records errors on the scene as from `where`. */
bg_status bg_array_reserve(bg_scene *scene, bg_array *array, uint32_t need, size_t elem,
                           const char *where);
/* Frees the storage of an array. */
void bg_array_release(bg_scene *scene, bg_array *array);

/* Checks a 1-based handle against a count and returns the 0-based index, or fails naming kind. */
bg_status bg_scene_handle(bg_scene *scene, const char *where, const char *kind, uint32_t handle,
                          uint32_t count, uint32_t *out_index);

/* Field validators used both by the API calls and by commit. where is the message prefix
 * ("bg_scene_add_material" or "bg_scene_commit: material 2"). */
bg_status bg_validate_camera(bg_scene *scene, const char *where, const bg_camera *camera);
bg_status bg_validate_color3(bg_scene *scene, const char *where, const char *field,
                             const double rgb[3]);
bg_status bg_validate_material(bg_scene *scene, const char *where, const bg_material *m,
                               uint32_t texture_count);
bg_status bg_validate_light(bg_scene *scene, const char *where, const bg_light *light);
bg_status bg_validate_object(bg_scene *scene, const char *where, const bg_object_desc *desc,
                             uint32_t material_count);
bg_status bg_validate_transform(bg_scene *scene, const char *where, const bg_mat4 *transform);

/* Adds an RGBA8 or RGBA32F image as a texture (texture.c); where names the API call. */
bg_status bg_texture_add(bg_scene *scene, const char *where, const bg_image *image,
                         const bg_texture_desc *desc, uint32_t *out_texture);

#endif
