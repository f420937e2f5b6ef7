/* emission.h — where photons start: a light of the scene chosen by its power,
 * then a point and a direction on it, and the photon's power, so that the
 * powers of N emitted photons sum, in expectation, to the scene's total
 * emitted power (flux-preserving emission, Jensen 2001 §5.1).
 *
 * Lights (conventions of common/brdf.h):
 *   area          the emissive triangles as one light of power sum pi Ke A,
 *                 a triangle picked by power (common/light_sampling),
 *                 a point uniform on it, a cosine-weighted direction on its
 *                 front side;
 *   point         power 4 pi I, uniform directions;
 *   spot          power 2 pi I ((1 - cos falloff) + (cos falloff - cos cone) / 2)
 *                 (the smoothstep of gb_spot_falloff integrates to 1/2),
 *                 directions uniform in the cone, each weighted by the falloff;
 *   directional   irradiance E through a disk of radius R (the scene's
 *                 bounding sphere) facing it, placed 2R before the centre:
 *                 power E pi R^2;
 *   environment   radiance L from every direction through the same disk
 *                 turned to face each direction: power 4 pi L pi R^2.
 * Each light is picked with probability proportional to the luminance of its
 * power, so every photon not from a spot leaves with the same luminance.
 *
 * The caller owns the gb_photon_emission and frees it with
 * gb_photon_emission_free; the scene must outlive it.
 */
#ifndef GB_PHOTONS_EMISSION_H
#define GB_PHOTONS_EMISSION_H

#include <stdint.h>

#include "light_sampling.h"
#include "surface.h"
#include "vec3.h"
#include "random.h"
#include "scene.h"

typedef enum gb_photon_emitter_type {
    GB_EMITTER_AREA,            /* every emissive triangle */
    GB_EMITTER_POINT,
    GB_EMITTER_SPOT,
    GB_EMITTER_DIRECTIONAL,
    GB_EMITTER_ENVIRONMENT,
} gb_photon_emitter_type;

typedef struct gb_photon_emitter {
    gb_photon_emitter_type type;
    const gb_light *light;      /* point, spot, directional; else NULL */
    double power[3];            /* W, RGB */
} gb_photon_emitter;

typedef struct gb_photon_emission {
    const gb_scene *scene;
    const gb_surface_table *surfaces;
    gb_light_table area;        /* the emissive triangles by power */
    uint32_t emitter_count;
    gb_photon_emitter *emitters;
    double *cdf;                /* emitter_count + 1: cumulative luminance fraction */
    double power[3];            /* W: sum of the emitters' power */
    gb_vec3 centre;             /* bounding sphere of the scene */
    float radius;
} gb_photon_emission;

/* A photon leaving a light. */
typedef struct gb_photon_ray {
    gb_vec3 origin;
    gb_vec3 direction;          /* unit, the way it travels */
    gb_vec3 power;              /* W: its share of `count` emitted photons */
} gb_photon_ray;

/* surfaces: the surface table of the scene, which must outlive the emission.
 * A scene with no light (gb_scene_has_light) gets emitter_count 0 and power
 * 0: gb_photon_emission_sample must not be called then. */
gb_result gb_photon_emission_build(const gb_scene *scene, const gb_surface_table *surfaces,
                                   gb_photon_emission *emission, gb_error *error);
void gb_photon_emission_free(gb_photon_emission *emission);

/* Emits one photon of a run of `count`, drawing from rng. */
void gb_photon_emission_sample(const gb_photon_emission *emission, uint64_t count,
                               gb_random *rng, gb_photon_ray *ray);

#endif
