/* light_emission.h — light leaving the scene's lights: a light chosen by its
 * power, then a point and a direction on it, and the power the ray carries,
 * so that the powers of N emitted rays sum, in expectation, to the scene's
 * total emitted power (flux-preserving emission, Jensen 2001 §5.1). The
 * photons of tools/photons and the VPL paths of runtime/topo start here, and
 * the environment's share of the light (environment_lights.h) is weighed
 * with the same powers.
 *
 * Lights (conventions of common/brdf.h), R the radius of the scene's
 * bounding sphere (gb_scene_bounding_sphere):
 *   area          the emissive triangles as one light of power sum pi Ke A,
 *                 a triangle picked by power (light_sampling.h), a point
 *                 uniform on it, a cosine-weighted direction on its front
 *                 side: Ke cos / (pdf_area cos / pi) = pi Ke / pdf_area;
 *   point         power 4 pi I, directions uniform on the sphere;
 *   spot          power 2 pi I ((1 - cos falloff) + (cos falloff - cos cone) / 2)
 *                 (the smoothstep of gb_spot_falloff integrates to 1/2),
 *                 directions uniform in the cone, each weighted by the falloff;
 *   directional   irradiance E through a disc of radius R facing it, centred
 *                 on the sphere's centre pushed 2R back against the light:
 *                 every ray parallel to the light, power E pi R^2;
 *   environment   radiance L from every direction through the same disc
 *                 turned to face each direction: power 4 pi L pi R^2.
 * Each light is picked with probability proportional to the luminance of its
 * power (cumulative_distribution.h), so every ray not from a spot leaves
 * with the same luminance.
 *
 * Decided here: the disc of a directional light. Any disc of radius R
 * perpendicular to the light and centred on the line through the sphere's
 * centre covers the projection of the whole scene along the light, and
 * every ray from it meets the scene where the parallel ray from the far side
 * of the sphere would: its distance only has to keep it outside the sphere
 * (at least R). 2R keeps it outside with room against rounding. A scene
 * flat or reduced to a point still gets a disc of radius 1e-6 (relative to
 * its position).
 *
 * The caller owns the gb_light_emission and frees it with
 * gb_light_emission_free; the scene and the surface table must outlive it.
 */
#ifndef GB_LIGHT_EMISSION_H
#define GB_LIGHT_EMISSION_H

#include <stdint.h>

#include "cumulative_distribution.h"
#include "light_sampling.h"
#include "random.h"
#include "scene.h"
#include "surface.h"
#include "vec3.h"

typedef enum gb_emitter_type {
    GB_EMITTER_AREA,            /* every emissive triangle */
    GB_EMITTER_POINT,
    GB_EMITTER_SPOT,
    GB_EMITTER_DIRECTIONAL,
    GB_EMITTER_ENVIRONMENT,
} gb_emitter_type;

typedef struct gb_emitter {
    gb_emitter_type type;
    const gb_light *light;      /* point, spot, directional; else NULL */
    double power[3];            /* W, RGB */
} gb_emitter;

/* What stands for the scene's environment. */
typedef enum gb_sky_emission {
    GB_SKY_EMITTED,             /* the environment itself, an emitter (photons) */
    GB_SKY_AS_LIGHTS,           /* the directional lights gb_scene_add_environment_lights
                                   appended to the scene (the runtime) */
} gb_sky_emission;

typedef struct gb_light_emission {
    const gb_scene *scene;
    const gb_surface_table *surfaces;
    gb_light_table area;        /* the emissive triangles by power */
    uint32_t emitter_count;     /* the lights of positive, finite power */
    gb_emitter *emitters;
    gb_cumulative_distribution by_luminance;   /* over the emitters */
    double power[3];            /* W: sum of the emitters' power */
    gb_vec3 centre;             /* the bounding sphere of the scene */
    float radius;
} gb_light_emission;

/* A ray leaving a light. */
typedef struct gb_emitted_ray {
    gb_vec3 origin;
    gb_vec3 direction;          /* unit, the way it travels */
    gb_vec3 power;              /* W: its share of `count` emitted rays */
} gb_emitted_ray;

/* surfaces: the surface table of the scene. A scene with no light
 * (gb_scene_has_light) gets emitter_count 0 and power 0:
 * gb_light_emission_sample must not be called then. */
gb_result gb_light_emission_build(const gb_scene *scene, const gb_surface_table *surfaces,
                                  gb_sky_emission sky, gb_light_emission *emission,
                                  gb_error *error);
void gb_light_emission_free(gb_light_emission *emission);

/* Emits one ray of a run of `count`, drawing from rng. */
void gb_light_emission_sample(const gb_light_emission *emission, uint64_t count,
                              gb_random *rng, gb_emitted_ray *ray);

/* ---- the powers, for whoever weighs lights against each other ---- */

/* The radius R of the scene's bounding sphere (the sphere through the
 * corners of its bounding box), and its centre. */
float gb_scene_bounding_sphere(const gb_scene *scene, gb_vec3 *centre);

/* The power (W, RGB) of a point, spot or directional light in a scene of
 * bounding radius R; a negative channel counts as 0. */
void gb_delta_light_power(const gb_light *light, float R, double power[3]);

/* The power of a sky of mean radiance L entering a scene of bounding
 * radius R: 4 pi L pi R^2. */
void gb_sky_power(const float L[3], float R, double power[3]);

/* The power of emissive triangle t: pi Ke A. */
void gb_area_light_power(const gb_scene *scene, uint32_t t, double power[3]);

/* Rec. 709 luminance of a power. */
double gb_power_luminance(const double power[3]);

#endif
