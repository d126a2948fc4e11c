/* Test helper for the removal suites: one scene built either with a doomed set of items or
 * without it. Removing the doomed items and committing must give exactly the committed state of the
 * scene built without them, so every renderer must draw the two alike. */
#ifndef UTIL_REMOVAL_H
#define UTIL_REMOVAL_H

#include "betelgeuse.h"

/* The doomed items: a texture and a material that uses it (both added first, so removing them
 * moves every later material and texture to another dense index), a sphere of that material in
 * front of the others (added second, so removing it moves every later object), and a light
 * (added first). */
typedef struct util_doomed {
    uint32_t texture, material, sphere, light;
} util_doomed;

/* Builds into an empty scene and commits: `spheres` spheres on a grid (materials in turn: red,
 * mirror, checker-textured, glossy) before a wall, two lights. doomed NULL builds without the
 * doomed items; otherwise they are added and their handles written there. */
void util_removal_scene(bg_scene *s, int spheres, util_doomed *doomed);
/* Removes the doomed items in an order their references allow, and commits. */
void util_removal_remove(bg_scene *s, const util_doomed *doomed);

#endif
