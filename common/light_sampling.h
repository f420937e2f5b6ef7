/* light_sampling.h — choosing where light comes from, for next-event
 * estimation in the reference renderer.
 *
 * Area lights (the emissive triangles) are sampled by power, then uniformly
 * by area on the chosen triangle: one sample per shading point. Point, spot
 * and directional lights are delta lights: each is evaluated at every
 * shading point (one shadow ray each). Conventions: common/brdf.h.
 *
 * The caller owns the gb_light_table and frees it with gb_light_table_free.
 */
#ifndef GB_LIGHT_SAMPLING_H
#define GB_LIGHT_SAMPLING_H

#include <stdint.h>

#include "cumulative_distribution.h"
#include "scene.h"
#include "surface.h"
#include "vec3.h"

typedef struct gb_light_table {
    uint32_t count;             /* emissive triangles of nonzero power */
    uint32_t *triangles;        /* count: their indices in the scene */
    gb_cumulative_distribution by_power;   /* over triangles: pi luminance(Ke) area */
    float *area_pdf;            /* triangle_count: P(pick t) / area(t); 0 if t does not emit */
} gb_light_table;

typedef struct gb_area_light_sample {
    uint32_t triangle;
    gb_vec3 position;
    gb_vec3 normal;             /* the front (emitting) normal */
    gb_vec3 radiance;           /* Ke */
    float pdf_area;             /* density per unit area of picking this point */
    float offset;               /* ray offset of the triangle */
} gb_area_light_sample;

typedef struct gb_delta_light_sample {
    gb_vec3 wi;                 /* unit, from the point toward the light */
    float distance;             /* to the light; INFINITY for a directional light */
    gb_vec3 irradiance;         /* on a surface facing wi, before visibility */
} gb_delta_light_sample;

gb_result gb_light_table_build(const gb_scene *scene, gb_light_table *table, gb_error *error);
void gb_light_table_free(gb_light_table *table);

/* Picks a point on an area light from three uniform numbers in [0, 1), the
 * triangle's shape read from the surface table of the same scene. Returns 0
 * when the scene has no area light. */
int gb_light_table_sample(const gb_light_table *table, const gb_surface_table *surfaces,
                          float u_pick, float u1, float u2, gb_area_light_sample *sample);

/* Density per unit area with which gb_light_table_sample picks a point of
 * triangle t. */
float gb_light_table_pdf_area(const gb_light_table *table, uint32_t t);

/* The light of a point, spot or directional light arriving at x. Returns 0
 * when none arrives (outside a spot's cone, black light). */
int gb_delta_light_arriving(const gb_light *light, gb_vec3 x, gb_delta_light_sample *sample);

#endif
