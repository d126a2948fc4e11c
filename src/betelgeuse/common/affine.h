/* Double-precision affine transforms: the checks and inverses behind every object transform. */
#ifndef BG_AFFINE_H
#define BG_AFFINE_H

#include "betelgeuse.h"

typedef enum bg_affine_check {
    BG_AFFINE_OK = 0,
    BG_AFFINE_NOT_FINITE,   /* an element is NaN or infinite */
    BG_AFFINE_NOT_AFFINE,   /* the bottom row is not (0, 0, 0, 1) */
    BG_AFFINE_SINGULAR      /* the linear part is (nearly) singular for its scale */
} bg_affine_check;

/* Below this, |det L| / s^3 counts as singular, where L is the linear part and s = ||L||_F / sqrt 3
 * the root mean square of its row norms. The ratio is at most 1 (a scaled rotation), scale-free (a
 * tiny but well-shaped object passes) and rotation-invariant (a slab 1e-13 thin is singular whether
 * axis-aligned or turned; a test on the product of row norms would pass the axis-aligned one). */
#define BG_AFFINE_SINGULAR_RATIO 1e-12

/* Checks m and, when it is fine and inv is not NULL, writes its inverse (also checked finite). */
bg_affine_check bgi_affine_inverse(const bg_mat4 *transform, double inv[4][4]);
/* A short English phrase for a check result ("is singular"). */
const char *bgi_affine_check_string(bg_affine_check check);
/* True when every element of the 3-vector is finite. */
bool bgi_vec3_finite(bg_vec3 v);
/* Euclidean length, without overflow for large components. */
double bgi_vec3_length(bg_vec3 v);

#endif
