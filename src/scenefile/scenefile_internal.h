/* The scene-file library's inside: one load context that every reader shares. It holds where the
 * reader stands in the JSON (path, e.g. "objects[3].sphere.radius"), so that every error can name
 * the file, the path and the reason through one sink (bgi_sf_fail), and the name tables that JSON
 * references resolve against. */
#ifndef BG_SCENEFILE_INTERNAL_H
#define BG_SCENEFILE_INTERNAL_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cJSON.h>

#include "betelgeuse_scenefile.h"

/* The longest path (file names, JSON paths) the loader builds; longer ones are refused by name. */
#define BGI_SF_PATH_MAX 4096

/* A name given in the file ("textures": {"earth": ...}) and the handle the scene gave its item. */
typedef struct bgi_sf_name {
    char *name;
    uint32_t handle;
} bgi_sf_name;

typedef struct bgi_sf_names {
    bgi_sf_name *items;
    size_t count, capacity;
} bgi_sf_names;

typedef struct bgi_sf_ctx {
    const char *file;            /* the file's name in messages */
    char dir[BGI_SF_PATH_MAX];   /* folder relative paths resolve against; "" = the current one */
    bg_logger logger;
    bg_scenefile_inputs inputs;  /* told of each file before it is read */
    bg_scene *scene;
    bg_scenefile_result *out;
    char *message;
    size_t message_size;
    bg_status status;            /* the first failure; later ones keep its message */
    char path[1024];             /* where the reader stands in the JSON */
    size_t path_len;
    bgi_sf_names textures, materials;
    uint32_t default_material;   /* bg_material_init(), added when an object names none */
} bgi_sf_ctx;

#define BGI_SF_TRY(call)              \
    do {                              \
        bg_status st_ = (call);       \
        if (st_ != BG_OK)             \
            return st_;               \
    } while (0)

/* Lets the compiler check the arguments of the printf-like sinks below against their formats. */
#if defined(__GNUC__)
#define BGI_SF_PRINTF_(format_arg, first_arg) __attribute__((__format__(__printf__, format_arg, first_arg)))
#else
#define BGI_SF_PRINTF_(format_arg, first_arg)
#endif

/* ---- context.c ---- */
void bgi_sf_ctx_init(bgi_sf_ctx *ctx, const char *file, const bg_scenefile_desc *desc, bg_scene *scene,
                     bg_scenefile_result *out, char *message, size_t message_size);
void bgi_sf_ctx_free(bgi_sf_ctx *ctx);
/* Records "FILE: PATH: reason" (the first failure only), logs it and returns status. */
bg_status bgi_sf_fail(bgi_sf_ctx *ctx, bg_status status, const char *format, ...) BGI_SF_PRINTF_(3, 4);
/* A scene call's failure: its status, with the scene's own message after the path. */
bg_status bgi_sf_scene_fail(bgi_sf_ctx *ctx, bg_status status, const char *what);
void bgi_sf_warn(bgi_sf_ctx *ctx, const char *format, ...) BGI_SF_PRINTF_(2, 3);
/* Path steps: each returns the length to give bgi_sf_pop to step back. */
size_t bgi_sf_push_key(bgi_sf_ctx *ctx, const char *key);
size_t bgi_sf_push_index(bgi_sf_ctx *ctx, size_t index);
void bgi_sf_pop(bgi_sf_ctx *ctx, size_t length);
/* Joins a relative path to ctx->dir (absolute paths stay) into out (BGI_SF_PATH_MAX). */
bg_status bgi_sf_resolve(bgi_sf_ctx *ctx, const char *path, char *out);
/* A file name value (a string) resolved as bgi_sf_resolve does, into out (BGI_SF_PATH_MAX bytes). */
bg_status bgi_sf_file_path(bgi_sf_ctx *ctx, const cJSON *v, char *out);
/* Sets ctx->dir to the folder of file ("" for a bare name). */
void bgi_sf_set_dir_of(bgi_sf_ctx *ctx, const char *file);
bg_status bgi_sf_names_add(bgi_sf_ctx *ctx, bgi_sf_names *names, const char *name, uint32_t handle);
/* The handle of name, or 0. */
uint32_t bgi_sf_names_find(const bgi_sf_names *names, const char *name);
/* The default material, added at first use. */
bg_status bgi_sf_default_material(bgi_sf_ctx *ctx, uint32_t *out);

/* ---- input.c: every file a load reads ---- */

/* Tells the caller's input callback that path is about to be read. */
void bgi_sf_note_input(bgi_sf_ctx *ctx, const char *path);
/* path opened for reading when it is a regular file (and noted), else BG_ERR_IO with the reason
 * after "what: " (e.g. "model file \"x.ply\": is a directory"); what NULL names nothing (the file is
 * the one the message starts with). */
bg_status bgi_sf_open_input(bgi_sf_ctx *ctx, const char *path, const char *what, FILE **out);

/* ---- image_decode.c: PNG and JPEG bytes to RGBA8 ---- */

