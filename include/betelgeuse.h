/* Betelgeuse: Whitted ray tracing through OpenGL 2.1, with a double-precision CPU reference.
 *
 * A scene is created, filled and committed (Embree style). Both renderers read only committed
 * state, so a scene that failed validation halfway still renders what was last committed.
 * Every fallible call returns a bg_status; the scene keeps the first error and its message until
 * it is cleared. The library never prints: diagnostics go to the optional logger.
 *
 * Conventions: right-handed world, y up by default (the camera's up vector decides); angles in
 * degrees; colours are linear RGB; matrices are row-major, m[row][col], and transform column
 * vectors (p' = M p), so bg_mat4_mul(a, b) applies b first.
 *
 * Handles (object, material, texture, light ids) are non-zero 32-bit numbers; 0 is never a valid
 * handle and means "none". A scene that never removes anything hands out 1, 2, 3, ... per kind, in
 * the order of the adds. Each handle names one item for good: after bg_scene_remove_* every call
 * given the removed handle fails with BG_ERR_INVALID_ARGUMENT ("... = 0x01000003 was removed"),
 * also once a later item reuses its storage (that item gets a different handle). Treat handles as
 * opaque beyond that (the low 24 bits are a slot, the high 8 bits count its reuses).
 */
#ifndef BETELGEUSE_H
#define BETELGEUSE_H

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#include "macs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Marks the public functions, as MACS_API does in macs.h: exactly these are exported. */
#ifndef BG_API
#if defined(__GNUC__) && __GNUC__ >= 4
#define BG_API __attribute__((visibility("default")))
#else
#define BG_API
#endif
#endif

/* ---- status ------------------------------------------------------------------------------- */

/* Every status with its default message, one list. */
#define BG_STATUS_LIST(X)                                                              \
    X(BG_OK, 0, "ok")                                                                  \
    X(BG_ERR_INVALID_ARGUMENT, 1, "invalid argument")                                  \
    X(BG_ERR_OUT_OF_MEMORY, 2, "out of memory")                                        \
    X(BG_ERR_IO, 3, "file input/output failed")                                        \
    X(BG_ERR_NOT_COMMITTED, 4, "the scene has no committed state")                     \
    X(BG_ERR_GL, 5, "the GPU renderer failed (see the message)")                       \
    X(BG_ERR_LIMIT, 6, "a hardware or library limit was exceeded")                     \
    X(BG_ERR_THREAD, 7, "a worker thread could not be started")                        \
    X(BG_ERR_GPU_OUT_OF_MEMORY, 8, "the GPU ran out of memory")                       \
    X(BG_ERR_CANCELLED, 9, "the render was cancelled by its progress callback")

/* Result of every fallible call; BG_OK is 0. */
typedef enum bg_status {
#define BG_STATUS_ENUM_(name, value, message) name = value,
    BG_STATUS_LIST(BG_STATUS_ENUM_)
#undef BG_STATUS_ENUM_
    BG_STATUS_COUNT_
} bg_status;

/* The default message of a status ("unknown status" for values outside the list). */
BG_API const char *bg_status_string(bg_status status);

/* ---- logging and allocation ---------------------------------------------------------------- */

/* Severity of a logged message; the same values as MACS's macs_log_level. */
typedef enum bg_log_level { BG_LOG_ERROR = 0, BG_LOG_WARNING, BG_LOG_INFO, BG_LOG_DEBUG } bg_log_level;

/* Receives diagnostics; the library never prints on its own. message lives for the call only. */
typedef void (*bg_log_fn)(bg_log_level level, const char *message, void *user);

/* Where diagnostics go: func NULL (the default) drops them; user is passed through. */
typedef struct bg_logger {
    bg_log_fn func;
    void *user;
} bg_logger;

/* Allocation hooks; all NULL means the C library's malloc, realloc and free. Otherwise alloc and
 * free must both be set; realloc is optional (without it the library allocates, copies, frees). */
typedef struct bg_allocator {
    void *(*alloc)(size_t size, void *user);
    void *(*realloc)(void *ptr, size_t size, void *user);
    void (*free)(void *ptr, void *user);
    void *user;
} bg_allocator;

/* ---- small math ---------------------------------------------------------------------------- */

typedef struct bg_vec3 { double x, y, z; } bg_vec3;
typedef struct bg_mat4 { double m[4][4]; } bg_mat4;

/* Shorthand for a bg_vec3 literal. */
BG_API bg_vec3 bg_vec3_make(double x, double y, double z);
/* The identity transform. */
BG_API bg_mat4 bg_mat4_identity(void);
/* A translation by (x, y, z). */
BG_API bg_mat4 bg_mat4_translate(double x, double y, double z);
/* A scale by (x, y, z) about the origin. */
BG_API bg_mat4 bg_mat4_scale(double x, double y, double z);
/* A right-handed rotation by angle_degrees about axis (normalised inside; a zero axis gives identity). */
BG_API bg_mat4 bg_mat4_rotate(bg_vec3 axis, double angle_degrees);
/* The product a * b: applying the result applies b first, then a. */
BG_API bg_mat4 bg_mat4_mul(bg_mat4 a, bg_mat4 b);

/* ---- images -------------------------------------------------------------------------------- */

typedef enum bg_pixel_format {
    BG_PIXEL_RGBA8 = 0, /* 8 bits per channel, encoded as the render settings say (sRGB by default) */
    BG_PIXEL_RGBA32F    /* linear float radiance, unclamped */
} bg_pixel_format;

/* A caller-owned image: the library reads or writes pixels, never allocates or frees them.
 * stride is the distance between rows in bytes; 0 means tightly packed. */
typedef struct bg_image {
    int width, height;
    bg_pixel_format format;
    size_t stride;
    void *pixels;
} bg_image;

/* Reads only the size of a PNG file (its header), so the caller can allocate. */
BG_API bg_status bg_png_size(const char *path, int *width, int *height, char *message, size_t message_size);
/* Reads a PNG of any colour type, depth and interlace into a caller-owned image of exactly its size,
 * keeping the file's encoding (gamma and colour chunks are not applied; grey and palettes become
 * RGB, no alpha means opaque). RGBA8 stores 8-bit samples as they are, 1-, 2- and 4-bit ones scaled
 * to 0..255, 16-bit ones as round(v / 257); RGBA32F stores every sample divided by 255 (65535 for
 * 16-bit files), still encoded. Missing or corrupt files give BG_ERR_IO naming the path and why. */
BG_API bg_status bg_png_load(const char *path, bg_image *image, char *message, size_t message_size);
/* Writes an image as an 8-bit RGBA PNG; RGBA32F images are clamped to [0, 1] and scaled by 255. */
BG_API bg_status bg_png_save(const char *path, const bg_image *image, char *message, size_t message_size);

/* ---- scene --------------------------------------------------------------------------------- */

typedef struct bg_scene bg_scene;

/* Defaults: no logger, the C library's allocator. */
typedef struct bg_scene_desc {
    bg_logger logger;
    bg_allocator allocator;
} bg_scene_desc;

