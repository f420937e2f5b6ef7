/* final_gather.c — a point's indirect irradiance gathered one bounce away
 * (final_gather.h). */
#include "final_gather.h"

#include <math.h>

#include "direction_sampling.h"
#include "light_octree_shading.h"

static const float PI = 3.14159265358979f;
static const float GOLDEN_RATIO_FRACTION = 0.618033988749895f;
static const float BELOW_ONE = 0x1.fffffep-1f;

/* Kd(s) / π times the octree's irradiance at s: the light s reflects
 * toward s->wo of what arrives there after a bounce or more. */
static gb_vec3 octree_reflected(const void *context, gb_surface *s)
{
    const gb_final_gather *gather = context;
    float p[3], n[3], ng[3], e[3];
    gb_vec3_store(s->position, p);
    gb_vec3_store(s->n, n);
    gb_vec3_store(s->ng, ng);
    gb_light_octree_irradiance(gather->octree, p, n, ng, e);
    const float *Kd = gb_surface_brdf(gather->paths.surfaces, s)->Kd;
    return gb_vec3_mul(gb_vec3_scale(gb_vec3_load(Kd), 1.0f / PI), gb_vec3_load(e));
}

/* The light y sends back toward the gathering point. */
static gb_vec3 light_from(const gb_final_gather *gather, gb_surface *y, gb_path_state *state)
{
    if (!gather->octree)
        return gb_path_radiance_leaving(&gather->paths, y, 1, gather->max_bounces, state);
    gb_path_tracer paths = gather->paths;
    paths.beyond = octree_reflected;
    paths.beyond_context = gather;
    return gb_path_radiance_leaving(&paths, y, 1, gather->octree_bounces, state);
}

/* The lattice's directions about n, shifted by (shift[0], shift[1]). */
typedef struct lattice {
    gb_vec3 n;
    int rays;
    float shift[2];
} lattice;

static lattice lattice_make(gb_vec3 n, int rays, gb_path_state *state)
{
    lattice l = {n, rays, {gb_path_uniform(state), gb_path_uniform(state)}};
    return l;
}

static gb_vec3 lattice_direction(const lattice *l, int j)
{
    float u1 = ((float)j + 0.5f) / (float)l->rays + l->shift[0];
    float u2 = (float)j * GOLDEN_RATIO_FRACTION + l->shift[1];
    u1 -= floorf(u1);
    u2 -= floorf(u2);
    return gb_cosine_direction(l->n, fminf(u1, BELOW_ONE), fminf(u2, BELOW_ONE));
}

/* The closest hit along dir from origin, off p; 0 when dir leaves below
 * p's ng or meets nothing. */
static int trace(const gb_final_gather *gather, const gb_texel_surface *p, gb_vec3 origin,
                 gb_vec3 dir, gb_hit *hit, gb_path_state *state)
{
    return gb_vec3_dot(dir, p->ng) > 0.0f &&
           gb_embree_intersect(gather->paths.rays, origin, dir, 0.0f, INFINITY, hit,
                               &state->rays);
}

float gb_final_gather_irradiance(const gb_final_gather *gather, const gb_texel_surface *p,
                                 float offset, int rays, gb_path_state *state, float out[3])
{
    lattice l = lattice_make(p->n, rays, state);
    gb_vec3 origin = gb_vec3_madd(p->x, p->ng, offset);
    gb_vec3 sum = {0.0f, 0.0f, 0.0f};
    double inverse_distances = 0.0;
    for (int j = 0; j < rays; ++j) {
        gb_vec3 dir = lattice_direction(&l, j);
        gb_hit hit;
        if (!trace(gather, p, origin, dir, &hit, state))
            continue;
        inverse_distances += 1.0 / fmax(hit.t, 1e-30);
        gb_surface y;
        gb_surface_at_hit(gather->paths.surfaces, &hit, dir, &y);
        sum = gb_vec3_add(sum, light_from(gather, &y, state));
    }
    gb_vec3_store(gb_vec3_scale(sum, PI / (float)rays), out);
    return inverse_distances > 0.0 ? (float)((double)rays / inverse_distances) : INFINITY;
}

int gb_final_gather_openness(const gb_final_gather *gather, const gb_texel_surface *p,
                             float offset, int rays, gb_path_state *state)
{
    lattice l = lattice_make(p->n, rays, state);
    gb_vec3 origin = gb_vec3_madd(p->x, p->ng, offset);
    int openness = 0;
    for (int j = 0; j < rays; ++j) {
        gb_vec3 dir = lattice_direction(&l, j);
        gb_hit hit;
        if (!trace(gather, p, origin, dir, &hit, state))
            continue;
        const float *front = gather->paths.surfaces->records[hit.triangle].normal;
        int open = gb_vec3_dot(gb_vec3_load(front), dir) < 0.0f &&
                   hit.t >= gather->near_distance;
        openness += open ? 1 : -1;
    }
    return openness;
}
