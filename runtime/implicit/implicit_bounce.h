/* implicit_bounce.h — ComputeIlluminateLeafNodes and PullupEnergy (4.3,
 * 4.4; implicit_bounce.c). The caller owns a solution from create until
 * free. */
#ifndef GB_IMPLICIT_BOUNCE_H
#define GB_IMPLICIT_BOUNCE_H

#include "implicit_links.h"
#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* Steps 8-11. radiance: scratch; display: out, the incident radiance
 * (E / pi) the runtime's direct pass does not draw: the environment's,
 * through the empty bins (4.4), plus the indirect light summed over
 * bounces. Every array has a value a side (implicit_model.h's sides and
 * layout): element arrays 2 * element_count * 3, the fronts first; node
 * arrays 2 * node_count * 3. */
typedef struct gb_implicit_solution {
    float *direct;              /* elements: E / pi from lights */
    float *sky;                 /* elements: its environment part */
    float *radiance;            /* nodes: outgoing radiance */
    float *emission;            /* nodes: Le pulled up (fronts only) */
    float *display;             /* elements */
    float *gathered;            /* elements, scratch */
    float *storage;             /* the one allocation the six arrays view */
} gb_implicit_solution;

gb_result gb_implicit_solution_create(const gb_implicit_model *model,
                                      gb_implicit_solution *solution, gb_error *error);
void gb_implicit_solution_free(gb_implicit_solution *solution);
/* Direct light at the elements: area lights through the links, the
 * environment through the empty bins, point, spot and directional lights
 * unshadowed. Then bounces of indirect light into display. */
void gb_implicit_illuminate(const gb_scene *scene, const gb_implicit_model *model,
                            const gb_implicit_links *links, int bounces,
                            gb_implicit_solution *solution);
/* PullupEnergy of per-element values, a side after the other (node_count
 * * 3 a side, the elements' element_count * 3 first in each): each
 * internal node gets on each side the area-weighted mean of its
 * children's, a node of several segments that of their fronts on both. */
void gb_implicit_pullup(const gb_implicit_model *model, float *values);

#endif
