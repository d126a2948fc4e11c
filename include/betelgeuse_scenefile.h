/* Betelgeuse scene files: JSON scenes (docs/scene_format.md) and model files (OBJ with MTL, PLY, STL,
 * glTF 2.0 and whatever else assimp reads) loaded into a caller's bg_scene, with the camera, image
 * size and render settings a command needs to render them.
 *
 * A library of its own (libbetelgeuse_scenefile, pkg-config betelgeuse_scenefile) so that
 * libbetelgeuse keeps its dependencies: this one adds cJSON and assimp. It fills the scene through
 * the public API of betelgeuse.h only.
 *
 * Errors: every loader returns a bg_status and writes a message into the caller's buffer (when not
 * NULL) of the form "FILE: JSON.PATH: reason", e.g.
 *     scene.json: objects[3].sphere.radius: must be > 0 (got -1)
 * Bad input (bad JSON, wrong types, unknown keys, out-of-range or non-finite values, unknown
 * material or texture names) is BG_ERR_INVALID_ARGUMENT; a file that cannot be read (the scene, a
 * texture, a model) is BG_ERR_IO; BG_ERR_OUT_OF_MEMORY and BG_ERR_LIMIT come from the scene. The
 * message also goes to the logger at BG_LOG_ERROR; the library never prints. On failure the scene
 * may hold part of what the file adds (destroy it); on success it is committed.
 */
#ifndef BETELGEUSE_SCENEFILE_H
#define BETELGEUSE_SCENEFILE_H

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#include "betelgeuse.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Told of each file a load reads, before it is read: the scene or model file itself, the textures,
 * and the files a model names (an OBJ's MTL, a glTF's buffers and images). A command uses it to
 * refuse an output path that would overwrite one of its inputs. path lives for the call only. */
typedef void (*bg_scenefile_input_fn)(const char *path, void *user);

typedef struct bg_scenefile_inputs {
    bg_scenefile_input_fn func;
    void *user;
} bg_scenefile_inputs;

/* Which axis of a model file points up. The renderer's up is +y, glTF's convention; a file written
 * Z-up (CAD exports, many scans) would lie on its side, so it is turned to stand on +y. */
typedef enum bg_scenefile_up {
    BG_SCENEFILE_UP_DEFAULT = 0, /* +y: the file as it is */
    BG_SCENEFILE_UP_Y,           /* +y, said explicitly */
    BG_SCENEFILE_UP_Z,           /* +z up, -y to the front (Blender's axes): turned -90 degrees about x */
    BG_SCENEFILE_UP_NEG_Y,       /* -y up: turned 180 degrees about x */
    BG_SCENEFILE_UP_NEG_Z,       /* -z up: turned +90 degrees about x */
    BG_SCENEFILE_UP_COUNT_       /* not an axis: the number of values */
} bg_scenefile_up;

/* bg_scenefile_desc.camera: the camera framing the bounds even when the file has cameras. */
#define BG_SCENEFILE_CAMERA_FRAME (-1)

/* Defaults: no logger; base_dir NULL (the current folder); name NULL ("<string>"); no input
 * callback; a model as its file has it (+y up, the file's normals or flat faces, its first camera or
 * one framing it); the camera as the file gives it.
 *
 * up_axis, smooth_angle_degrees and camera apply to model files (bg_scenefile_load_model); a JSON
 * scene given any of them is refused (its meshes have "transform" and "normals" of their own).
 * look_from, look_at, fov_y_degrees, aperture_radius and focus_distance apply to both, after the
 * camera is chosen. A bad value is BG_ERR_INVALID_ARGUMENT with the field named ("desc->camera: ..."). */
