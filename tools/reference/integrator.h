/* integrator.h — the radiance arriving along one camera ray, in each mode of
 * the reference renderer (tools/reference/reference.h says what each mode
 * counts). Thread-safe: all mutable state is the caller's gb_trace_state.
 */
#ifndef GB_INTEGRATOR_H
#define GB_INTEGRATOR_H

#include "embree_scene.h"
#include "light_sampling.h"
#include "random.h"
#include "reference.h"
#include "surface.h"
#include "vec3.h"

typedef struct gb_integrator {
    const gb_scene *scene;
    const gb_embree_scene *rays;
    const gb_surface_table *surfaces;
    const gb_light_table *lights;
    const gb_vpl_set *vpls;     /* vpl mode */
    gb_reference_mode mode;
    int min_bounces, max_bounces; /* full mode */
} gb_integrator;

typedef struct gb_trace_state {
    gb_random rng;              /* the pixel's stream */
    uint64_t rays;              /* rays traced so far */
} gb_trace_state;

/* Radiance toward the camera along the unit direction dir from origin. */
gb_vec3 gb_integrator_radiance(const gb_integrator *integrator, gb_vec3 origin, gb_vec3 dir,
                               gb_trace_state *state);

#endif