/* What an image's first bytes say it is. */
typedef enum bgi_sf_image_format {
    BGI_SF_IMAGE_UNKNOWN = 0,
    BGI_SF_IMAGE_PNG,
    BGI_SF_IMAGE_JPEG,
    BGI_SF_IMAGE_KTX2,
    BGI_SF_IMAGE_WEBP
} bgi_sf_image_format;

bgi_sf_image_format bgi_sf_image_sniff(const unsigned char *data, size_t size);
/* "PNG", "JPEG", "KTX2", "WebP" or "unknown-format", for messages. */
const char *bgi_sf_image_format_name(bgi_sf_image_format format);
/* Decodes a PNG or JPEG held in memory into out: RGBA8, tightly packed, pixels from malloc (the
 * caller frees them). PNG samples are libpng's simplified API's 8-bit sRGB ones (16-bit files
 * rounded), JPEG's are TurboJPEG's; no alpha means opaque. On failure nothing is left allocated and
 * reason says why: BG_ERR_IO for another format or corrupt data, BG_ERR_OUT_OF_MEMORY. */
bg_status bgi_sf_image_decode(const unsigned char *data, size_t size, bg_image *out, char *reason,
                              size_t reason_size);

/* ---- json_scan.c: what cJSON cannot report ---- */

/* The line and column (from 1) of at in text. */
void bgi_sf_line_column(const char *text, const char *at, int *line, int *column);
/* Refuses, by line and column, a text nested deeper than the JSON reader's limit (it would say only
 * "not valid JSON") and a string with an escaped NUL (\u0000), which would cut a name or a path
 * short without a word. */
bg_status bgi_sf_json_scan(bgi_sf_ctx *ctx, const char *text);

/* ---- json_value.c: typed readers of the value at the current path ---- */

/* An interval of allowed numbers; open ends exclude their bound, infinite bounds are no bound. */
typedef struct bgi_sf_range {
    double lo, hi;
    bool lo_open, hi_open;
} bgi_sf_range;

extern const bgi_sf_range bgi_sf_any;      /* every finite number */
extern const bgi_sf_range bgi_sf_nonneg;   /* >= 0 */
extern const bgi_sf_range bgi_sf_positive; /* > 0 */
extern const bgi_sf_range bgi_sf_unit;     /* [0, 1] */

const char *bgi_sf_type_name(const cJSON *v);
/* v must be an object whose keys are all in allowed (NULL-terminated), each given once. */
bg_status bgi_sf_check_object(bgi_sf_ctx *ctx, const cJSON *v, const char *const *allowed);
bg_status bgi_sf_number(bgi_sf_ctx *ctx, const cJSON *v, bgi_sf_range range, double *out);
bg_status bgi_sf_int(bgi_sf_ctx *ctx, const cJSON *v, int lo, int hi, int *out);
bg_status bgi_sf_bool(bgi_sf_ctx *ctx, const cJSON *v, bool *out);
bg_status bgi_sf_string(bgi_sf_ctx *ctx, const cJSON *v, const char **out);
/* An array of exactly n numbers in range. */
bg_status bgi_sf_numbers(bgi_sf_ctx *ctx, const cJSON *v, int n, bgi_sf_range range, double *out);
bg_status bgi_sf_vec3(bgi_sf_ctx *ctx, const cJSON *v, bg_vec3 *out);
/* A colour: a number (grey) or [r, g, b], each in range. */
bg_status bgi_sf_rgb(bgi_sf_ctx *ctx, const cJSON *v, bgi_sf_range range, double out[3]);
/* One of the names (NULL-terminated); out gets its index. */
bg_status bgi_sf_enum(bgi_sf_ctx *ctx, const cJSON *v, const char *const *names, int *out);

/* The same for a member of obj: absent leaves out unchanged. */
const cJSON *bgi_sf_member(const cJSON *obj, const char *key);
bg_status bgi_sf_field_number(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bgi_sf_range range, double *out);
bg_status bgi_sf_field_int(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, int lo, int hi, int *out);
bg_status bgi_sf_field_bool(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bool *out);
bg_status bgi_sf_field_vec3(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bg_vec3 *out);
bg_status bgi_sf_field_rgb(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, bgi_sf_range range, double out[3]);
bg_status bgi_sf_field_enum(bgi_sf_ctx *ctx, const cJSON *obj, const char *key, const char *const *names, int *out);

/* ---- the sections ---- */
bg_status bgi_sf_read_camera(bgi_sf_ctx *ctx, const cJSON *v);
bg_status bgi_sf_read_image(bgi_sf_ctx *ctx, const cJSON *v);
bg_status bgi_sf_read_settings(bgi_sf_ctx *ctx, const cJSON *v);
/* "settings.environment": {"file", "intensity", "light", "sampling"} (environment.c). */
bg_status bgi_sf_read_environment(bgi_sf_ctx *ctx, const cJSON *v);
/* Decodes a Radiance .hdr file (read from its start) into RGBA32F texels to free with
 * bgi_sf_hdr_free, or NULL with the reason in why; w and h get its size. */
