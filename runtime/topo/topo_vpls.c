/* topo_vpls.c — the VPLs of the topological method (Noël & Biri 2014, §V:
 * instant radiosity, Keller 1997): paths traced with Embree from the primary
 * lights as common/light_emission.h emits them (the sky through its
 * directional lights), a VPL at each hit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "direction_sampling.h"
#include "embree_scene.h"
#include "light_emission.h"
#include "surface.h"
#include "random.h"
#include "topo.h"

enum { MAX_PATH_VERTICES = 16 };

/* Follows one path, appending its VPLs to set (up to count). */
static void trace_path(const gb_light_emission *emission, const gb_embree_scene *rays,
                       gb_random *rng, uint32_t count, gb_vpl_set *set)
{
    gb_emitted_ray p;
    gb_light_emission_sample(emission, 1, rng, &p);
    uint64_t ray_count = 0;
    for (int vertex = 0; vertex < MAX_PATH_VERTICES && set->count < count; ++vertex) {
        gb_hit hit;
        if (!gb_embree_intersect(rays, p.origin, p.direction, 0.0f, INFINITY, &hit, &ray_count))
            return;
        gb_surface s;
        gb_surface_at_hit(emission->surfaces, &hit, p.direction, &s);
        gb_vec3 Kd = gb_vec3_load(gb_surface_brdf(emission->surfaces, &s)->Kd);
        gb_vec3 power = gb_vec3_mul(p.power, Kd);
        if (gb_vec3_is_zero(power))
            return;
        gb_vpl *vpl = &set->vpls[set->count++];
        gb_vec3_store(s.position, vpl->position);
        gb_vec3_store(s.ng, vpl->normal);
        gb_vec3_store(power, vpl->power);
        float survive = fminf(1.0f, gb_vec3_max(Kd));   /* Russian roulette */
        if (gb_random_float(rng) >= survive)
            return;
        p.power = gb_vec3_scale(power, 1.0f / survive);
        float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
        p.direction = gb_cosine_direction(s.ng, u1, u2);
        p.origin = gb_surface_ray_origin(&s, p.direction);
    }
}

static void divide_power(gb_vpl_set *set, uint64_t paths)
{
    float scale = paths ? (float)(1.0 / (double)paths) : 0.0f;
    for (uint32_t i = 0; i < set->count; ++i)
        for (int c = 0; c < 3; ++c)
            set->vpls[i].power[c] *= scale;
}

gb_result gb_topo_vpls_generate(const gb_scene *scene, uint32_t count, uint64_t seed,
                                gb_vpl_set *set, gb_error *error)
{
    memset(set, 0, sizeof *set);
    if (count == 0 || count > (1u << 24))
        return gb_fail(error, GB_ERROR_ARGUMENT, "--vpls %u is not in 1..16777216", count);
    gb_surface_table surfaces;
    gb_light_emission emission = {0};
    gb_embree_scene *rays = NULL;
    gb_result result = gb_surface_table_build(scene, &surfaces, error);
    if (result != GB_OK)
        return result;
    result = gb_light_emission_build(scene, &surfaces, GB_SKY_AS_LIGHTS, &emission, error);
    if (result == GB_OK)
        result = gb_embree_scene_create(scene, 1, &rays, error);
    if (result == GB_OK && !(set->vpls = calloc(count, sizeof *set->vpls)))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "VPLs: out of memory");
    uint64_t paths = 0;
    /* No light to trace from (gbview warned): no VPL, no indirect light. */
    int dark = result == GB_OK && emission.emitter_count == 0;
    for (; result == GB_OK && !dark && set->count < count; ++paths) {
        if (paths > 1000u * (uint64_t)count) {   /* light that never reaches a surface */
            result = gb_fail(error, GB_ERROR_INVALID,
                             "VPLs: %u paths from the lights hit no reflecting surface",
                             (unsigned)paths);
            break;
        }
        gb_random rng = gb_random_make(seed, paths);
        trace_path(&emission, rays, &rng, count, set);
    }
    if (result == GB_OK) {
        divide_power(set, paths);
        set->scene_hash = scene->hash;
    } else {
        gb_vpl_free(set);
    }
    if (rays)
        gb_embree_scene_destroy(rays);
    gb_light_emission_free(&emission);
    gb_surface_table_free(&surfaces);
    return result;
}
