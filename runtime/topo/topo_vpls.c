/* topo_vpls.c — the VPLs of the topological method (Noël & Biri 2014, §V:
 * instant radiosity, Keller 1997): paths traced with Embree from the primary
 * lights, a VPL at each hit. A directional light sends its paths from a
 * disk facing it that covers the scene's bounding sphere. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "embree_scene.h"
#include "light_sampling.h"
#include "surface.h"
#include "random.h"
#include "topo.h"

enum { MAX_PATH_VERTICES = 16 };

/* The primary lights as one discrete distribution: index 0 is every area
 * light together (the light table picks among them), 1 + i light i. */
typedef struct emitters {
    uint32_t count;
    double *cdf;                /* count + 1 */
    gb_light_table table;
    gb_surface_table surfaces;
    const gb_scene *scene;
} emitters;

typedef struct path_start {
    gb_vec3 origin, direction, flux;
} path_start;

static float spot_solid_angle(const gb_light *light)
{
    return 2.0f * (float)GB_PI * (1.0f - cosf(light->cone_angle * (float)GB_PI / 180.0f));
}

/* The scene's bounding sphere: centre and radius. */
static float bounding_sphere(const gb_scene *scene, gb_vec3 *centre)
{
    gb_vec3 lo = gb_vec3_load(scene->bounds_min), hi = gb_vec3_load(scene->bounds_max);
    *centre = gb_vec3_scale(gb_vec3_add(lo, hi), 0.5f);
    return 0.5f * gb_vec3_length(gb_vec3_sub(hi, lo)) * 1.001f;
}

static double light_power(const gb_scene *scene, const gb_light *light)
{
    gb_vec3 I = gb_vec3_load(light->intensity), centre;
    float radius = bounding_sphere(scene, &centre);
    switch (light->type) {
    case GB_LIGHT_POINT: return 4.0 * GB_PI * gb_vec3_luminance(I);
    case GB_LIGHT_SPOT: return spot_solid_angle(light) * gb_vec3_luminance(I);
    case GB_LIGHT_DIRECTIONAL: return GB_PI * radius * radius * gb_vec3_luminance(I);
    }
    return 0.0;
}

static gb_result emitters_build(const gb_scene *scene, emitters *e, gb_error *error)
{
    memset(e, 0, sizeof *e);
    e->scene = scene;
    e->count = 1 + scene->light_count;
    e->cdf = calloc(e->count + 1, sizeof *e->cdf);
    if (!e->cdf)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "VPLs: out of memory");
    gb_result result = gb_light_table_build(scene, &e->table, error);
    if (result == GB_OK)
        result = gb_surface_table_build(scene, &e->surfaces, error);
    if (result != GB_OK)
        return result;
    for (uint32_t i = 0; i < e->count; ++i)
        e->cdf[i + 1] = e->cdf[i] + (i == 0 ? e->table.total_power
                                            : light_power(scene, &scene->lights[i - 1]));
    return GB_OK;
}

static void emitters_free(emitters *e)
{
    free(e->cdf);
    gb_light_table_free(&e->table);
    gb_surface_table_free(&e->surfaces);
}

static gb_vec3 cosine_direction(gb_vec3 n, float u1, float u2)
{
    gb_vec3 t, b;
    gb_vec3_frame(n, &t, &b);
    float r = sqrtf(u1), phi = 2.0f * (float)GB_PI * u2;
    return gb_vec3_from_frame(t, b, n, r * cosf(phi), r * sinf(phi), sqrtf(fmaxf(0.0f, 1.0f - u1)));
}

/* Uniform on the cone of half-angle acos(cos_max) around axis. */
static gb_vec3 cone_direction(gb_vec3 axis, float cos_max, float u1, float u2)
{
    gb_vec3 t, b;
    gb_vec3_frame(axis, &t, &b);
    float z = 1.0f - u1 * (1.0f - cos_max), r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    float phi = 2.0f * (float)GB_PI * u2;
    return gb_vec3_from_frame(t, b, axis, r * cosf(phi), r * sinf(phi), z);
}

static uint32_t pick_emitter(const emitters *e, float u, double *probability)
{
    double target = u * e->cdf[e->count];
    uint32_t i = 0;
    while (i + 1 < e->count && e->cdf[i + 1] <= target)
        ++i;
    while (e->cdf[i + 1] - e->cdf[i] <= 0.0)   /* never a light of no power */
        i = (i + 1) % e->count;
    *probability = (e->cdf[i + 1] - e->cdf[i]) / e->cdf[e->count];
    return i;
}

/* Flux leaving an area light along a cosine direction: Ke pi / pdf_area. */
static int start_on_area_light(const emitters *e, gb_random *rng, path_start *start)
{
    gb_area_light_sample s;
    float u = gb_random_float(rng), u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    if (!gb_light_table_sample(&e->table, &e->surfaces, u, u1, u2, &s) || !(s.pdf_area > 0.0f))
        return 0;
    start->direction = cosine_direction(s.normal, gb_random_float(rng), gb_random_float(rng));
    start->origin = gb_vec3_madd(s.position, s.normal, s.offset);
    start->flux = gb_vec3_scale(s.radiance, (float)GB_PI / s.pdf_area);
    return 1;
}

/* Uniform on the disk of radius R facing the light, R outside the scene:
 * flux E pi R^2. */
