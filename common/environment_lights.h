/* environment_lights.h — a scene's environment (its colour or lat-long
 * map, formats/environment.h) as a few directional lights, so that every
 * method lights surfaces by the sky with the shadows of its directional
 * lights: Debevec's median cut ("A Median Cut Algorithm for Light Probe
 * Sampling", 2005).
 *
 * The sphere of directions, as a lat-long grid of the map's texels (or of
 * GB_ENVIRONMENT_GRID_WIDTH x _HEIGHT cells of a constant colour), is cut
 * into count regions of equal energy: the region of most energy is split
 * across its longer side (its width measured at its middle latitude) where
 * the energy, luminance x solid angle, halves. Each region becomes one
 * directional light from its energy centroid, of irradiance the region's
 * sum of L dOmega (so that a surface facing it receives what the region
 * sends, up to the spread of the region's directions).
 *
 * Nothing is kept: the caller owns the scene and the lights. */
#ifndef GB_ENVIRONMENT_LIGHTS_H
#define GB_ENVIRONMENT_LIGHTS_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

enum {
    GB_MOST_ENVIRONMENT_LIGHTS = 64,   /* what a scene lit by its sky alone gets */
    GB_ENVIRONMENT_GRID_WIDTH = 64,     /* a constant colour's lat-long cells */
    GB_ENVIRONMENT_GRID_HEIGHT = 32,
};

/* The environment's share of the light power entering the scene, in 0..1:
 * the power of the sky (L its mean radiance) against that of the scene's
 * own lights, all as common/light_emission.h weighs them, by luminance. 0
 * for a black sky. */
double gb_environment_share(const gb_scene *scene);

/* How many lights stand for the environment by default: most times its
 * share, rounded up (64 on a scene lit by its sky alone; 6 on Sponza,
 * whose sun and point light outshine its sky: each light costs the direct
 * pass as much as the sun). */
uint32_t gb_environment_light_count(const gb_scene *scene, uint32_t most);

/* Fills lights[0 .. *made) with at most count directional lights (fewer
 * when the environment has fewer cells; none when it is black). */
gb_result gb_environment_lights(const gb_scene *scene, uint32_t count, gb_light *lights,
                                uint32_t *made, gb_error *error);

/* Appends gb_environment_lights(scene, count) to scene->lights (the scene's
 * own lights first, unchanged) and counts them in
 * scene->environment_light_count. */
gb_result gb_scene_add_environment_lights(gb_scene *scene, uint32_t count, gb_error *error);

#endif
