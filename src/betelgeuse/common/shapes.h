/* Every shape as one X-macro row: each table or choice over bg_shape in the library (the GPU's shader
 * files and suffixes, thinness, the default UV mapping, the CPU intersector, the world box) is
 * generated from this list, so a shape is described once.
 *
 * A new shape takes, and nothing else in src/:
 *   1. its enumerator in bg_shape (include/betelgeuse.h, before BG_SHAPE_COUNT_) and its prototype
 *      described there and in docs/shading.md section 2;
 *   2. one row below;
 *   3. glsl110/bg_shape_<name>.glsl defining bg_shape_span (the float port of the CPU intersector);
 *   4. its CPU intersector in cpu/intersect.c, under the name its row gives;
 *   5. its half extent in scene/object_data.c, under the name its row gives, unless it is unbounded
 *      (its world box then feeds the object tree, scene/tree.c).
 * Outside the library, the benchmark peers (bench/) and the test scenes name shapes of their own.
 *
 * Columns of X(shape, name, glsl, thin, default_uv, cpu_span, half_extent):
 *   shape       the bg_shape enumerator
 *   name        the suffix of its GLSL functions: a pass over several shapes holds one renamed copy
 *               of bg_shape_span and of the stage functions over it per shape (bg_hit_root_sphere)
 *   glsl        the glsl110/ file defining its bg_shape_span
 *   thin        true for a surface without an inside (one root, two sides, light passes straight
 *               on); false for a closed solid (an entry and an exit root, Fresnel at the interface)
 *   default_uv  the mapping BG_UV_DEFAULT resolves to at commit
 *   cpu_span    void f(const double o[3], const double d[3], bg_cpu_span *span) in cpu/intersect.c
 *   half_extent double f(double a, double b, double c) in scene/object_data.c: the half extent along one
 *               world axis of the transformed prototype, from that axis's row (a b c) of the linear
 *               part; NULL for an unbounded shape (no world box, never scissored or cut) */
#ifndef BG_SHAPES_H
#define BG_SHAPES_H

#include "betelgeuse.h"

#define BG_SHAPES(X)                                                                                          \
    X(BG_SHAPE_SPHERE, "sphere", "bg_shape_sphere.glsl", false, BG_UV_SPHERICAL, sphere_span, sphere_extent) \
    X(BG_SHAPE_PLANE, "plane", "bg_shape_plane.glsl", true, BG_UV_PLANAR, plane_span, NULL)                  \
    X(BG_SHAPE_BOX, "box", "bg_shape_box.glsl", false, BG_UV_BOX, box_span, box_extent)                      \
    X(BG_SHAPE_CYLINDER, "cylinder", "bg_shape_cylinder.glsl", false, BG_UV_CYLINDRICAL, cylinder_span,      \
      cylinder_extent)                                                                                        \
    X(BG_SHAPE_RECTANGLE, "rectangle", "bg_shape_rectangle.glsl", true, BG_UV_PLANAR, rectangle_span,        \
      rectangle_extent)

/* A row for every enumerator: the tables generated from the list index by shape. */
#define BG_SHAPE_ROW_COUNT_(shape, name, glsl, thin, default_uv, cpu_span, half_extent) +1
typedef char bg_shapes_one_row_per_shape[(0 BG_SHAPES(BG_SHAPE_ROW_COUNT_)) == BG_SHAPE_COUNT_ ? 1 : -1];
#undef BG_SHAPE_ROW_COUNT_

/* Whether the shape is thin (its column above); both renderers branch on it per hit. */
static inline bool bg_shape_thin(bg_shape shape)
{
#define BG_SHAPE_THIN_(shape, name, glsl, thin, default_uv, cpu_span, half_extent) [shape] = thin,
    static const bool is_thin[BG_SHAPE_COUNT_] = {BG_SHAPES(BG_SHAPE_THIN_)};
#undef BG_SHAPE_THIN_
    return (unsigned)shape < BG_SHAPE_COUNT_ && is_thin[shape];
}

#endif
