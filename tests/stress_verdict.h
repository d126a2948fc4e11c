/* Whether a float32 stress case stays within the normal thresholds: one rule for bench/stress.c (the
 * report) and tests/test_bg_stress.c (the assertions), so that "holds" means the same in both. */
#ifndef STRESS_VERDICT_H
#define STRESS_VERDICT_H

#include <stdio.h>

#include "gpu_thresholds.h"
#include "scenes/stress_cases.h"

/* The normal thresholds of a case: its shared scene's row of gpu_thresholds.h, the mesh row for a
 * mesh scene of its own; for another scene of its own, the loosest bound of each column over the table (no row is a better model of an unmeasured
 * scene, and the envelope is still far below what a real mistake costs). */
static inline gpu_threshold stress_threshold(const stress_case *c)
{
    if (c->scene < SCENE_COUNT)
        return *gpu_threshold_of(c->scene);
    if (c->meshes)
        return gpu_mesh_threshold;
    gpu_threshold t = gpu_thresholds[0];
    for (int i = 1; i < SCENE_COUNT; i++) {
        const gpu_threshold *r = &gpu_thresholds[i];
        t.interior_max = r->interior_max > t.interior_max ? r->interior_max : t.interior_max;
        t.mean = r->mean > t.mean ? r->mean : t.mean;
        t.psnr = r->psnr < t.psnr ? r->psnr : t.psnr;
        t.over = r->over > t.over ? r->over : t.over;
    }
    t.scene = SCENE_COUNT;
    return t;
}

/* True when the GPU image of a case holds against its reference: within the thresholds, no acne
 * pixel, no non-finite value; otherwise writes the first failure into why. */
static inline bool stress_holds(const stress_case *c, const image_metrics *m, const image_acne *acne,
                                size_t nonfinite, char *why, size_t size)
{
    gpu_threshold t = stress_threshold(c);
    if (nonfinite != 0) {
        snprintf(why, size, "%zu non-finite values in the float output", nonfinite);
        return false;
    }
    if (!gpu_threshold_check(&t, m, why, size))
        return false;
    if (acne->pixels != 0) {
        snprintf(why, size, "%ld acne pixels (%ld wrongly shadowed, %ld speckles; first at (%d, %d))", acne->pixels,
                 acne->shadowed, acne->speckles, acne->first_x, acne->first_y);
        return false;
    }
    return true;
}

#endif