/* Creates an empty scene (no objects, no lights, a default camera); desc may be NULL. */
BG_API bg_status bg_scene_create(const bg_scene_desc *desc, bg_scene **out_scene);
/* Frees the scene and everything it owns; NULL is ignored. */
BG_API void bg_scene_destroy(bg_scene *scene);
/* The first error since the last clear (BG_OK if none). */
BG_API bg_status bg_scene_error(const bg_scene *scene);
/* The message of the first error, naming the field and object ("" if none). */
BG_API const char *bg_scene_error_message(const bg_scene *scene);
/* Forgets the stored error. */
BG_API void bg_scene_clear_error(bg_scene *scene);

/* How camera rays leave the camera: from one point (a perspective view, fov_y_degrees), or parallel
 * along the view direction from a rectangle across it (an orthographic view, half_height), as CAD
 * and technical drawings show a model. */
typedef enum bg_projection { BG_PROJECTION_PERSPECTIVE = 0, BG_PROJECTION_ORTHOGRAPHIC } bg_projection;

/* The camera: a pinhole, or a thin lens for depth of field (docs/shading.md 1.4), or an orthographic
 * view (docs/shading.md 1.5). Defaults (bg_camera_init): at (0, 0, 5) looking at the origin, up
 * (0, 1, 0), perspective with a vertical field of view of 45 degrees, a pinhole; half_height 1 for
 * an orthographic view. The aspect ratio comes from the image size. A lens of aperture_radius > 0 sits
 * at position, across the view; each camera sample passes through its own point of the lens
 * (stratified and scrambled, docs/shading.md 1.3) towards where the pinhole ray meets the plane in
 * focus, focus_distance ahead along the view direction, so points on that plane stay sharp and the
 * others blur into discs (the thin-lens circle of confusion). The blur converges as samples add up:
 * settings.samples, or an accumulation. */
typedef struct bg_camera {
    bg_vec3 position;
    bg_vec3 look_at;
    bg_vec3 up;
    double fov_y_degrees;   /* in (0, 180) */
    double aperture_radius; /* the lens radius in world units, finite and >= 0; 0 = the pinhole, the
                               image of a camera without a lens bit for bit */
    double focus_distance;  /* finite and >= 0; 0 = |look_at - position| (the plane through look_at) */
    bg_projection projection; /* ORTHOGRAPHIC: rays parallel to look_at - position, leaving the plane
                                 through position across the view; no lens (aperture_radius 0) */
    double half_height;     /* ORTHOGRAPHIC: half the view's height in world units, in [1e-100, 1e100];
                               its half-width is half_height times the image's aspect ratio */
} bg_camera;

/* The default camera described above. */
BG_API bg_camera bg_camera_init(void);
/* Sets the camera; rejects non-finite values, look_at == position, up parallel to the view. */
BG_API bg_status bg_scene_set_camera(bg_scene *scene, const bg_camera *camera);

/* ---- textures ------------------------------------------------------------------------------ */

typedef enum bg_texture_wrap { BG_WRAP_REPEAT = 0, BG_WRAP_CLAMP } bg_texture_wrap;

/* How a texel is read between texel centres (docs/shading.md 5): bilinear over the four nearest
 * (GL_LINEAR), or the one texel the point falls in (GL_NEAREST: pixel art, masks, checkers). */
typedef enum bg_texture_filter { BG_FILTER_LINEAR = 0, BG_FILTER_NEAREST } bg_texture_filter;

typedef enum bg_texture_encoding {
    BG_TEXTURE_SRGB = 0, /* colour data: RGBA8 texels are decoded from sRGB to linear where they are
                            sampled, before filtering (docs/shading.md 5) */
    BG_TEXTURE_LINEAR    /* data (roughness, masks): texels are used as stored, RGBA8 divided by 255 */
} bg_texture_encoding;

/* Defaults: repeat, sRGB colour data, linear filtering. RGBA32F images are taken as linear whatever
 * the encoding; their texels must be finite and >= 0. */
typedef struct bg_texture_desc {
    bg_texture_wrap wrap;
    bg_texture_encoding encoding;
    bg_texture_filter filter;
} bg_texture_desc;

/* Copies a caller image into the scene as a texture at its own precision (docs/shading.md 5.2): an
 * RGBA8 image stays 4 bytes a texel on the host and on the GPU, an RGBA32F one 16; desc may be NULL. */
BG_API bg_status bg_scene_add_texture(bg_scene *scene, const bg_image *image, const bg_texture_desc *desc,
                                      uint32_t *out_texture);
/* Removes a texture; refused (BG_ERR_INVALID_ARGUMENT, naming the material and field) while a
 * material still references it, also through an unused coat. Takes effect at the next commit. */
BG_API bg_status bg_scene_remove_texture(bg_scene *scene, uint32_t texture);
/* Loads a PNG file as a texture: its samples as bg_png_load keeps them, decoded as desc says like an
 * RGBA8 image's (an 8-bit file stays 4 bytes a texel), except that 16-bit files keep all 16 bits
 * (v / 65535 is decoded, into 16-byte linear float texels); missing or corrupt files give BG_ERR_IO
 * naming the path and why. */
BG_API bg_status bg_scene_load_texture_png(bg_scene *scene, const char *path, const bg_texture_desc *desc,
                                           uint32_t *out_texture);

/* ---- materials ----------------------------------------------------------------------------- */

/* A colour property: the constant, multiplied texel by texel with the texture's RGB when texture
 * is non-zero. */
typedef struct bg_color_param {
    double r, g, b;
    uint32_t texture;
} bg_color_param;

/* A scalar property: the constant, multiplied by one channel (0..3) of the texture when texture
 * is non-zero. */
typedef struct bg_scalar_param {
    double value;
    uint32_t texture;
    int channel;
} bg_scalar_param;

/* One layer of Schlick's 1994 model: reflectance at normal incidence C, roughness r in [0, 1]
 * (0 perfect mirror, 1 Lambertian), isotropy p in [0, 1] (0 fully anisotropic, 1 isotropic). */
typedef struct bg_schlick_layer {
    bg_color_param reflectance;
    bg_scalar_param roughness;
    bg_scalar_param isotropy;
} bg_schlick_layer;

/* The sides of a mesh's triangles that rays meet. The front is the side its corners are seen
 * counter-clockwise from in the mesh's own space: a mirroring transform keeps it the front (in
 * world space it is then the clockwise side, as glTF has it for a negative determinant). */
typedef enum bg_mesh_sides {
    BG_SIDES_SOLID = 0, /* both: the mesh is a closed solid, and a ray that meets a back is inside it
                         * (unlit by direct light; refraction leaves there) */
    BG_SIDES_FRONT,     /* only fronts: a ray that meets a back passes through, for every ray, as a
                         * rasteriser culls back faces (glTF's doubleSided false) */
    BG_SIDES_BOTH,      /* both, as an open surface: a back is shaded as a front facing the ray,
                         * and transparency passes light straight on, as through a plane (glTF's
                         * doubleSided true) */
    BG_SIDES_COUNT_
} bg_mesh_sides;

