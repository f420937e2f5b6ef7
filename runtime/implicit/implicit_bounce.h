/* implicit_bounce.h — ComputeIlluminateLeafNodes and PullupEnergy (4.3,
 * 4.4; implicit_bounce.c). The caller owns a solution from create until
 * free. */
#ifndef GB_IMPLICIT_BOUNCE_H
#define GB_IMPLICIT_BOUNCE_H

#include "implicit_links.h"
#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* Steps 8-11. radiance: node_count * 3 scratch; display: element_count * 3
 * out, the incident radiance (E / pi) the runtime's direct pass does not
 * draw: the environment's, through the empty bins (4.4), plus the indirect
 * light summed over bounces. */
typedef struct gb_implicit_solution {
    float *direct;              /* element_count * 3: E / pi from lights */
    float *sky;                 /* element_count * 3: its environment part */
    float *radiance;            /* node_count * 3: outgoing radiance */
    float *emission;            /* node_count * 3: Le pulled up */
    float *display;             /* element_count * 3 */
    float *gathered;            /* element_count * 3 scratch */
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
/* PullupEnergy of per-element values (element_count * 3 at the start of
 * values, node_count * 3 in all): each internal node gets the area-weighted
 * mean of its children. */
void gb_implicit_pullup(const gb_implicit_model *model, float *values);

#endif
