/* Double-precision affine transforms: the checks and inverses behind every object transform. */
#ifndef BG_AFFINE_H
#define BG_AFFINE_H

#include "betelgeuse.h"

typedef enum bg_affine_check {
    BG_AFFINE_OK = 0,
    BG_AFFINE_NOT_FINITE,   /* an element is NaN or infinite */
    BG_AFFINE_NOT_AFFINE,   /* the bottom row is not (0, 0, 0, 1) */
    BG_AFFINE_SINGULAR,     /* the linear part is (nearly) singular for its scale */
    BG_AFFINE_SCALE,        /* the overall scale is outside [BG_AFFINE_MIN_SCALE, BG_AFFINE_MAX_SCALE] */
    BG_AFFINE_INVERSE_OVERFLOW /* the inverse has an element beyond the double range */
} bg_affine_check;

/* Below this, |det L| / s^3 counts as singular, where L is the linear part and s = ||L||_F / sqrt 3
 * the root mean square of its row norms. The ratio is at most 1 (a scaled rotation), scale-free (a
 * tiny but well-shaped object passes) and rotation-invariant (a slab 1e-13 thin is singular whether
 * axis-aligned or turned; a test on the product of row norms would pass the axis-aligned one). */
#define BG_AFFINE_SINGULAR_RATIO 1e-12

/* The overall scale s (above) an object transform may have. The inverse's linear part is at most
 * about 6e12 / s and the world box about |translation| + 1.8 s, so these keep both, and the squares
 * of object-space directions the renderers form (up to (6e12 / s)^2 and down to (1 / 1.8 s)^2), a
 * hundred decades inside the normal double range. betelgeuse.h states the same range. */
#define BG_AFFINE_MIN_SCALE 1e-100
#define BG_AFFINE_MAX_SCALE 1e100
/* The range as messages write it: "[1e-100, 1e100]". */
#define BG_AFFINE_TEXT_(x) #x
#define BG_AFFINE_TEXT(x) BG_AFFINE_TEXT_(x)
#define BG_AFFINE_SCALE_RANGE "[" BG_AFFINE_TEXT(BG_AFFINE_MIN_SCALE) ", " BG_AFFINE_TEXT(BG_AFFINE_MAX_SCALE) "]"

/* Checks m and, when it is fine and inv is not NULL, writes its inverse (checked finite). The
 * overall scale s goes to out_scale (when not NULL) once m is known finite and affine, else 0. */
bg_affine_check bgi_affine_inverse(const bg_mat4 *transform, double inv[4][4], double *out_scale);
/* A short English phrase for a check result ("is singular"). */
const char *bgi_affine_check_string(bg_affine_check check);
/* True when every element of the 3-vector is finite. */
bool bgi_vec3_finite(bg_vec3 v);
/* Euclidean length, without overflow for large components (infinite only when the length is). */
double bgi_vec3_length(bg_vec3 v);
/* v scaled to length 1, computed on v divided by its largest component so that any finite
 * non-zero v works, however large or small; the zero vector stays zero. */
bg_vec3 bgi_vec3_normalize(bg_vec3 v);

#endif