/* A material. docs/shading.md gives every formula. The perfectly specular share of a layer
 * (roughness below 1/2) is traced as a mirror ray; transparency in [0, 1] blends in a dielectric
 * interface of index ior (> 0) with exact Fresnel weights and total internal reflection.
 * Defaults (bg_material_init): a white Lambertian base (C = 0.8, r = 1, p = 1), no coat,
 * ambient (0.1, 0.1, 0.1), no emission, opaque, ior 1.5, coverage 1 read from a texture's alpha
 * (channel 3) with no cut-out, meshes as closed solids. */
typedef struct bg_material {
    bg_schlick_layer base;
    bool has_coat;           /* the two-layer form: coat is a glossy layer over the base */
    bg_schlick_layer coat;
    bg_color_param ambient;  /* multiplies the scene's ambient light */
    bg_color_param emission; /* added as is */
    bg_scalar_param transparency;
    double ior;
    /* A cut-out (glTF's alphaMode MASK), on mesh objects: where the coverage (value times one channel
     * of its texture, read at the mesh's texture coordinates like every other parameter) is below
     * coverage_cutoff, the surface is not there for any ray, shadow rays included. coverage_cutoff
     * in [0, 1]; 0 (the default) cuts nothing and leaves coverage unread. */
    bg_scalar_param coverage;
    double coverage_cutoff;
    /* Which sides of a mesh object's triangles are there (the analytic shapes ignore it). */
    bg_mesh_sides sides;
    /* Glossy reflection (docs/shading.md 9.1): the reflected ray (the specular share, and a
     * transparent interface's reflection) leaves, at each camera sample, in a direction drawn from
     * the lobe of the roughness, the coat's if the material has one, else the base's: Schlick's zenith
     * factor Z(t) / pi (the GGX distribution of alpha^2 = r) over the mirror's normal. The blur
     * converges as samples add up. false (the default): a perfect mirror; roughness 0 is a perfect
     * mirror either way, bit for bit. Transmitted rays stay sharp. */
    bool glossy;
} bg_material;

/* The default material described above. */
BG_API bg_material bg_material_init(void);
/* Adds a material; every field is validated and the message names the first bad one. */
BG_API bg_status bg_scene_add_material(bg_scene *scene, const bg_material *material, uint32_t *out_material);
/* Replaces a material's values (cheap re-commit: no new geometry). */
BG_API bg_status bg_scene_set_material(bg_scene *scene, uint32_t material, const bg_material *values);
/* Removes a material; refused (BG_ERR_INVALID_ARGUMENT, naming the object) while an object still
 * uses it. Takes effect at the next commit. */
BG_API bg_status bg_scene_remove_material(bg_scene *scene, uint32_t material);

/* ---- objects ------------------------------------------------------------------------------- */

/* Every primitive is convex and is its prototype placed by an affine transform:
 *   SPHERE     unit sphere at the origin
 *   PLANE      the infinite plane y = 0, front side +y
 *   BOX        the cube [-1, 1]^3
 *   CYLINDER   radius 1 about the y axis, y in [-1, 1], capped
 *   RECTANGLE  the square [-1, 1] x [-1, 1] in the plane y = 0, front side +y */
typedef enum bg_shape {
    BG_SHAPE_SPHERE = 0,
    BG_SHAPE_PLANE,
    BG_SHAPE_BOX,
    BG_SHAPE_CYLINDER,
    BG_SHAPE_RECTANGLE,
    BG_SHAPE_COUNT_
} bg_shape;

/* How an object maps its prototype hit point to texture coordinates (docs/shading.md). */
typedef enum bg_uv_mapping {
    BG_UV_DEFAULT = 0,  /* the shape's natural one: sphere spherical, plane and rectangle planar,
                           box per face, cylinder cylindrical */
    BG_UV_SPHERICAL,
    BG_UV_PLANAR,
    BG_UV_BOX,
    BG_UV_CYLINDRICAL,
    BG_UV_COUNT_
} bg_uv_mapping;

/* Defaults (bg_object_desc_init): identity transform, the default UV mapping with scale (1, 1),
 * casts shadows. material must name a material of the scene. transform must be finite and affine
 * (bottom row 0 0 0 1). Its linear part L has the overall scale s = |L|_F / sqrt 3 (the radius of a
 * sphere, the half size of a cube), which must lie in [1e-100, 1e100], so that the inverse (at most
 * about 1e13 / s) and the squares the renderers form from object-space rays stay far inside the
 * double range; and it must be non-singular for that scale: |det(L / s)| >= 1e-12, computed on
 * L / s so that no scale in range overflows it, a test that ignores overall scale and rotation but
 * rejects slabs thinner than 1e-12 of their size.
 * Its inverse and the object's world box must be finite in double (a translation near the double
 * range can break either). Every add and set_transform runs the very checks a commit runs, so an
 * accepted object never makes a commit fail. */
typedef struct bg_object_desc {
    bg_shape shape;
    bg_mat4 transform;
    uint32_t material;
    bg_uv_mapping uv_mapping;
    double uv_scale[2];  /* texture repeats per prototype square [-1, 1]^2 (planar, box) or per turn
                            (spherical, cylindrical longitude); > 0 */
    bool casts_shadows;
} bg_object_desc;

/* The default object of a shape, described above. */
BG_API bg_object_desc bg_object_desc_init(bg_shape shape, uint32_t material);
/* Adds an object; transforms outside the rules above, unknown shapes or materials are rejected
 * (meshes are added by bg_scene_add_mesh below, never through bg_object_desc). */
BG_API bg_status bg_scene_add_object(bg_scene *scene, const bg_object_desc *desc, uint32_t *out_object);
/* Shorthand: a sphere of the given centre and radius, in [1e-100, 1e100] (the scale rule above). */
BG_API bg_status bg_scene_add_sphere(bg_scene *scene, bg_vec3 center, double radius, uint32_t material,
                                     uint32_t *out_object);
/* Shorthand: the plane through point with the given normal (non-zero); its planar UV axes are
 * chosen from the normal as docs/shading.md says. */
BG_API bg_status bg_scene_add_plane(bg_scene *scene, bg_vec3 point, bg_vec3 normal, uint32_t material,
                                    uint32_t *out_object);
/* A triangle mesh (docs/shading.md 2.10). The scene copies every array at add; the caller may free
 * them after the call. The mesh is a closed solid: counter-clockwise seen from outside is the front,
 * and a ray that meets a back face is inside (refraction enters at front faces, leaves at back ones;
 * direct light reaches front faces only, as it reaches closed shapes only from outside), so an open
 * mesh such as a terrain is lit from its front side. Degenerate triangles (repeated or collinear
 * vertices) are kept and never hit.
 * Defaults (bg_mesh_desc_init): no arrays (they must be set), identity transform, casts shadows.
 * Rules, each refused by bg_scene_add_mesh with BG_ERR_INVALID_ARGUMENT naming the field:
 * - positions and indices non-NULL, triangle_count > 0, every index < vertex_count (the message
 *   names the triangle and the index), every position, normal and uv finite (naming the vertex);
 * - normals and uvs may be NULL: face normals, and no texture coordinates (uv (0, 0) everywhere,
 *   and tangents from the shapes' fallback rule, docs/shading.md 3);
 * - transform and material follow bg_object_desc's rules;
 * - counts whose byte sizes overflow size_t, more than 2^23 triangles (the mesh tree's limit) or
 *   more than 2^32 - 1 vertices are BG_ERR_LIMIT.
 * Both renderers draw meshes, the GPU renderer in every plan (bg_gpu_plan). */
