/* The float32 stress cases (docs/stress.md): scenes that push the GPU renderer's single
 * precision where it is weakest, each rendered by bench/stress.c and, for the must-hold ones,
 * asserted by tests/test_bg_stress.c against the double-precision CPU reference. One table, so the
 * program and the test can never disagree about what a case is. */
#ifndef STRESS_CASES_H
#define STRESS_CASES_H

#include <stdbool.h>
#include <stddef.h>

#include "betelgeuse.h"
#include "scenes.h"

/* Every case renders at this size: the size tests/gpu_thresholds.h was measured at, so the normal
 * thresholds apply unchanged. */
#define STRESS_WIDTH 160
#define STRESS_HEIGHT 120

typedef enum stress_class {
    STRESS_MUST_HOLD = 0, /* asserted in make check: within the normal thresholds, no acne, no NaN */
    STRESS_SWEEP          /* measured and reported only (the test still asserts it has no NaN or Inf) */
} stress_class;

/* One case: a shared scene placed by scale and offset (scene < SCENE_COUNT), or a small scene of its
 * own (build, with scene == SCENE_COUNT), with the render settings it needs. */
typedef struct stress_case {
    const char *name;
    const char *stresses;  /* what float32 risks here, for the report */
    stress_class class_;
    bool quick;            /* part of the QUICK=1 subset of bench/stress */
    scene_id scene;
    double scale;          /* 0 means 1 */
    double offset;         /* distance the scene is moved from the origin... */
    int direction;         /* ...along direction 0, 1 or 2 (stress_cases.c) */
    bg_status (*build)(bg_scene *scene);
    int max_depth;         /* 0 means the default */
    double min_weight;     /* 0 means the default */
    double dmax;           /* 0 means automatic */
    bool meshes;           /* a scene of its own with meshes, judged by the mesh thresholds */
} stress_case;

/* The number of cases and case i (NULL past the end). */
size_t stress_case_count(void);
const stress_case *stress_case_at(size_t i);
/* Builds the case into an empty scene and commits it. */
bg_status stress_case_build(const stress_case *c, bg_scene *scene);
/* True when the case is a shared scene moved away from scale 1 and offset 0: then the same scene at
 * the origin is a second reference, and comparing against it shows the drift of the whole pipeline
 * (the CPU reference's own double-precision drift included). */
bool stress_case_is_placed(const stress_case *c);
/* Builds that scene at scale 1 and offset 0 and commits it (only for placed cases). */
bg_status stress_case_build_origin(const stress_case *c, bg_scene *scene);
/* The render settings of the case. */
bg_render_settings stress_case_settings(const stress_case *c);

#endif