typedef struct bg_scenefile_desc {
    bg_logger logger;     /* errors (BG_LOG_ERROR) and what a model's materials lose (BG_LOG_WARNING) */
    const char *base_dir; /* bg_scenefile_load_string only: the folder relative paths resolve
                             against (file loads use the scene file's own folder) */
    const char *name;     /* bg_scenefile_load_string only: the text's name in messages */
    bg_scenefile_inputs inputs; /* each file read, as it is opened */
    bg_scenefile_up up_axis;    /* the model's root turned first, so that the framing camera sees the
                                   turned bounds and the file's cameras and lights turn with it */
    double smooth_angle_degrees; /* 0: a mesh without normals stays flat-faceted, as its file says;
                                    (0, 180]: normals computed for meshes without their own, averaged
                                    over the faces at a vertex whose normals differ from the face's by
                                    at most this (a sharper edge keeps a crease); 180: fully smooth */
    int camera;           /* 0: the file's first camera, else one framing the bounds; N >= 1: the
                             file's Nth camera (more than it has is an error); BG_SCENEFILE_CAMERA_FRAME */
    const bg_vec3 *look_from; /* not NULL: replaces the chosen camera's position */
    const bg_vec3 *look_at;   /* not NULL: replaces the point it looks at */
    double fov_y_degrees;     /* 0: the chosen camera's; else in (0, 180), replacing it (the framing
                                 camera keeps the model in view at this angle); refused for an
                                 orthographic camera, which has no angle to set */
    /* The thin lens (bg_camera): pointers, since 0 is a value to ask for (the pinhole; in focus at
       look_at) and so cannot also mean "the file's". */
    const double *aperture_radius; /* not NULL: finite and >= 0, replacing the camera's */
    const double *focus_distance;  /* not NULL: finite and >= 0, replacing the camera's */
} bg_scenefile_desc;

/* The image a scene asks for. Defaults: 640 x 480, 1 sample per pixel. samples is the scene's wish:
 * the caller passes it on to the renderer's settings where they have a field for it. */
typedef struct bg_scenefile_image {
    int width, height; /* 1 .. 16384 */
    int samples;       /* 1 .. BG_MAX_SAMPLES (256), what the renderers take */
} bg_scenefile_image;

/* What was loaded, for a command's `info`: counts over the items the loader added, and the world
 * box of the bounded objects (every analytic shape but the plane, every mesh vertex). */
typedef struct bg_scenefile_summary {
    size_t objects;      /* analytic objects and mesh objects, instances included */
    size_t meshes;       /* mesh objects (instances included) */
    uint64_t triangles;  /* summed over the mesh objects (an instance counts its triangles again) */
    uint64_t vertices;   /* summed the same way, as the mesh objects hold them (after welding and creases) */
    size_t lights;
    size_t materials;
    size_t textures;
    bool unbounded;      /* a plane is in the scene (it is not in the box) */
    bool bounded;        /* some object is bounded: bounds_min and bounds_max hold its box */
    bg_vec3 bounds_min, bounds_max;
} bg_scenefile_summary;

/* A loaded scene's settings; caller-owned, filled by the loaders (the scene itself holds the
 * objects, materials, textures, lights, camera and ambient light). */
typedef struct bg_scenefile_result {
    bg_camera camera;              /* also set on the scene */
    bg_scenefile_image image;
    bg_render_settings settings;   /* bg_render_settings_init() with the file's max_depth,
                                      background, encoding, integrator and path_ambient */
    double ambient[3];             /* also set on the scene */
    bool camera_from_file;         /* false: the default camera (JSON) or one framing the bounds (model) */
    int file_cameras;              /* the cameras the file holds (a JSON scene: 1 with "camera", else 0) */
    int camera_number;             /* which of them is the camera, from 1; 0: none (framing or default) */
    bool lights_from_file;         /* false for a model without lights: a default light was added */
    bg_scenefile_summary summary;
} bg_scenefile_result;

/* Loads a JSON scene file (docs/scene_format.md) into scene, which should be empty. */
BG_API bg_status bg_scenefile_load(const char *path, const bg_scenefile_desc *desc, bg_scene *scene,
                                   bg_scenefile_result *out, char *message, size_t message_size);
/* The same from JSON text (tests, generated scenes); desc->base_dir and desc->name apply. */
BG_API bg_status bg_scenefile_load_string(const char *text, const bg_scenefile_desc *desc, bg_scene *scene,
                                          bg_scenefile_result *out, char *message, size_t message_size);
/* Loads a model file (OBJ, PLY, STL, glTF 2.0, ...) as a whole scene: its meshes with their materials
 * (docs/scene_format.md, "Model files"), its first camera (or desc->camera) and its lights where it
 * has them, else a camera framing its bounds and one point light; the image's aspect follows the
 * file's camera. */
BG_API bg_status bg_scenefile_load_model(const char *path, const bg_scenefile_desc *desc, bg_scene *scene,
                                         bg_scenefile_result *out, char *message, size_t message_size);
/* Loads either: a path ending in ".json" (any case) as a scene file, any other as a model file. */
BG_API bg_status bg_scenefile_load_any(const char *path, const bg_scenefile_desc *desc, bg_scene *scene,
                                       bg_scenefile_result *out, char *message, size_t message_size);

#ifdef __cplusplus
}
#endif

#endif