typedef struct bg_mesh_desc {
    const float *positions;    /* 3 per vertex */
    size_t vertex_count;
    const uint32_t *indices;   /* 3 per triangle, counter-clockwise = front */
    size_t triangle_count;
    const float *normals;      /* optional, 3 per vertex: smooth shading; NULL = face normals */
    const float *uvs;          /* optional, 2 per vertex; NULL = no texture coordinates */
    bg_mat4 transform;
    uint32_t material;
    bool casts_shadows;
} bg_mesh_desc;

/* The default mesh description of a material, described above. */
BG_API bg_mesh_desc bg_mesh_desc_init(uint32_t material);
/* Adds a mesh object: copies the arrays and builds the mesh's own tree over its triangles (at add,
 * so that commit never fails on it and its cost stays out of commits). */
BG_API bg_status bg_scene_add_mesh(bg_scene *scene, const bg_mesh_desc *desc, uint32_t *out_object);
/* Adds another object showing the triangles of mesh_object (an object added by bg_scene_add_mesh
 * or by this call) with its own transform (bg_object_desc's rules), material and shadow flag. The
 * triangles and their tree are shared, not copied, and live while any object uses them: removing
 * the original keeps its instances working. A thousand copies of a model cost one mesh plus a
 * thousand small objects:
 *     uint32_t ids[1000];
 *     bg_scene_add_mesh(scene, &desc, &ids[0]);
 *     for (int i = 1; i < 1000; i++) {
 *         bg_mat4 m = bg_mat4_translate(i % 10, i / 100, (i / 10) % 10);
 *         bg_scene_add_mesh_instance(scene, ids[0], &m, desc.material, true, &ids[i]);
 *     }
 * mesh_object not a mesh object (an analytic shape) is BG_ERR_INVALID_ARGUMENT. */
BG_API bg_status bg_scene_add_mesh_instance(bg_scene *scene, uint32_t mesh_object, const bg_mat4 *transform,
                                            uint32_t material, bool casts_shadows, uint32_t *out_object);
/* Moves an object (cheap re-commit); the transform is checked as bg_object_desc says. */
BG_API bg_status bg_scene_set_transform(bg_scene *scene, uint32_t object, const bg_mat4 *transform);
/* Removes an object. Like every pending change it takes effect at the next commit: until then
 * both renderers still draw the last committed scene, object included. */
BG_API bg_status bg_scene_remove_object(bg_scene *scene, uint32_t object);

/* ---- lights -------------------------------------------------------------------------------- */

/* The kinds of light (docs/shading.md 7). The area lights (sphere and rectangle) cast soft shadows:
 * each camera sample lights a point with one point of the light's shape, chosen for that pixel and
 * sample by a stratified, scrambled pattern (docs/shading.md 1.3), so n samples send n distinct
 * shadow rays to each area light and the penumbra converges as samples add up. The shapes light the
 * scene; with bg_light.visible they are drawn too. */
typedef enum bg_light_type {
    BG_LIGHT_POINT = 0,
    BG_LIGHT_DIRECTIONAL,
    BG_LIGHT_SPHERE,    /* a ball of the given radius about position; each sample is a point light
                           on the part of the sphere seen from the lit point, uniform in the solid
                           angle it covers there. Radius 0 is BG_LIGHT_POINT, bit for bit */
    BG_LIGHT_RECTANGLE, /* the parallelogram position + a edge_u + b edge_v, a and b in [0, 1],
                           shining from its front, the side edge_u x edge_v points to; each sample is
                           a point light on it, uniform in area, whose radiance is scaled by the cosine
                           between that normal and the direction to the lit point (a Lambertian panel;
                           with attenuation (0, 0, 1) exactly an emitter of radiance
                           color * intensity / area). No spot cone */
    BG_LIGHT_TYPE_COUNT_
} bg_light_type;

/* Defaults (bg_light_init): a white point light of intensity 1 at (0, 0, 0), attenuation
 * (1, 0, 0) (none), no spot cone (spot_cutoff_degrees 180), radius 0, edges (1, 0, 0) and
 * (0, 0, 1) (a unit square facing down, for a rectangle). Radiance arriving from a point light
 * is color * intensity * spot / (constant + linear d + quadratic d^2); a directional light has
 * no attenuation and shines along direction; an area light's sample is a point light at the
 * sample point (the distance d and the spot factor taken from there). */
typedef struct bg_light {
    bg_light_type type;
    bg_vec3 position;   /* point lights; a sphere light's centre; a rectangle light's corner */
    bg_vec3 direction;  /* directional lights, and the axis of a spot cone; non-zero where used */
    double color[3];
    double intensity;
    double attenuation[3];       /* constant, linear, quadratic; >= 0, not all 0 */
    double spot_cutoff_degrees;  /* (0, 90], or 180 for no cone (rectangle lights: 180) */
    double spot_exponent;        /* >= 0 */
    double radius;               /* sphere lights: finite, in [0, 1e100] */
    bg_vec3 edge_u, edge_v;      /* rectangle lights: finite, not parallel (|edge_u x edge_v| at
                                    least 1e-12 |edge_u| |edge_v|) */
    bool visible;                /* area lights: false (the default) lights the scene unseen; true
                                    also draws the shape for camera, mirror and refracted rays,
                                    glowing with color * intensity (black otherwise) and casting no
                                    shadow, so the light's own shadow rays pass it (an object of the
                                    committed scene that no handle names; spheres below radius 1e-100
                                    are not drawn) */
} bg_light;

/* The default light described above. */
BG_API bg_light bg_light_init(void);
/* Adds a light; every field is validated. */
BG_API bg_status bg_scene_add_light(bg_scene *scene, const bg_light *light, uint32_t *out_light);
/* Replaces a light's values (cheap re-commit). */
BG_API bg_status bg_scene_set_light(bg_scene *scene, uint32_t light, const bg_light *values);
/* Removes a light; it takes effect at the next commit. */
BG_API bg_status bg_scene_remove_light(bg_scene *scene, uint32_t light);
/* Sets the scene's ambient light colour (linear, >= 0; default (1, 1, 1)); each material's
 * ambient colour multiplies it. */
BG_API bg_status bg_scene_set_ambient(bg_scene *scene, const double rgb[3]);

/* ---- environment --------------------------------------------------------------------------- */

/* How an environment that lights the scene picks its direction at each camera sample. */
typedef enum bg_environment_sampling {
    BG_ENVIRONMENT_IMPORTANCE = 0, /* in proportion to each texel's luminance times its solid angle
                                      (uniform where the image is black everywhere) */
    BG_ENVIRONMENT_UNIFORM,        /* uniform over the sphere of directions */
    BG_ENVIRONMENT_SAMPLING_COUNT_
} bg_environment_sampling;

