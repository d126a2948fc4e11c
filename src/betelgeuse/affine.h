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

/* Below this, |det L| / (|row 0| |row 1| |row 2|) counts as singular. By Hadamard's inequality the
 * ratio is at most 1 (orthogonal rows); it is scale-free, so a tiny but well-shaped object passes. */
#define BG_AFFINE_SINGULAR_RATIO 1e-12

/* Checks m and, when it is fine and inv is not NULL, writes its inverse (also checked finite). */
bg_affine_check bg_affine_inverse(const bg_mat4 *transform, double inv[4][4]);
/* A short English phrase for a check result ("is singular"). */
const char *bg_affine_check_string(bg_affine_check check);
/* True when every element of the 3-vector is finite. */
bool bg_vec3_finite(bg_vec3 v);
/* Euclidean length, without overflow for large components. */
double bg_vec3_length(bg_vec3 v);

#endif
