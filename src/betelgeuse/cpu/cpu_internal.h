/* The CPU reference renderer's internals, exposed so that tests can check each step on its own.
 * Every formula follows docs/shading.md; everything is double precision. */
#ifndef BG_CPU_INTERNAL_H
#define BG_CPU_INTERNAL_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "../scene/scene_internal.h"
#include "../common/render_view.h"
#include "../common/scramble.h"

/* "No object" for the skip and inside indices of a ray. */
#define BG_CPU_NONE UINT32_MAX

/* ---- small vector helpers (header-local so every file inlines them) ------------------------ */

static inline double bg_v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void bg_v3_set(double out[3], double x, double y, double z)
{
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static inline void bg_v3_cross(const double a[3], const double b[3], double out[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    bg_v3_set(out, x, y, z);
}

/* Normalises in place; a zero (or non-finite-length) vector is left unchanged and false returned. */
static inline bool bg_v3_normalize(double v[3])
{
    double len = sqrt(bg_v3_dot(v, v));
    if (!(len > 0.0) || !isfinite(len))
        return false;
    v[0] /= len;
    v[1] /= len;
    v[2] /= len;
    return true;
}

/* Duff, Burgess, Christensen, Hery, Kensler, Liani and Villemin (2017): an orthonormal pair a, b
 * across the unit vector w, without a branch on a near-zero component (docs/shading.md 7). */
static inline void bgi_cpu_basis_across(const double w[3], double a[3], double b[3])
{
    double sign = w[2] >= 0.0 ? 1.0 : -1.0;
    double k = -1.0 / (sign + w[2]);
    double m = w[0] * w[1] * k;
    bg_v3_set(a, 1.0 + sign * w[0] * w[0] * k, sign * m, -sign * w[0]);
    bg_v3_set(b, m, sign + w[1] * w[1] * k, -w[1]);
}

/* ---- intersection (intersect.c) ------------------------------------------------------------ */

/* Where a ray meets a prototype, in object space. Closed shapes (sphere, box, cylinder) give the
 * interval [t[0], t[1]] of the line inside the solid; thin shapes (plane, rectangle) give one t. */
typedef struct bg_cpu_span {
    int count;             /* 0 miss, 1 thin surface, 2 closed interval (t[0] <= t[1]) */
    double t[2];           /* entry and exit parameters along the unnormalised object-space ray */
    double normal[2][3];   /* outward (front, +y for thin shapes) prototype normals, unnormalised */
} bg_cpu_span;

/* Intersects the object-space ray o + t d (d not normalised) with a prototype shape. */
void bgi_cpu_intersect_prototype(bg_shape shape, const double o[3], const double d[3], bg_cpu_span *span);

/* A candidate hit on one object, before its attributes are computed. */
typedef struct bg_cpu_candidate {
    double t;       /* world ray parameter (the same in object space) */
    int root;       /* 0 the entry (or the only) root, 1 the exit root; meshes: 0 front, 1 back */
    double p[3];    /* object-space point */
    double n[3];    /* object-space outward normal (unnormalised) */
    uint32_t triangle; /* meshes: the triangle hit (BG_CPU_NONE for the analytic shapes) */
    double bary[3];    /* meshes: the weights of its vertices */
} bg_cpu_candidate;

/* Transforms a world ray into the object's space (direction not normalised). */
void bgi_cpu_object_ray(const bg_object_data *object, const double o[3], const double d[3], double oo[3],
                       double od[3]);

/* Which triangle points of a mesh object are there for rays (mesh_filter.c, docs/shading.md 2.11):
 * its material's front_only and cut-out, resolved for one object. */
typedef struct bg_cpu_mesh_filter {
    bool front_only;
    double cutoff;                    /* 0: no cut-out */
    double coverage;                  /* the coverage value, times a texel's channel when texture is set */
    const bg_texture_data *texture;
    int channel;
    double uv_scale[2];
} bg_cpu_mesh_filter;

/* The filter of a mesh object into *storage, or NULL when its material lets every point through. */
const bg_cpu_mesh_filter *bgi_cpu_mesh_filter_of(const bg_scene_state *state, const bg_object_data *object,
                                                 bg_cpu_mesh_filter *storage);
/* Whether the filter keeps the point of weights bary on a triangle met from its object-space front
 * (front) or back. */
bool bgi_cpu_mesh_filter_keeps(const bg_cpu_mesh_filter *filter, const bg_mesh_data *mesh, uint32_t triangle,
                               const double bary[3], bool front);

/* The hit of a world ray on an object with t in (0, t_max]: the nearest root, or with far_root the
 * exit root of a closed shape (a refracted ray travelling inside it). */
bool bgi_cpu_intersect_object(const bg_object_data *object, const double o[3], const double d[3], bool far_root,
                             double t_max, bg_cpu_candidate *candidate);
/* The same, skipping triangle skip_triangle of a mesh object (BG_CPU_NONE: none; ignored by the
 * analytic shapes): the rule that lets a ray leave a mesh triangle (docs/shading.md 2.10); and the
 * points a mesh's filter (NULL: none) drops. */
bool bgi_cpu_intersect_object_except(const bg_object_data *object, const double o[3], const double d[3],
                                    bool far_root, uint32_t skip_triangle, const bg_cpu_mesh_filter *filter,
                                    double t_max, bg_cpu_candidate *candidate);

/* A shadow segment is open at its light end by this share of its length: a root at
 * t >= t_max (1 - BG_SHADOW_END_REL) does not block (docs/shading.md 2.8). A light lying exactly on
 * a surface ends its segments on that surface, and whether that root falls a last bit before or
 * after t_max is rounding noise, decided differently in float and double; a tolerance relative to
 * t_max keeps the rule scale-invariant. The value is set by the GPU, which computes the root and the
 * length in float (unit roundoff u = 2^-24) from the same point: each takes a handful of roundings
 * (transform, subtraction, sqrt, division; GLSL 1.10 promises no correctly rounded division or
 * sqrt), amplified where the segment meets the surface at a grazing angle. Measured on llvmpipe with
 * the stress case "light on a surface": 2^-24 (the float step just below 1) already settles every
 * pixel, 0 leaves 22 acne pixels. 2^-16 = 256 u is that measured need with a margin of 2^8 for
 * coarser division and sqrt and more grazing segments; the price is that a true blocker within
 * 2^-16 of the segment's length from the light is ignored (15 um at 1 m, about the float spacing of
 * coordinates of magnitude 100 there). The GLSL side (bg_stage_shadow.glsl) uses the same value. */
#define BG_SHADOW_END_REL 0x1p-16

/* True when the segment o + t l, t in (0, t_max (1 - BG_SHADOW_END_REL)), meets the object (shadow test). */
bool bgi_cpu_segment_blocked(const bg_object_data *object, const double o[3], const double l[3], double t_max);
/* The same, skipping triangle skip_triangle of a mesh object (BG_CPU_NONE: none) and the points
 * its filter (NULL: none) drops. */
bool bgi_cpu_segment_blocked_except(const bg_object_data *object, const double o[3], const double l[3],
                                   uint32_t skip_triangle, const bg_cpu_mesh_filter *filter, double t_max);

/* A finished hit with everything shading needs. */
typedef struct bg_cpu_hit {
    uint32_t object;      /* 0-based object index */
    double t;
    double position[3];   /* world */
    double normal[3];     /* world, unit, facing the ray */
    double tangent[3];    /* world, unit, perpendicular to normal (dP/du orthogonalised) */
    double uv[2];         /* after uv_scale */
    bool entering;        /* closed: the ray arrives from outside; thin: it arrives on the +y side;
                             meshes: it meets a front face */
    uint32_t triangle;    /* meshes: the triangle hit; BG_CPU_NONE for the analytic shapes */
    double geometric_normal[3]; /* meshes: world, unit, on the side the ray arrives from */
    double offset;        /* meshes: how far a ray leaving the hit starts off the surface (2.10) */
} bg_cpu_hit;

/* t0 made a unit tangent: orthogonalised against the unit normal n, or the fallback axis rule of
 * docs/shading.md 3 when t0 vanishes or lies along n. */
void bgi_cpu_finish_tangent(const double t0[3], const double n[3], double t[3]);

/* Fills the hit's attributes from a candidate on object (index) for the world ray o + t d. */
void bgi_cpu_hit_attributes(const bg_object_data *object, uint32_t index, const double o[3], const double d[3],
                           const bg_cpu_candidate *candidate, bg_cpu_hit *hit);

/* ---- triangles (triangle.c) ----------------------------------------------------------------- */

/* A ray prepared once for many triangle tests (Woop, Benthin and Wald 2013, docs/shading.md 2.9): the
 * dominant axis kz of the direction, kx and ky chosen so that (kx, ky, kz) keeps the handedness that
 * the shear's sign would flip, and the shear that maps the direction to (0, 0, 1). */
typedef struct bg_cpu_triangle_ray {
    double o[3];
    int kx, ky, kz;
    double sx, sy, sz;  /* d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz] */
    bool valid;         /* false for a zero or non-finite direction: every test misses */
} bg_cpu_triangle_ray;

/* Where a ray meets a triangle. */
typedef struct bg_cpu_triangle_hit {
    double t;        /* the parameter of o + t d (d as given, not normalised) */
    double bary[3];  /* weights of v0, v1, v2 (each in [0, 1], summing to 1 up to rounding) */
    bool front;      /* the ray meets the side (v1 - v0) x (v2 - v0) points to: d.n < 0 */
} bg_cpu_triangle_hit;

/* Prepares the ray o + t d for bgi_cpu_triangle_intersect. */
void bgi_cpu_triangle_ray_init(const double o[3], const double d[3], bg_cpu_triangle_ray *ray);

/* Watertight ray/triangle test with the fill rule of docs/shading.md 2.9: a hit with t in
 * (t_min, t_max) on either side (no culling). A ray through an edge or vertex shared by consistently
 * wound triangles hits exactly one of them (unless the surface folds over in the ray's view, as for
 * a ray along it); a triangle whose edge vectors have a zero cross product (repeated vertices,
 * collinear) is never hit. hit may be NULL. */
bool bgi_cpu_triangle_intersect(const bg_cpu_triangle_ray *ray, const double v0[3], const double v1[3],
                                const double v2[3], double t_min, double t_max, bg_cpu_triangle_hit *hit);

/* a b - c d, rounded once from the exact value when the plain evaluation gives 0 and the factors lie
 * in [2^-480, 2^495] (or are 0), so that its sign is always the exact one there; the plain value
 * otherwise (whose sign is exact whenever it is not 0). */
double bgi_cpu_diff_of_products(double a, double b, double c, double d);

/* ---- meshes (mesh_hit.c, docs/shading.md 2.10) ----------------------------------------------- */

/* The nearest triangle of a mesh object met by the object-space ray oo + t od with t in
 * (0, t_max], skipping skip_triangle and the points filter (NULL: none) drops; of equal t the lower
 * triangle index wins. */
bool bgi_cpu_mesh_nearest(const bg_object_data *object, const bg_cpu_mesh_filter *filter, const double oo[3],
                         const double od[3], uint32_t skip_triangle, double t_max, bg_cpu_candidate *candidate);
/* Whether some triangle but skip_triangle meets the object-space segment with t in (0, t_limit) at a
 * point that filter (NULL: none) keeps. */
bool bgi_cpu_mesh_blocked(const bg_object_data *object, const bg_cpu_mesh_filter *filter, const double oo[3],
                         const double od[3], uint32_t skip_triangle, double t_limit);
/* bgi_cpu_hit_attributes for a mesh object. */
void bgi_cpu_mesh_attributes(const bg_object_data *object, uint32_t index, const double d[3],
                            const bg_cpu_candidate *candidate, bg_cpu_hit *hit);
/* Where a ray leaving hit in direction dir starts: the hit position for the analytic shapes; for a
 * mesh, the position moved by hit->offset along the geometric normal to the side dir goes. */
void bgi_cpu_leave_origin(const bg_cpu_hit *hit, const double dir[3], double origin[3]);

/* ---- UV mappings (uv_map.c) ---------------------------------------------------------------- */

/* The texture coordinates (before uv_scale) and dP/du of an object-space point. */
void bgi_cpu_uv_map(bg_uv_mapping mapping, const double p[3], double uv[2], double dpdu[3]);

/* ---- textures and material parameters (texture_sample.c) ------------------------------------ */

/* GL_LINEAR sampling (no mipmaps) of a texture at (u, v) with its wrap mode. */
void bgi_cpu_texture_sample(const bg_texture_data *texture, double u, double v, double rgba[4]);

/* A material evaluated at one surface point, every value clamped to its range. */
typedef struct bg_cpu_layer {
    double c[3];  /* reflectance at normal incidence, [0, 1] */
    double r;     /* roughness, [0, 1] */
    double p;     /* isotropy, [0, 1] */
} bg_cpu_layer;

typedef struct bg_cpu_surface {
    bg_cpu_layer base;
    bool has_coat;
    bg_cpu_layer coat;
    double ambient[3];
    double emission[3];
    double transparency;
    double ior;
} bg_cpu_surface;

/* Evaluates every (possibly textured) material parameter at texture coordinates uv. */
void bgi_cpu_surface_eval(const bg_scene_state *state, const bg_material *material, const double uv[2],
                         bg_cpu_surface *surface);

/* ---- Schlick's BRDF (brdf.c) ---------------------------------------------------------------- */

/* Spectral factor S(u) = C + (1 - C)(1 - u)^5 per channel. */
void bgi_cpu_schlick_s(const double c[3], double u, double s[3]);
/* Lambertian, glossy and specular shares (a, b, c) of a layer of roughness r. */
void bgi_cpu_schlick_split(double r, double *a, double *b, double *c);
/* The glossy directional factor D(t, v, v', w) of roughness r and isotropy p (0 when v or v' <= 0). */
double bgi_cpu_schlick_d(double r, double p, double t, double v, double vl, double w);
/* The non-Dirac BRDF f (single or coat over base) for unit normal n, tangent, unit view direction
 * (towards the viewer) and unit light direction (towards the light). */
void bgi_cpu_brdf(const bg_cpu_surface *surface, const double n[3], const double tangent[3], const double view[3],
                 const double light[3], double f[3]);
/* The weight of the perfectly specular (mirror) share for the view cosine v = n.view. */
void bgi_cpu_mirror_weight(const bg_cpu_surface *surface, double v, double m[3]);
/* Exact unpolarised dielectric Fresnel reflectance for cosine cos_i and index ratio n1 -> n2;
 * returns 1 on total internal reflection and sets *cos_t otherwise. */
double bgi_cpu_fresnel(double cos_i, double n1, double n2, double *cos_t);

/* ---- tracing (shade.c) ---------------------------------------------------------------------- */

/* The nearest hit of a world ray (unit d) skipping object skip and taking the far root of object
 * inside (either may be BG_CPU_NONE); false on a miss. */
bool bgi_cpu_nearest_hit(const bg_scene_state *state, const double o[3], const double d[3], uint32_t skip,
                        uint32_t inside, bg_cpu_hit *hit);
/* The same where skip is a mesh object and only its triangle skip_triangle is skipped (BG_CPU_NONE:
 * the whole object skip, as above). */
bool bgi_cpu_nearest_hit_except(const bg_scene_state *state, const double o[3], const double d[3], uint32_t skip,
                               uint32_t skip_triangle, uint32_t inside, bg_cpu_hit *hit);

/* The radiance arriving at p from a light (0 outside a spot cone), its unit direction l and the
 * shadow segment's length; false when the light cannot contribute (docs/shading.md 7). */
bool bgi_cpu_light_arrival(const bg_light *light, const double p[3], double l[3], double *t_max, double radiance[3]);
/* The same for the light's point at this camera sample (area_light.c, docs/shading.md 7): an area
 * light's sample point (of the unit-square point of its dimension) as a point light, a rectangle's
 * radiance scaled by its cosine towards p; point and directional lights as above. */
bool bgi_cpu_light_sample(const bg_scene_state *state, uint32_t light, const bgi_sample_point *sample,
                          const double p[3], double l[3], double *t_max, double radiance[3]);
/* The point of a sphere light (centre c, radius r) seen from p for the unit-square point uv: uniform
 * in the solid angle of the cone the sphere fills; c itself when p is inside or on it. */
void bgi_cpu_sphere_light_point(const double c[3], double r, const double p[3], const double uv[2], double q[3]);
/* An area light's point (sphere or rectangle) for the unit-square point uv, seen from p. */
void bgi_cpu_area_light_point(const bg_light *light, const double p[3], const double uv[2], double q[3]);
/* A rectangle light's unit front normal (edge_u x edge_v) and its area |edge_u x edge_v|. */
void bgi_cpu_rectangle_light_frame(const bg_light *light, double n[3], double *area);
/* Whether the shadow segment p + t l, t in (0, t_max), is blocked for a hit on object self (and
 * mesh triangle self_triangle, BG_CPU_NONE for the analytic shapes) (docs/shading.md 2.8). */
bool bgi_cpu_shadowed(const bg_scene_state *state, const double p[3], const double l[3], double t_max, uint32_t self,
                      uint32_t self_triangle);
/* Whether a secondary ray of path weight w is followed: some channel positive and >= min_weight. */
bool bgi_cpu_worth_following(const double w[3], double min_weight);

/* Adds weight x the radiance along a ray at bounce level `level` into out; skip, skip_triangle and
 * inside as bgi_cpu_nearest_hit_except takes them. */
void bgi_cpu_trace(const bg_scene_state *state, const bg_render_settings *settings, const bgi_sample_point *sample,
                   const double o[3], const double d[3], int level, const double weight[3], uint32_t skip,
                   uint32_t skip_triangle, uint32_t inside, double out[3]);

/* The linear radiance of one primary ray (o, unit d) of a camera sample (which places the area
 * lights' points; NULL: sample 0 of 1 of frame pixel (0, 0)). */
void bgi_cpu_shade_ray(const bg_scene_state *state, const bg_render_settings *settings,
                       const bgi_sample_point *sample, const double o[3], const double d[3], double rgb[3]);

/* The path integrator's radiance along one camera ray (path.c, docs/shading.md 13). */
void bgi_cpu_path_ray(const bg_scene_state *state, const bg_render_settings *settings, const bgi_sample_point *sample,
                      const double o[3], const double d[3], double out[3]);

/* What a ray of unit direction d that meets nothing sees of the environment (environment_sample.c,
 * docs/shading.md 7.1): the texture filtered at d, times the intensity. */
void bgi_cpu_environment_radiance(const bg_scene_state *state, const double d[3], double rgb[3]);
/* The environment as a light at this camera sample: its unit direction l and E_l, false when it
 * brings nothing (the shadow segment is unbounded). */
bool bgi_cpu_environment_light(const bg_scene_state *state, const bgi_sample_point *sample, double l[3],
                               double radiance[3]);

/* The environment's direction l for the unit-square point xi by its sampling rule (7.1), the density
 * pdf of that direction (per steradian) and the stored texel it falls in (before the intensity);
 * false when the rule gives none. */
bool bgi_cpu_environment_draw(const bg_scene_state *state, const double xi[2], double l[3], double *pdf,
                              double texel[3]);
/* The density with which bgi_cpu_environment_draw gives the unit direction d (docs/shading.md 13.3). */
double bgi_cpu_environment_pdf(const bg_scene_state *state, const double d[3]);

/* The glossy reflection of the unit direction d off unit normal n (facing the ray) for roughness
 * r > 0 and the unit-square point uv (docs/shading.md 9.1): d mirrored about a normal drawn from
 * Schlick's zenith factor. False when it points below the surface (no reflected ray then). */
bool bgi_cpu_glossy_reflect(const double d[3], const double n[3], double r, const double uv[2], double out[3]);

/* Moves a pinhole ray (o at the eye, unit d) of a camera with aperture_radius > 0 onto the thin lens
 * (lens.c, docs/shading.md 1.4): through this sample's point of the lens towards where the pinhole
 * ray meets the plane in focus. */
void bgi_cpu_lens_ray(const bg_camera_data *camera, const bgi_sample_point *sample, double o[3], double d[3]);

/* The primary ray through the centre of pixel (x, y) of a width x height image (row 0 at the top). */
void bgi_cpu_primary_ray(const bg_camera_data *camera, int width, int height, int x, int y, double o[3],
                        double d[3]);

/* The primary ray through the point (fx, fy) of a width x height frame, in pixels from its top-left
 * corner (x right, y down; docs/shading.md 1): pixel (x, y)'s centre is (x + 0.5, y + 0.5). */
void bgi_cpu_frame_ray(const bg_camera_data *camera, int width, int height, double fx, double fy, double o[3],
                      double d[3]);

/* Renders pixel (x, y) of the view's image (row 0 at the top) into texel, 4 bytes (RGBA8 in the
 * settings' encoding) or 4 floats (RGBA32F), alpha 1: the average of the view's samples
 * sample_first .. sample_first + sample_count - 1 of the frame's pixel (x0 + x, y0 + y). With all
 * the samples, what bg_render_cpu writes there. */
void bgi_cpu_render_texel(const bg_scene_state *state, const bg_render_settings *settings,
                         const bgi_render_view *view, int x, int y, bg_pixel_format format, void *texel);

/* Renders pixel (x, y) of image (rows `stride` bytes apart, row 0 at the top) in its format, alpha 1,
 * as bgi_cpu_render_texel does. The GPU's tree plan calls it for the pixels it cannot finish. */
void bgi_cpu_render_pixel(const bg_scene_state *state, const bg_render_settings *settings,
                         const bgi_render_view *view, const bg_image *image, size_t stride, int x, int y);

#endif