/* An equirectangular image around the scene (docs/shading.md 7.1): rays that meet nothing see it in
 * place of settings.background, at every bounce, and it may light the scene as a distant light.
 * The image's centre column looks along -z, its top row straight up (+y), its left and right edges
 * meet behind (+z); use BG_WRAP_REPEAT for the texture, so that the seam blends across. Defaults
 * (bg_environment_init): none (texture 0), intensity 1, lighting off, importance sampling. */
typedef struct bg_environment {
    uint32_t texture;   /* a texture of the scene (bg_scene_add_texture: linear RGBA32F for HDR
                           images); 0 = no environment: misses see settings.background */
    double intensity;   /* finite, >= 0: scales every texel */
    bool lights;        /* also a distant light: each camera sample sends one shadow ray to one
                           direction of the image, drawn as sampling says */
    bg_environment_sampling sampling;
} bg_environment;

/* The default environment described above (none). */
BG_API bg_environment bg_environment_init(void);
/* Sets the scene's environment (takes effect at the next commit); a texture in use by it cannot be
 * removed. The importance tables are built here, once per texture (O(texels)). Refused, naming the
 * field: an unknown texture, a bad intensity or sampling; BG_ERR_OUT_OF_MEMORY for the tables. The
 * multipass plan does not draw environments: a frame that would go to it is refused (BG_ERR_LIMIT,
 * saying why it would), and BG_PLAN_AUTO takes a fused plan for them. */
BG_API bg_status bg_scene_set_environment(bg_scene *scene, const bg_environment *environment);

/* ---- commit -------------------------------------------------------------------------------- */

/* Validates the whole scene and makes it what the renderers see: computes bounds, inverse
 * transforms (in double) and what the renderers need, and applies removals. Cheap when only values
 * changed (no allocation). A stored error does not block it; if it fails (out of memory or a
 * library limit: every field check already ran when its item was added or set), the previous
 * commit stays, removed items included. */
BG_API bg_status bg_scene_commit(bg_scene *scene);
/* Bumped by every successful commit; renderers use it to tell what changed. */
BG_API uint64_t bg_scene_commit_count(const bg_scene *scene);

/* ---- rendering ----------------------------------------------------------------------------- */

typedef enum bg_output_encoding {
    BG_ENCODING_SRGB = 0, /* RGBA8 output is the sRGB transfer function of clamped linear radiance */
    BG_ENCODING_LINEAR    /* RGBA8 output is clamped linear radiance x 255 */
} bg_output_encoding;

/* Work the GPU renderer skips when a scene does not need it (docs/gpu_pipeline.md). Each skip can be
 * switched off through bg_render_settings.gpu_disable_skips to test that it changes no pixel and to
 * measure what it saves. */
enum {
    BG_SKIP_SPECIALIZE = 1u << 0,  /* off: generic shaders with every material feature and texture
                                      slot (1x1 white textures where a material has none) */
    BG_SKIP_BOUNCE_CULL = 1u << 1, /* off: secondary rays are spawned even without mirrors or glass */
    BG_SKIP_OCCLUSION = 1u << 2,   /* off: ray sets are traced even when the occlusion query counts
                                      no live pixel in them */
    BG_SKIP_STENCIL = 1u << 3,     /* off: passes run on dead and missed pixels too (weight 0) */
    BG_SKIP_SCISSOR = 1u << 4,     /* off: camera-ray intersection covers the whole image, not each
                                      bounded object's screen rectangle */
    BG_SKIP_SHADOW_CULL = 1u << 5, /* off: a shadow pass for every object, even one that casts no
                                      shadow or can only shadow itself (the pass then blocks nothing) */
    BG_SKIP_FACING = 1u << 6,      /* off: shadow and light work also for surfaces facing away from a
                                      light (the result is then multiplied by 0) */
    BG_SKIP_BATCH = 1u << 7,       /* off: one object per intersection pass and per shadow pass, not
                                      several objects (up to the hardware's limits) in one */
    BG_SKIP_ALL = (1u << 8) - 1u   /* every bit above: all skips off, the most literal frame */
};

/* How the GPU renderer lays out a frame (docs/gpu_pipeline.md). The plans render the same shading
 * model within the same accuracy against the CPU reference, but not bit for bit alike. */
typedef enum bg_gpu_plan {
    BG_PLAN_AUTO = 0,  /* fused where the scene and the GL limits allow it (BG_PLAN_FUSED up to 7
                          bounded objects, BG_PLAN_FUSED_TREE from 8 or whenever the scene holds a
                          mesh), else multipass (the reason is logged at BG_LOG_INFO); multipass
                          whenever an option only it has is asked for: gpu_disable_skips, dmax,
                          half_gbuffer or float_depth */
    BG_PLAN_FUSED,     /* one fragment pass per frame traces, shades and encodes the whole image,
                          every object's test written into the shader (a mesh's test walks its own
                          tree, as in BG_PLAN_FUSED_TREE); bg_render_gpu fails (BG_ERR_LIMIT, or
                          BG_ERR_GL when GL refuses the program) where it cannot run */
    BG_PLAN_MULTIPASS, /* ray maps, G-buffer, shadow, light and spawn passes level by level, one
                          intersection pass per object batch (a mesh's walks its own tree) */
    BG_PLAN_FUSED_TREE /* the fused pass with the bounded objects in a tree walked from textures, so
                          its program and its cost grow with the shapes and log(objects); meshes'
                          own trees and triangles are walked from a third texture. In every plan a
                          pixel whose walks would outrun the shader's loop limit is rendered by
                          the CPU reference (bg_render_stats.fallback_pixels) */
} bg_gpu_plan;

/* How the fused tree plan finds the object each camera ray meets first (docs/gpu_pipeline.md,
 * "Primary visibility by rasterisation"). Either way the first hits are the same, bit for bit. */
typedef enum bg_primary_visibility {
    BG_PRIMARY_AUTO = 0, /* rasterise where it was measured to pay (a mesh in the tree, at most one
                            footprint triangle per 8 pixels), else walk */
    BG_PRIMARY_WALK,     /* every camera ray walks the object tree, as every other ray does */
    BG_PRIMARY_RASTER    /* each tree object's footprint is drawn first, with its exact test in the
                            fragment and the nearest kept by the depth test; the walk runs only where
                            two objects or triangles tie. Needs BG_PLAN_FUSED_TREE's walk, a pinhole or
                            orthographic camera, meshes without front-only or cut-out filters and
                            float32 blending (bg_render_gpu fails with BG_ERR_LIMIT, naming why) */
} bg_primary_visibility;

/* How a render adds up the light a camera ray brings (docs/shading.md 8, 9 and 13). */
typedef enum bg_integrator {
    BG_INTEGRATOR_WHITTED = 0, /* the paper's model: emission, ambient and every light at each hit,
                                  then mirror and refracted rays (and glossy ones) as a ray tree */
    BG_INTEGRATOR_PATH         /* global illumination: one path per camera sample that bounces off
                                  every surface by sampling its BRDF, with every light sampled at each
                                  hit (multiple importance sampling for visible area lights and the
                                  environment) and Russian roulette from BG_PATH_ROULETTE_DEPTH on.
                                  Area lights are emitters of uniform radiance (docs/shading.md 13).
                                  The CPU reference and the fused GPU plans draw it; BG_PLAN_MULTIPASS
                                  refuses it (BG_ERR_LIMIT), and BG_PLAN_AUTO takes a fused plan */
} bg_integrator;

