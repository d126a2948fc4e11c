/* The scenes of bench_distribution: one per effect of distribution ray tracing (docs/shading.md 1.3,
 * 1.4, 7 and 9.1), each the size of the example scenes (examples/scenes/json: a few objects, one or
 * two lights), so that a sample's cost compares with those scenes' frames in the other tables. Each
 * scene holds its own effect only (point lights and a pinhole where the effect is another), so a
 * row measures that effect. */
#ifndef DISTRIBUTION_SCENES_H
#define DISTRIBUTION_SCENES_H

#include <stdbool.h>

#include "betelgeuse.h"

/* Each fills an empty scene, without committing (the caller commits and reports the scene's message),
 * and returns the first failure. Deterministic. With effect false it builds the scene's plain twin:
 * the same objects and materials with the effect taken out (area lights as point lights at their
 * centre or middle, a pinhole, mirrors in place of glossy lobes, and for the environment a sun as a
 * directional light of its direction and an ambient term in place of the sky), which costs what the
 * scene costs but for the effect. */

/* A floor, two spheres, a box and a cylinder under a sphere light and a rectangle light, no mirrors:
 * the soft shadows are the only noise. */
bg_status distribution_area_lights(bg_scene *scene, bool effect);
/* Five spheres receding over a checkered floor, a thin lens focused on the middle one (the earth
 * texture, sharp), the nearer and farther ones blurred by up to about 20 pixels at 512x512; two
 * point lights, one mirror sphere. */
bg_status distribution_depth_of_field(bg_scene *scene, bool effect);
/* Glossy spheres of roughness 0.1 and 0.25 and a glossy coated one, reflecting a checkered floor, a
 * two-colour checkered wall and diffuse spheres; two point lights, a pinhole. */
bg_status distribution_glossy(bg_scene *scene, bool effect);
/* A floor, a diffuse, a glossy and a small sphere lit only by an environment of a blue sky and a
 * small bright sun (no lights, no ambient), its light drawn by importance or uniformly: the two rows
 * compare the rules at equal sample counts and, with their times, at equal time. */
bg_status distribution_environment_importance(bg_scene *scene, bool effect);
bg_status distribution_environment_uniform(bg_scene *scene, bool effect);

#endif