float *bgi_sf_hdr_decode(FILE *file, int *w, int *h, char *why, size_t why_size);
void bgi_sf_hdr_free(float *texels);

/* Loads an environment image file (a Radiance .hdr, or a PNG decoded from sRGB) into a texture of the
 * scene; BG_ERR_IO naming the file and the reason (environment.c). */
bg_status bgi_sf_load_environment_image(bgi_sf_ctx *ctx, const char *path, uint32_t *out_texture);
bg_status bgi_sf_read_textures(bgi_sf_ctx *ctx, const cJSON *v);
bg_status bgi_sf_read_materials(bgi_sf_ctx *ctx, const cJSON *v);
bg_status bgi_sf_read_objects(bgi_sf_ctx *ctx, const cJSON *v);
bg_status bgi_sf_read_lights(bgi_sf_ctx *ctx, const cJSON *v);
/* A transform: a list of steps applied in order, or one step ({"matrix": ...} among them). */
bg_status bgi_sf_read_transform(bgi_sf_ctx *ctx, const cJSON *v, bg_mat4 *out);

/* ---- model.c: model files through assimp ---- */

/* How a model's normals are taken. */
typedef enum bgi_sf_normals { BGI_SF_NORMALS_FILE = 0, BGI_SF_NORMALS_SMOOTH, BGI_SF_NORMALS_FLAT } bgi_sf_normals;

typedef struct bgi_sf_model_desc {
    const char *path;         /* resolved */
    bg_mat4 transform;        /* placed before every node's own transform */
    uint32_t material;        /* 0: the file's materials */
    bool casts_shadows;
    bgi_sf_normals normals;
    double smooth_angle;      /* BGI_SF_NORMALS_FILE: > 0 computes a mesh's missing normals, creased above it */
    bool scene_items;         /* also its cameras and lights (a model loaded as the whole scene) */
    int camera;               /* scene_items: bg_scenefile_desc.camera, checked against the file */
} bgi_sf_model_desc;

bg_status bgi_sf_load_model(bgi_sf_ctx *ctx, const bgi_sf_model_desc *desc);

/* ---- normals.c ---- */

/* Normals for a mesh without its own (normals.c): area-weighted sums over the faces at each vertex
 * within angle_degrees of a corner's own face (180: all of them), a vertex copied, with its uv, for
 * each side of a crease. *p and *uv (may point to NULL) are replaced by arrays of *nv vertices when
 * copies are made, idx (3 nt) is rewritten, *n is new. BG_ERR_OUT_OF_MEMORY or BG_ERR_LIMIT (more
 * vertices than 32-bit indices reach) leave the arrays as they were. */
bg_status bgi_sf_crease_normals(float **p, float **uv, size_t *nv, uint32_t *idx, size_t nt, double angle_degrees,
                                float **n);

/* ---- weld.c ---- */

/* Joins the vertices of equal position (and uv, where uv is not NULL), bit for bit, before normals are
 * averaged over shared vertices: p and uv are compacted in place (*nv shrinks), idx (3 nt) rewritten.
 * BG_ERR_OUT_OF_MEMORY leaves everything as it was. */
bg_status bgi_sf_weld_vertices(float *p, float *uv, size_t *nv, uint32_t *idx, size_t nt);

/* ---- desc_options.c: what the caller's desc asks beyond the file ---- */

/* desc's values in range, and none that a JSON scene (model false) cannot take; the failure names
 * the field. desc may be NULL. */
bg_status bgi_sf_check_desc(bgi_sf_ctx *ctx, const bg_scenefile_desc *desc, bool model);
/* The rotation that turns the file's up axis to +y. */
bg_mat4 bgi_sf_up_transform(bg_scenefile_up up);
/* desc's look_from, look_at, fov_y_degrees, aperture_radius and focus_distance over
 * ctx->out->camera; a camera they leave without a direction, or looking along its up, is refused
 * naming them. desc may be NULL. */
bg_status bgi_sf_apply_view(bgi_sf_ctx *ctx, const bg_scenefile_desc *desc);

/* ---- summary.c ---- */
void bgi_sf_summary_reset(bg_scenefile_summary *s);
void bgi_sf_summary_point(bg_scenefile_summary *s, bg_mat4 m, double x, double y, double z);
/* An analytic object of that shape under transform m. */
void bgi_sf_summary_shape(bg_scenefile_summary *s, bg_shape shape, bg_mat4 m);

/* ---- math ---- */
/* The frame bg_scene_add_plane gives a unit normal (docs/shading.md, the plane's planar axes). */
bg_mat4 bgi_sf_plane_frame(bg_vec3 n);
/* n / |n|, computed as the scene library does, so that shorthand planes keep its bits. */
bg_vec3 bgi_sf_normalize(bg_vec3 v);

/* A glTF camera's vertical field of view (radians) from assimp's mHorizontalFOV and mAspect (0: none),
 * by the formula of that assimp version (camera_fov.c). */
double bgi_sf_gltf_fov_y(double horizontal_fov, double aspect, unsigned assimp_major, unsigned assimp_minor);

#endif