/* The first bounce level at which a path may be ended by Russian roulette under BG_INTEGRATOR_PATH:
 * the camera ray's hit is level 0, so levels 0 .. 2 always go on (up to max_depth). */
#define BG_PATH_ROULETTE_DEPTH 3

/* Told how much of a render is done: fraction in [0, 1], never decreasing from call to call, first
 * 0 before any work and last exactly 1 once the image is complete (that last call's return value
 * is ignored). Return false to cancel: the render stops at the next row (CPU) or sample pass (GPU)
 * and returns BG_ERR_CANCELLED. Called from the thread that called the render, once per finished
 * row on the CPU (whichever thread rendered it) and once per sample pass and tile on the GPU
 * (docs/shading.md 1.2). */
typedef bool (*bg_progress_fn)(double fraction, void *user);

/* Told that rows [y0, y1) of the caller's image (row 0 at the top) hold their final bytes, so that
 * a caller can encode, write or show them while the renderer works on the rows below (the command
 * streams its PNG this way). bg_render_gpu calls it once per band of tiles, after the band's last
 * tile, while the next tile renders on the GPU; one call for [0, height) when the image is one piece.
 * bg_render_cpu calls it once for [0, height) when the image is complete. The calls come in order
 * from the thread that called the render, before the render returns, and the bands they name cover
 * the image exactly once. Read the rows only: until the render returns, a later tile may write the
 * same bytes there again. A render that fails or is cancelled makes no more calls; the bands already
 * told are written. */
typedef void (*bg_rows_fn)(int y0, int y1, void *user);

#define BG_MAX_SAMPLES 256
/* The largest side of any image, texture or frame, in pixels: keeps width * height * 16 bytes well
 * inside size_t and within what GL 2.1 hardware can hold. */
#define BG_MAX_IMAGE_SIDE 16384
/* The most bounce levels a render follows (bg_render_settings.max_depth). */
#define BG_MAX_DEPTH 64

/* Defaults (bg_render_settings_init): background (0, 0, 0) linear, max_depth 5 bounce levels,
 * min_weight 1/512, the Whitted integrator (no ambient should path be chosen), sRGB encoding,
 * threads 0 (the online cores), dmax 0 (automatic), no phase
 * timing, every skip on, GPU plan automatic, one sample at each pixel centre, the frame is the
 * image, no progress callback, no rows callback. */
typedef struct bg_render_settings {
    double background[3];
    int max_depth;      /* bounce levels after the primary hit, 0 .. BG_MAX_DEPTH; under
                           BG_INTEGRATOR_PATH the most bounces of any path */
    double min_weight;  /* BG_INTEGRATOR_WHITTED: a ray whose path weight is below this in every
                           channel is not followed (the path integrator uses roulette instead) */
    bg_integrator integrator; /* 0 = BG_INTEGRATOR_WHITTED */
    bool path_ambient;  /* BG_INTEGRATOR_PATH only: add the scene's ambient term at each hit as
                           Whitted does; false (the default) leaves it out, since the bounces bring
                           the light it stands in for */
    bg_output_encoding encoding;
    int threads;        /* CPU renderer only; 0 = online cores, at most 256 */
    double dmax;        /* GPU renderer only: the distance up to which depth is linear and finest
                           (t / (2 dmax)); farther hits are kept on a compressed scale
                           (docs/gpu_pipeline.md); 0 = per level from the scene's bounds */
    bool gpu_timing;    /* GPU renderer only: measure the time of each phase (bg_render_stats.timing):
                           with GPU timer queries where GL has them, which wait for nothing until the
                           call's end, else with the wall clock between glFinish calls, which slows
                           the frame; and count shaded fragments (occlusion queries) */
    unsigned gpu_disable_skips; /* GPU renderer only: BG_SKIP_* bits to switch off (testing) */
    bg_gpu_plan gpu_plan; /* GPU renderer only: the frame's plan; 0 = BG_PLAN_AUTO */
    bg_primary_visibility primary; /* GPU renderer only, the fused tree plan: how camera rays find
                           their first hit; 0 = BG_PRIMARY_AUTO */
    int samples;        /* camera rays per pixel, 0 .. BG_MAX_SAMPLES; 0 and 1 = one ray at the pixel
                           centre. More are placed on a fixed stratified pattern (docs/shading.md 1.1),
                           the same in both renderers, and averaged with equal weights (a box filter) */
    int frame_width, frame_height; /* the full frame the image is a window of (a crop window, a tile):
                           0 = the image's size; at most BG_MAX_IMAGE_SIDE per side */
    int window_x, window_y; /* the image's top-left pixel in the frame (x right, y down); the image must
                           lie inside the frame. Every pixel is the frame's pixel at that place */
    bg_progress_fn progress; /* NULL: no progress calls, no cancelling */
    void *progress_user;     /* passed to progress */
    double gpu_memory_budget; /* GPU renderer only, bg_render_gpu: bytes of render targets one tile may
                           hold, by the renderer's estimate of the worst plan (docs/gpu_pipeline.md,
                           "Tiles"); an image beyond it or beyond GL's texture size limit is rendered
                           in tiles, bit-identical to one pass; 0 = 1 GiB, else at least 1 MiB */
    bg_rows_fn rows_done;    /* bg_render_gpu and bg_render_cpu: told as rows of the image become
                                final; NULL: no calls */
    void *rows_user;         /* passed to rows_done */
} bg_render_settings;

/* The default settings described above. */
BG_API bg_render_settings bg_render_settings_init(void);

/* Renders the committed scene with the double-precision CPU reference renderer into a
 * caller-owned image (size 1 .. 16384 per side). The output does not depend on the thread count.
 * Cancelled (BG_ERR_CANCELLED): each row of the image is either complete or untouched. */
BG_API bg_status bg_render_cpu(bg_scene *scene, const bg_render_settings *settings, bg_image *image);

/* ---- GPU renderer -------------------------------------------------------------------------- */

/* The GPU ray tracer: ray maps, per-object intersection passes, shadow, lighting and bounce passes,
 * all MACS render passes on the caller's MACS context. */
typedef struct bg_renderer bg_renderer;

/* Defaults: context required; 24-bit depth; RGBA32F G-buffer; no logger; the C library's allocator. */
typedef struct bg_renderer_desc {
    macs_context *context; /* the MACS context to render with; its GL context must be current */
    bool float_depth;      /* a 32-bit float depth buffer when GL has ARB_depth_buffer_float and the
                              MACS context was created with allow_float_depth; else 24-bit */
    bool half_gbuffer;     /* RGBA16F instead of RGBA32F for the G-buffer's material and direction
                              targets (normal, base, transparency, tangent, coat), trading error for
                              bandwidth; the hit position and the ambient/emission/ior target stay
                              RGBA32F. Probed once at creation: where GL cannot render to RGBA16F the
                              renderer logs a warning and keeps RGBA32F (bg_render_stats says which) */
    bg_logger logger;
    bg_allocator allocator;
} bg_renderer_desc;

