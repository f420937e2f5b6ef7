/* trace.c — one photon path (trace.h). */
#include "trace.h"

#include <math.h>
#include <stdlib.h>

#include "array_reserve.h"
#include "brdf_sampling.h"

static int is_finite_colour(gb_vec3 c)
{
    return isfinite(c.x) && isfinite(c.y) && isfinite(c.z);
}

static int store(gb_photons_sink *sink, const gb_surface *surface, gb_vec3 power,
                 unsigned bounce)
{
    if (!gb_array_reserve(&sink->records, &sink->capacity, sink->count + 1,
                          sizeof *sink->records))
        return 0;
    gb_photons_record *r = &sink->records[sink->count++];
    float wo[3], ng[3];
    gb_vec3_store(surface->position, r->position);
    gb_vec3_store(power, r->power);
    gb_vec3_store(surface->wo, wo);
    gb_vec3_store(surface->ng, ng);
    r->direction = gb_photon_pack_direction(wo);
    r->normal = gb_photon_pack_normal(ng, bounce);
    return 1;
}

void gb_photons_sink_free(gb_photons_sink *sink)
{
    free(sink->records);
    *sink = (gb_photons_sink){0};
}

/* Veach's adjoint factor for light paths with shading normals: 1 without. */
static float shading_correction(const gb_surface *s, gb_vec3 out)
{
    if (s->n.x == s->ng.x && s->n.y == s->ng.y && s->n.z == s->ng.z)
        return 1.0f;
    float num = gb_vec3_dot(s->n, s->wo) * gb_vec3_dot(s->ng, out);
    float den = gb_vec3_dot(s->ng, s->wo) * gb_vec3_dot(s->n, out);
    if (!(den > 0.0f))
        return 0.0f;
    return fminf(num / den, GB_PHOTONS_MAX_SHADING_CORRECTION);
}

/* Russian roulette: 1 when the photon goes on, *power then divided by q. */
static int survives(gb_vec3 before, gb_vec3 *power, gb_random *rng)
{
    float q = fminf(1.0f, gb_vec3_max(*power) / gb_vec3_max(before));
    if (!(q > 0.0f) || gb_random_float(rng) >= q)
        return 0;
    *power = gb_vec3_scale(*power, 1.0f / q);
    return 1;
}

/* Reflects the photon at the surface: a new direction and power, or 0 when
 * the path ends there. */
static int reflect(const gb_photons_tracer *tracer, gb_surface *surface, unsigned reflection,
                   gb_random *rng, gb_vec3 *direction, gb_vec3 *power)
{
    float u_lobe = gb_random_float(rng), u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    const gb_brdf *brdf = gb_surface_brdf(tracer->surfaces, surface);
    gb_brdf_sample sample;
    if (!gb_brdf_sample_direction(brdf, surface->n, surface->wo, u_lobe, u1, u2, &sample))
        return 0;
    if (gb_vec3_dot(surface->ng, sample.wi) <= 0.0f)
        return 0;                       /* nothing shines through a surface */
    float correction = shading_correction(surface, sample.wi);
    gb_vec3 next = gb_vec3_scale(gb_vec3_mul(*power, sample.weight), correction);
    /* a material of negative reflectance reflects nothing */
    next = gb_vec3_make(fmaxf(next.x, 0.0f), fmaxf(next.y, 0.0f), fmaxf(next.z, 0.0f));
    if (reflection > tracer->roulette_start && !survives(*power, &next, rng))
        return 0;
    if (!(gb_vec3_max(next) > 0.0f))
        return 0;
    *direction = sample.wi;
    *power = next;
    return 1;
}

int gb_photons_trace_path(const gb_photons_tracer *tracer, const gb_emitted_ray *ray,
                          gb_random *rng, gb_photons_sink *sink, gb_photons_counters *counters)
{
    gb_vec3 origin = ray->origin, direction = ray->direction, power = ray->power;
    if (!(gb_vec3_max(power) > 0.0f))
        return 1;                       /* a black photon (the edge of a spot) */
    for (unsigned bounce = 0;; ++bounce) {
        if (!is_finite_colour(power)) {
            ++counters->nonfinite;
            return 1;
        }
        gb_hit hit;
        if (!gb_embree_intersect(tracer->rays, origin, direction, 0.0f, INFINITY, &hit,
                                 &counters->rays)) {
            ++counters->escaped;
            return 1;
        }
        gb_surface surface;
        gb_surface_at_hit(tracer->surfaces, &hit, direction, &surface);
        if (bounce > 0 || tracer->store == GB_PHOTON_STORE_ALL) {
            if (!store(sink, &surface, power, bounce))
                return 0;
            ++counters->stored;
        }
        if (bounce == tracer->bounces ||
            !reflect(tracer, &surface, bounce + 1, rng, &direction, &power))
            return 1;
        origin = gb_surface_ray_origin(&surface, direction);
    }
}
