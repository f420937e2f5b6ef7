/* integrator.h — the radiance arriving along one camera ray, in each mode of
 * the reference renderer (tools/reference/reference.h says what each mode
 * counts). Thread-safe: all mutable state is the caller's gb_path_state.
 */
#ifndef GB_INTEGRATOR_H
#define GB_INTEGRATOR_H

#include "path_tracing.h"
#include "reference.h"

typedef struct gb_integrator {
    gb_path_tracer paths;
    const gb_vpl_set *vpls;     /* vpl mode */
    gb_reference_mode mode;
    int min_bounces, max_bounces; /* full mode */
} gb_integrator;

/* Radiance toward the camera along the unit direction dir from origin. */
gb_vec3 gb_integrator_radiance(const gb_integrator *integrator, gb_vec3 origin, gb_vec3 dir,
                               gb_path_state *state);

#endif