/* Creates a renderer, whose textures and passes are made at the first render and kept while the
 * scene's structure and the image size stay the same; on failure message (if not NULL) gets the reason. */
BG_API bg_status bg_renderer_create(const bg_renderer_desc *desc, bg_renderer **out_renderer, char *message,
                                    size_t message_size);
/* Frees the renderer and its GPU objects (the MACS context stays the caller's); NULL is ignored. */
BG_API void bg_renderer_destroy(bg_renderer *renderer);
/* The first error since the last clear (BG_OK if none). */
BG_API bg_status bg_renderer_error(const bg_renderer *renderer);
/* The message of the first error ("" if none); GL failures carry MACS's message. */
BG_API const char *bg_renderer_error_message(const bg_renderer *renderer);
/* Forgets the stored error. */
BG_API void bg_renderer_clear_error(bg_renderer *renderer);

/* Renders the committed scene on the GPU into a caller-owned image, with the same shading model
 * and output encoding as bg_render_cpu. A failure (image larger than the GL limits, GPU out of
 * memory) leaves the renderer usable for the next call. Images larger than the GL texture size limit or
 * settings.gpu_memory_budget are rendered tile by tile (bg_render_stats.tiles), each tile a window of
 * the frame, so the image is the same bit for bit; a tile's read-back is queued while the next tile
 * renders, and settings.rows_done is told each band of tiles as it is final. Cancelled
 * (BG_ERR_CANCELLED), it leaves the image untouched but for the tiles already finished: a tile
 * reaches the image only once its every sample pass is done. A scene with a length beyond what float resolves (an object's scale outside
 * [1e-15, 1e15], anything farther than 1e15 from the camera, a lens wider than 1000 times its focus
 * distance: docs/gpu_pipeline.md, "Float range") is refused with BG_ERR_LIMIT naming the item; the CPU
 * renderer takes it. */
BG_API bg_status bg_render_gpu(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                               bg_image *image);

/* Renders like bg_render_gpu, but into a MACS texture that stays on the GPU, for a caller that draws
 * the frame (an interactive viewer) rather than reading it: target is a texture of the renderer's
 * MACS context (macs_texture_create, or a caller's own GL texture through macs_texture_wrap), and its
 * size is the image's. Its format picks the output as bg_image's does: RGBA8 holds the settings'
 * encoding (sRGB or linear, the bytes bg_render_gpu's RGBA8 image gets), RGBA32F linear unclamped
 * radiance (bg_render_gpu's RGBA32F image), RGBA16F the same rounded to half floats by GL (values
 * above 65504 become infinite); alpha is 1 everywhere.
 * Orientation: texture row 0 (the bottom row, t = 0, as GL has it) is the image's BOTTOM row: a quad
 * drawn with texture coordinate (0, 0) at its bottom-left corner shows the image upright, and
 * macs_texture_read returns the rows bottom first, the reverse of bg_image's top-first rows.
 * Cost: nothing of the image comes back to the host. The fused and multipass plans write the target
 * with their last pass. A plan must still render its pixels whose walks (BG_PLAN_FUSED_TREE's, or any
 * plan's in a mesh) ran out of loop steps on the CPU (bg_render_stats.fallback_pixels): where the
 * scene can have such pixels, one more pass packs those marks into one bit
 * per pixel, ceil(width / 32) x height x 4 bytes are read back (the call waits for the GPU there, as
 * bg_render_gpu's read-back does), and the CPU reference's pixels go up with one glTexSubImage2D per
 * run of marked pixels in a row; the frame is then what bg_render_gpu gives. With settings.samples > 1
 * the marks are read once, after the last sample. The samples are summed on the GPU and written into target once all are done (docs/gpu_pipeline.md,
 * "Samples, windows and progress"): an RGBA8 target gets bg_render_gpu's bytes by a GPU pass with
 * nothing read back, a float target the mean read back and uploaded; a cancelled render leaves target
 * untouched; a window (settings.frame_*, window_*) is honoured as by bg_render_gpu, but target is
 * never tiled. The renderer keeps no hold on target: destroying it after the call is fine.
 * Errors: as bg_render_gpu's, with target in the image's place: BG_ERR_INVALID_ARGUMENT when target
 * is NULL or belongs to another macs_context, or is larger than 16384 per side; BG_ERR_LIMIT beyond
 * the GL texture size limit; BG_ERR_GL (with MACS's message) when GL cannot render into the target's
 * format, as some GL cannot into RGBA16F. */
BG_API bg_status bg_render_gpu_to_texture(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                                          macs_texture *target);

/* Progressive accumulation (docs/gpu_pipeline.md, "Accumulation"): a frame's running sum of samples,
 * kept on the GPU in float textures of the renderer's MACS context, for a caller that shows a frame
 * while it refines (an interactive viewer) without reading anything back. Each sample is one pass
 * of the plan the settings choose into a float texture, added to the sum by a GPU pass in sample
 * order: the same float additions, in the same order, as bg_render_gpu's multi-sample frames make
 * (they go through it too), so after N samples of the pattern of settings.samples = N the resolved
 * image equals bg_render_gpu's at samples = N bit for bit (IEEE single-precision adds, as GLSL's
 * float on llvmpipe and on GPUs that honour it). The sample pattern is docs/shading.md 1.1's; the
 * mean of its first k < N samples in row-major order is a preview, not a k-sample image.
 * GPU memory: three RGBA32F textures of the size and one more for a sample (64 bytes a pixel).
 * Destroy an accumulation before its renderer's MACS context. */
typedef struct bg_accumulation bg_accumulation;

/* An empty accumulation of width x height (1 .. 16384 and the GL texture size limit per side:
 * BG_ERR_INVALID_ARGUMENT and BG_ERR_LIMIT), for the renderer's frames of that size. */
BG_API bg_status bg_accumulation_create(bg_renderer *renderer, int width, int height, bg_accumulation **out);
/* Frees it and its textures; NULL is ignored. */
BG_API void bg_accumulation_destroy(bg_accumulation *accumulation);
/* Adds samples [first, first + count) of the pattern of settings->samples = N to the sum: first is 0
 * (starting over, whatever the sum held) or the samples it holds, which must be of the same N;
 * count >= 1 and first + count <= N. The settings are those of bg_render_gpu (a window included);
 * progress goes from first / N to (first + count) / N. Each call may change the scene, camera or
 * plan, and a camera move or a value edit compiles no program, as for bg_render_gpu; samples added
 * since a change mix the two, so start over (first = 0) after one. Every check fails before any
 * pass, naming the argument; a failure or a cancel leaves the sum and its count as they were. */
BG_API bg_status bg_render_gpu_accumulate(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                                          bg_accumulation *accumulation, int first, int count);
/* The samples in the sum (0 for NULL). */
BG_API int bg_accumulation_samples(const bg_accumulation *accumulation);
/* The mean of the samples so far into a caller image of the accumulation's size, RGBA8 encoded as
 * settings->encoding says or RGBA32F linear, as bg_render_gpu writes them: one read-back, of the
 * bytes resolved on the GPU for RGBA8 (4 bytes a pixel), of the sum for RGBA32F (16).
 * BG_ERR_INVALID_ARGUMENT without samples, or for another size or renderer. */
