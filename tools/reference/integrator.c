/* integrator.c — each mode of the reference renderer: path tracing
 * (common/path_tracing.h) over a range of bounce counts, and the two special
 * first-bounce estimators (unshadowed, VPL). */
#include "integrator.h"

#include <math.h>

#include "brdf_sampling.h"
#include "surface.h"

enum { MAX_UNSHADOWED_LAYERS = 4096 };   /* surfaces crossed along one direction */

static const gb_vec3 BLACK = {0.0f, 0.0f, 0.0f};

/* indirect1-unshadowed: one BRDF direction from the first hit, and every
 * surface along it (not only the first) as the second vertex. */
static gb_vec3 trace_unshadowed(const gb_integrator *in, gb_vec3 origin, gb_vec3 dir,
                                gb_path_state *state)
{
    gb_hit hit;
    if (!gb_embree_intersect(in->paths.rays, origin, dir, 0.0f, INFINITY, &hit, &state->rays))
        return BLACK;
    gb_surface first;
    gb_surface_at_hit(in->paths.surfaces, &hit, dir, &first);
    gb_brdf_sample sample;
    float u_lobe = gb_path_uniform(state), u1 = gb_path_uniform(state), u2 = gb_path_uniform(state);
    if (!gb_brdf_sample_direction(gb_surface_brdf(in->paths.surfaces, &first), first.n, first.wo,
                                  u_lobe, u1, u2, &sample) ||
        gb_vec3_dot(first.ng, sample.wi) <= 0.0f)
        return BLACK;
    gb_vec3 start = gb_surface_ray_origin(&first, sample.wi), sum = BLACK;
    float tnear = 0.0f;
    for (int layer = 0; layer < MAX_UNSHADOWED_LAYERS; ++layer) {
        if (!gb_embree_intersect(in->paths.rays, start, sample.wi, tnear, INFINITY, &hit, &state->rays))
            break;
        gb_surface second;
        gb_surface_at_hit(in->paths.surfaces, &hit, sample.wi, &second);
        sum = gb_vec3_add(sum, gb_path_radiance_leaving(&in->paths, &second, 1, 1, state));
        tnear = hit.t + second.offset;
    }
    return gb_vec3_mul(sample.weight, sum);
}

/* The light of one VPL reflected at s toward s->wo, with its shadow ray. */
static gb_vec3 vpl_light(const gb_integrator *in, gb_surface *s, const gb_vpl *vpl,
                         gb_path_state *state)
{
    gb_vec3 position = gb_vec3_load(vpl->position);
    gb_vec3 to_vpl = gb_vec3_sub(position, s->position);
    float d2 = gb_vec3_dot(to_vpl, to_vpl);
    if (!(d2 > 0.0f))
        return BLACK;
    float distance = sqrtf(d2);
    gb_vec3 wi = gb_vec3_scale(to_vpl, 1.0f / distance);
    float emission = gb_vpl_emission(-gb_vec3_dot(gb_vec3_load(vpl->normal), wi));
    gb_vec3 power = gb_vec3_load(vpl->power);
    if (emission <= 0.0f || gb_vec3_is_zero(power) || !gb_path_reflects(s, wi))
        return BLACK;
    gb_vec3 origin = gb_surface_ray_origin(s, wi);
    float tfar = distance - 2.0f * gb_ray_offset(gb_vec3_max_abs(position));
    if (tfar > 0.0f && gb_embree_occluded(in->paths.rays, origin, wi, 0.0f, tfar, &state->rays))
        return BLACK;
    return gb_vec3_scale(gb_vec3_mul(gb_path_reflected(&in->paths, s, wi), power),
                         emission * gb_inverse_square(d2));
}

static gb_vec3 gather_vpls(const gb_integrator *in, gb_vec3 origin, gb_vec3 dir,
                           gb_path_state *state)
{
    gb_hit hit;
    if (!in->vpls ||
        !gb_embree_intersect(in->paths.rays, origin, dir, 0.0f, INFINITY, &hit, &state->rays))
        return BLACK;
    gb_surface s;
    gb_surface_at_hit(in->paths.surfaces, &hit, dir, &s);
    gb_vec3 sum = BLACK;
    for (uint32_t i = 0; i < in->vpls->count; ++i)
        sum = gb_vec3_add(sum, vpl_light(in, &s, &in->vpls->vpls[i], state));
    return sum;
}

gb_vec3 gb_integrator_radiance(const gb_integrator *in, gb_vec3 origin, gb_vec3 dir,
                               gb_path_state *state)
{
    switch (in->mode) {
    case GB_REFERENCE_DIRECT:
        return gb_path_radiance(&in->paths, origin, dir, 0, 1, state);
    case GB_REFERENCE_INDIRECT1:
        return gb_path_radiance(&in->paths, origin, dir, 2, 2, state);
    case GB_REFERENCE_INDIRECT1_UNSHADOWED:
        return trace_unshadowed(in, origin, dir, state);
    case GB_REFERENCE_VPL:
        return gather_vpls(in, origin, dir, state);
    case GB_REFERENCE_FULL:
    default:
        return gb_path_radiance(&in->paths, origin, dir, in->min_bounces, in->max_bounces, state);
    }
}
