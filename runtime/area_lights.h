/* area_lights.h — the scene's emissive triangles as a few shadowed point
 * emitters, which is how the runtime's direct lighting sees area lights.
 *
 * The approximation: count points are placed on the emissive triangles,
 * power-weighted and deterministic (no random seed): point i takes
 * u = (i + 0.5) / count through the cumulative power of the triangles
 * (power ~ mean(Ke) x area) to choose its triangle, the rest of u and the
 * base-2 radical inverse of i to choose a point on it (uniform by area).
 * Each point is a one-sided Lambertian emitter of its triangle's normal:
 * intensity I(w) = I0 max(0, dot(normal, w)) with
 * I0 = Ke area / (count p), p the probability of choosing that triangle, so
 * that the points' total power equals the lights' (pi |Ke| area summed).
 * Each gets a shadow map of its own (shadow_maps.h). The error shrinks as
 * count grows: penumbrae become count overlapping hard shadows.
 * Near a light a point's 1/r^2 would grow without bound where the surface
 * it stands for gives at most pi Ke: each point also carries the area it
 * stands for, area / (count p), and lights as a disc of that area does
 * on its axis, I cos / (r^2 + area / pi) (exact for a receiver facing a
 * uniform disc; far from the light, r^2 >> area, it is the point's 1/r^2).
 */
#ifndef GB_AREA_LIGHTS_H
#define GB_AREA_LIGHTS_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

typedef struct gb_point_emitter {
    float position[3];
    float normal[3];            /* unit: the emitting side */
    float intensity[3];         /* I0, W/sr along the normal */
    float area;                 /* the emitting area it stands for */
} gb_point_emitter;

/* *emitters (malloc'ed, the caller frees) gets count points, or none when
 * the scene has no emissive triangle or count is 0. */
gb_result gb_area_light_sample(const gb_scene *scene, uint32_t count,
                               gb_point_emitter **emitters, uint32_t *emitter_count,
                               gb_error *error);

/* Base-2 radical inverse (van der Corput) of i, in [0, 1). */
float gb_radical_inverse2(uint32_t i);

#endif