BG_API bg_status bg_accumulation_resolve(bg_renderer *renderer, const bg_accumulation *accumulation,
                                         const bg_render_settings *settings, bg_image *image);
/* The same into a MACS texture of the renderer's context and the accumulation's size, on the GPU
 * with nothing read back: RGBA8 the bytes of bg_accumulation_resolve exactly (the GPU compares the sum
 * with the host encoding's thresholds: docs/gpu_pipeline.md, "Exact bytes"), a float format linear,
 * divided by the GPU. */
BG_API bg_status bg_accumulation_resolve_to_texture(bg_renderer *renderer, const bg_accumulation *accumulation,
                                                    const bg_render_settings *settings, macs_texture *target);

/* Kinds of GPU pass, counted in bg_render_stats. */
typedef enum bg_pass_kind {
    BG_PASS_RAYS = 0,   /* camera ray maps */
    BG_PASS_MARK,       /* live-pixel stencil of a secondary ray set */
    BG_PASS_INTERSECT,  /* one object (or batch) against one ray set, writing the G-buffer */
    BG_PASS_BACKGROUND, /* the background colour where a live ray missed */
    BG_PASS_SHADOW,     /* one object (or batch) against the shadow segments of up to four lights */
    BG_PASS_LIGHT,      /* up to four lights (and ambient and emission once) into the accumulation */
    BG_PASS_SPAWN,      /* reflected or transmitted ray maps of the next level */
    BG_PASS_RESOLVE,    /* accumulation to the output encoding */
    BG_PASS_KIND_COUNT_
} bg_pass_kind;

/* Phases of a frame, timed when bg_render_settings.gpu_timing is set. */
typedef enum bg_phase {
    BG_PHASE_SETUP = 0, /* scene upload, shader specialisation, allocation (0 when cached) */
    BG_PHASE_RAYS,
    BG_PHASE_INTERSECT,
    BG_PHASE_SHADOW,
    BG_PHASE_LIGHT,      /* lighting and background */
    BG_PHASE_BOUNCE,     /* spawning and marking secondary ray sets, with their occlusion queries */
    BG_PHASE_RESOLVE,    /* resolve pass and read-back into the caller's image (or, into a texture, the resolve
                            pass and the tree's fallback pixels) */
    BG_PHASE_COUNT_
} bg_phase;

/* How bg_render_settings.gpu_timing measured the phases. */
typedef enum bg_timing {
    BG_TIMING_NONE = 0,   /* not timed */
    BG_TIMING_GPU_TIMERS, /* GL_ARB_timer_query or GL_EXT_timer_query: nothing waits between phases */
    BG_TIMING_WALL_CLOCK  /* no timer queries: glFinish around each phase, which slows the frame */
} bg_timing;

#define BG_STATS_MAX_LEVELS 65

/* What the last bg_render_gpu call did. */
typedef struct bg_render_stats {
    int passes[BG_PASS_KIND_COUNT_]; /* passes drawn per kind (a pass split by MACS counts once) */
    int chunks;                      /* MACS program/framebuffer chunks drawn in all */
    int levels;                      /* bounce levels traced after the camera level */
    int ray_sets;                    /* ray sets traced: camera rays plus every live reflected or
                                        transmitted set (a level may hold several) */
    int ray_sets_skipped;            /* spawned sets the occlusion query found empty */
    uint64_t live_pixels[BG_STATS_MAX_LEVELS]; /* live rays per level, summed over its sets */
    double dmax[BG_STATS_MAX_LEVELS];          /* the dmax used at each traced level */
    uint64_t intersect_pixels;       /* pixels covered by intersection passes (scissor rectangles) */
    int gbuffer_targets;             /* G-buffer textures written by each intersection pass */
    int gbuffer_half_targets;        /* how many of those were RGBA16F (bg_renderer_desc.half_gbuffer) */
    int depth_bits;                  /* 24, or 32 for a float depth buffer */
    bool timed;                      /* the fields below were measured (gpu_timing) */
    bg_timing timing;                /* how: GPU timers, or the wall clock where GL has none */
    double phase_ms[BG_PHASE_COUNT_]; /* per phase, summed over the call's sample passes and tiles.
                                        GPU timers: the GPU's time on the phase's GL commands (host
                                        work in a phase, such as flipping the rows read back or the
                                        CPU's fallback pixels, is not in it). Wall clock: the time
                                        between glFinish calls around the phase, host work included */
    double total_ms;                 /* wall time of the whole call, from its start until its last
                                        command was done and the timers read */
    uint64_t shaded_fragments;       /* fragments kept by shadow and light passes (gpu_timing; the
                                        multipass plan's last sample pass) */
    int intersect_objects;           /* objects tested by intersection passes, summed over the passes
                                        (over passes[BG_PASS_INTERSECT]: objects per pass) */
    int shadow_objects;              /* the same for shadow passes */
    bg_gpu_plan plan;                /* the plan that ran: BG_PLAN_FUSED, BG_PLAN_FUSED_TREE or
                                        BG_PLAN_MULTIPASS. A fused plan draws one pass, counted as BG_PASS_INTERSECT (or as
                                        BG_PASS_BACKGROUND for a scene without objects); it keeps no
                                        ray sets, levels, dmax, G-buffer or depth buffer, so those
                                        fields stay 0 */
    int programs_compiled;           /* shader programs this render compiled, in any plan (0 when every
                                        program it needed was cached: a re-commit that changes only
                                        camera, lights, transforms or material values compiles none) */
    uint64_t fallback_pixels;        /* pixels whose walks (of the object tree, or of a mesh's tree in
                                        any plan) would have run past the shader's loop limit in any
                                        of their samples, rendered by the CPU reference instead (for
                                        every sample; with bg_render_gpu_accumulate, every pixel the
                                        accumulation's CPU reference holds) */
    int tiles;                       /* tiles the image was rendered in (1: one piece); the other
                                        fields describe the last tile's last sample pass, but
                                        fallback_pixels and programs_compiled count every pass */
    uint64_t texture_bytes;          /* GPU memory the scene's textures hold, in bytes of texels as
                                        uploaded: 4 a texel for an 8-bit image, 16 for a float one,
                                        and 4096 for the sRGB decode table where one is sampled
                                        (docs/shading.md 5.2); no mipmaps, no driver overhead */
    macs_work gl_work;               /* the GL work the whole call issued (macs_work, counted by MACS at
                                        each GL call): of every tile and sample pass, the resolve and
                                        the read-back into the image, the fallback pixels' uploads and
                                        any scene upload or program build. Set by bg_render_gpu,
                                        bg_render_gpu_to_texture and bg_render_gpu_accumulate, and by
                                        the accumulation resolves, which set only this field (the
                                        others stay the last render's). docs/gpu_pipeline.md, "GL work
                                        per frame", gives each plan's budget */
    bool primary_raster;             /* the camera rays' first hits were rasterised
                                        (bg_render_settings.primary) */
} bg_render_stats;

/* Copies the statistics of the last render (all zero before the first). */
BG_API void bg_renderer_get_stats(const bg_renderer *renderer, bg_render_stats *stats);

#ifdef __cplusplus
}
#endif

#endif
