/* final_gather.h — a surface point's indirect irradiance by a final gather
 * (Jensen 1996, photon mapping's final gather; vivianloc-2007 §3.3's
 * reconstruction one bounce away): `rays` directions drawn by cos θ / π
 * about the shading normal n, each traced with Embree to the surface y it
 * meets, which sends back toward x
 *     octree: the light of paths of 1..octree_bounces reflections from y on
 *             (common/path_tracing.h; 1: the light reflected once at y),
 *             plus, where such a path stops, Kd / π times the octree's
 *             irradiance there (light_octree_shading.h), the light that
 *             arrives after more: the octree's errors reach x only through
 *             octree_bounces + 1 reflections, averaged over the hemisphere;
 *     paths:  every path of 1..max_bounces reflections from y on (the
 *             octree unused): unbiased, the limit of the octree's gather.
 * A direction below ng or one that meets nothing brings no indirect light
 * (the background it sees is direct light). The estimate is
 *     E = π / rays · Σ L(y_j → x).
 * The directions are a rank-1 lattice (j / rays, j φ) shifted by one
 * random offset (Cranley and Patterson), mapped by Malley's method: each
 * is cosine-distributed, together they cover the hemisphere evenly.
 *
 * The probe says whether a point looks into the open, where a camera can
 * be: of `rays` such directions, those meeting a triangle's front at least
 * near_distance away, less those meeting a back (inside a solid) or a
 * front nearer (a gap no camera fits in: a ceiling just above a light).
 *
 * The random numbers come from the caller's state only, so a texel's value
 * depends on its stream, never on the thread that computes it. The caller
 * owns the tracer's tables, the octree and the state. Thread-safe (reads
 * only, but the state).
 */
#ifndef GB_FINAL_GATHER_H
#define GB_FINAL_GATHER_H

#include <stdint.h>

#include "light_octree.h"
#include "path_tracing.h"
#include "texel_surface.h"

typedef struct gb_final_gather {
    gb_path_tracer paths;
    const gb_light_octree *octree;  /* read at the hits; NULL: paths traced on */
    int max_bounces;                /* paths: most reflections, y's the first */
    int octree_bounces;             /* octree: reflections traced before it is read, >= 1 */
    float near_distance;            /* a gap narrower than this is closed */
} gb_final_gather;

/* The irradiance E (W/m^2, linear RGB) at p from `rays` directions, which
 * leave from p->x moved offset along p->ng. Returns the harmonic mean of
 * the distances the rays travel to the scene, rays / Σ 1/t (a ray that
 * meets nothing counts as infinitely long; INFINITY when none meets it):
 * the scale over which E changes (Ward, Rubinstein and Clear 1988's R_i,
 * texel_interpolation.h). */
float gb_final_gather_irradiance(const gb_final_gather *gather, const gb_texel_surface *p,
                                float offset, int rays, gb_path_state *state, float out[3]);

/* Open minus closed directions of `rays` at p (Embree's closest hits only). */
int gb_final_gather_openness(const gb_final_gather *gather, const gb_texel_surface *p,
                             float offset, int rays, gb_path_state *state);

#endif
