/* trace.h — one photon path: from a light, hit after hit, each hit stored as
 * a photon (formats/photon_map.h) and reflected by the material's BRDF
 * (common/brdf.h, sampled by common/brdf_sampling) until it
 * leaves the scene, is absorbed or has made `bounces` reflections.
 *
 * Power is carried flux-preservingly (Jensen 2001 §5.1.3): at each
 * reflection the photon's power is multiplied by f cos / pdf; from reflection
 * roulette_start + 1 on, Russian roulette keeps it with probability
 * q = min(1, max(new power) / max(power)) and divides by q, so a photon of a
 * grey diffuse surface keeps its power and survives with probability Kd.
 * With interpolated (shading) normals the adjoint correction of Veach 1997
 * §5.3 is applied: cos_s(in) cos_g(out) / (cos_g(in) cos_s(out)), capped.
 *
 * Rays leave a surface from its hit point moved along the geometric normal
 * by gb_surface's offset: 2^-16 of the largest coordinate magnitude of the
 * triangle's corners, a bound on the float error of any point computed on it,
 * so a path never hits its own surface again, at 1e6 as at 1.
 */
#ifndef GB_PHOTONS_TRACE_H
#define GB_PHOTONS_TRACE_H

#include <stddef.h>
#include <stdint.h>

#include "embree_scene.h"
#include "surface.h"
#include "light_emission.h"
#include "photon_map.h"
#include "random.h"

/* The adjoint shading-normal correction never multiplies power by more. */
#define GB_PHOTONS_MAX_SHADING_CORRECTION 4.0f

typedef struct gb_photons_tracer {
    const gb_embree_scene *rays;
    const gb_surface_table *surfaces;
    unsigned bounces;           /* most reflections, 1..GB_PHOTON_MAX_BOUNCES */
    unsigned roulette_start;    /* reflections made before the roulette plays */
    gb_photon_store store;
} gb_photons_tracer;

/* One stored photon, as photon_run keeps them until the paths are done. */
typedef struct gb_photons_record {
    float position[3];
    float power[3];
    uint32_t direction;         /* gb_photon_pack_direction */
    uint32_t normal;            /* gb_photon_pack_normal, with the bounce count */
} gb_photons_record;

/* A growing list of records. */
typedef struct gb_photons_sink {
    gb_photons_record *records;
    size_t count, capacity;
} gb_photons_sink;

typedef struct gb_photons_counters {
    uint64_t rays;              /* rtcIntersect1 calls */
    uint64_t stored;
    uint64_t escaped;           /* rays that left the scene */
    uint64_t nonfinite;         /* paths ended because their power overflowed */
} gb_photons_counters;

/* Traces the path of ray, drawing from rng. Returns 0 only when the sink
 * cannot grow (out of memory). */
int gb_photons_trace_path(const gb_photons_tracer *tracer, const gb_emitted_ray *ray,
                          gb_random *rng, gb_photons_sink *sink, gb_photons_counters *counters);

void gb_photons_sink_free(gb_photons_sink *sink);

#endif