static void start_on_directional_light(const gb_scene *scene, const gb_light *light, float u1,
                                       float u2, path_start *start)
{
    gb_vec3 centre, t, b, d = gb_vec3_normalize(gb_vec3_load(light->direction));
    float radius = bounding_sphere(scene, &centre);
    gb_vec3_frame(d, &t, &b);
    float r = radius * sqrtf(u1), phi = 2.0f * (float)GB_PI * u2;
    start->origin = gb_vec3_add(gb_vec3_madd(centre, d, -radius),
                                gb_vec3_from_frame(t, b, d, r * cosf(phi), r * sinf(phi), 0.0f));
    start->direction = d;
    start->flux = gb_vec3_scale(gb_vec3_load(light->intensity), (float)GB_PI * radius * radius);
}

static int start_on_delta_light(const gb_scene *scene, const gb_light *light, gb_random *rng,
                                path_start *start)
{
    gb_vec3 I = gb_vec3_load(light->intensity);
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    if (light->type == GB_LIGHT_DIRECTIONAL) {
        start_on_directional_light(scene, light, u1, u2, start);
        return 1;
    }
    start->origin = gb_vec3_load(light->position);
    if (light->type == GB_LIGHT_POINT) {
        start->direction = cone_direction(gb_vec3_make(0.0f, 0.0f, 1.0f), -1.0f, u1, u2);
        start->flux = gb_vec3_scale(I, 4.0f * (float)GB_PI);
        return 1;
    }
    float cos_cone = cosf(light->cone_angle * (float)GB_PI / 180.0f);
    float cos_falloff = cosf(light->falloff_angle * (float)GB_PI / 180.0f);
    gb_vec3 axis = gb_vec3_load(light->direction);
    start->direction = cone_direction(axis, cos_cone, u1, u2);
    float c = gb_vec3_dot(start->direction, axis), falloff = 1.0f;
    if (c < cos_falloff && cos_falloff > cos_cone) {   /* common/brdf.h smoothstep */
        float t = (c - cos_cone) / (cos_falloff - cos_cone);
        falloff = t * t * (3.0f - 2.0f * t);
    }
    start->flux = gb_vec3_scale(I, falloff * spot_solid_angle(light));
    return 1;
}

static int start_path(const emitters *e, gb_random *rng, path_start *start)
{
    double probability;
    uint32_t i = pick_emitter(e, gb_random_float(rng), &probability);
    if (!(i == 0 ? start_on_area_light(e, rng, start)
                 : start_on_delta_light(e->scene, &e->scene->lights[i - 1], rng, start)))
        return 0;
    start->flux = gb_vec3_scale(start->flux, (float)(1.0 / probability));
    return 1;
}

/* Follows one path, appending its VPLs to set (up to count). */
static void trace_path(const emitters *e, const gb_embree_scene *rays, gb_random *rng,
                       uint32_t count, gb_vpl_set *set)
{
    path_start p = {0};
    if (!start_path(e, rng, &p))
        return;
    uint64_t ray_count = 0;
    for (int vertex = 0; vertex < MAX_PATH_VERTICES && set->count < count; ++vertex) {
        gb_hit hit;
        if (!gb_embree_intersect(rays, p.origin, p.direction, 0.0f, INFINITY, &hit, &ray_count))
            return;
        gb_surface s;
        gb_surface_at_hit(&e->surfaces, &hit, p.direction, &s);
        gb_vec3 Kd = gb_vec3_load(gb_surface_brdf(&e->surfaces, &s)->Kd);
        gb_vec3 power = gb_vec3_mul(p.flux, Kd);
        if (gb_vec3_is_zero(power))
            return;
        gb_vpl *vpl = &set->vpls[set->count++];
        gb_vec3_store(s.position, vpl->position);
        gb_vec3_store(s.ng, vpl->normal);
        gb_vec3_store(power, vpl->power);
        float survive = fminf(1.0f, gb_vec3_max(Kd));   /* Russian roulette */
        if (gb_random_float(rng) >= survive)
            return;
        p.flux = gb_vec3_scale(power, 1.0f / survive);
        p.direction = cosine_direction(s.ng, gb_random_float(rng), gb_random_float(rng));
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
    emitters e;
    gb_embree_scene *rays = NULL;
    gb_result result = emitters_build(scene, &e, error);
    if (result == GB_OK)
        result = gb_embree_scene_create(scene, 1, &rays, error);
    if (result == GB_OK && !(set->vpls = calloc(count, sizeof *set->vpls)))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "VPLs: out of memory");
    uint64_t paths = 0;
    /* No light to trace from (gbview warned): no VPL, no indirect light. */
    int dark = result == GB_OK && !(e.cdf[e.count] > 0.0);
    for (; result == GB_OK && !dark && set->count < count; ++paths) {
        if (paths > 1000u * (uint64_t)count) {   /* light that never reaches a surface */
            result = gb_fail(error, GB_ERROR_INVALID,
                             "VPLs: %u paths from the lights hit no reflecting surface",
                             (unsigned)paths);
            break;
        }
        gb_random rng = gb_random_make(seed, paths);
        trace_path(&e, rays, &rng, count, set);
    }
    if (result == GB_OK) {
        divide_power(set, paths);
        set->scene_hash = scene->hash;
    } else {
        gb_vpl_free(set);
    }
    if (rays)
        gb_embree_scene_destroy(rays);
    emitters_free(&e);
    return result;
}
