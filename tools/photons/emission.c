/* emission.c — photons leaving the scene's lights (emission.h). */
#include "emission.h"

#include <math.h>
#include <stdlib.h>

#include "brdf.h"

enum { MAX_EMITTERS_BEYOND_LIGHTS = 2 };    /* the area lights, the environment */

static double luminance(const double c[3])
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

static void set_power(double power[3], const float colour[3], double scale)
{
    for (int k = 0; k < 3; ++k)
        power[k] = colour[k] > 0.0f ? scale * colour[k] : 0.0;
}

/* sum over emissive triangles of pi Ke A (RGB). */
static void area_power(const gb_scene *scene, const gb_light_table *table, double power[3])
{
    power[0] = power[1] = power[2] = 0.0;
    for (uint32_t i = 0; i < table->count; ++i) {
        uint32_t t = table->triangles[i];
        double one[3];
        set_power(one, scene->materials[scene->triangle_material[t]].Ke,
                  GB_PI * gb_triangle_area(scene, t));
        for (int k = 0; k < 3; ++k)
            power[k] += one[k];
    }
}

/* The solid angle a spot light's falloff integrates to. */
static double spot_solid_angle(const gb_light *light)
{
    double cos_cone = cos(light->cone_angle * (GB_PI / 180.0));
    double cos_falloff = cos(light->falloff_angle * (GB_PI / 180.0));
    if (cos_falloff < cos_cone)
        cos_falloff = cos_cone;
    return 2.0 * GB_PI * ((1.0 - cos_falloff) + 0.5 * (cos_falloff - cos_cone));
}

/* The disk area of directional and environment emission. */
static double disk_area(const gb_photon_emission *emission)
{
    return GB_PI * (double)emission->radius * (double)emission->radius;
}

static void delta_light_power(const gb_photon_emission *emission, const gb_light *light,
                              double power[3])
{
    switch (light->type) {
    case GB_LIGHT_POINT:
        set_power(power, light->intensity, 4.0 * GB_PI);
        return;
    case GB_LIGHT_SPOT:
        set_power(power, light->intensity, spot_solid_angle(light));
        return;
    case GB_LIGHT_DIRECTIONAL:
        set_power(power, light->intensity, disk_area(emission));
        return;
    }
    set_power(power, light->intensity, 0.0);
}

/* Appends an emitter whose power has positive, finite luminance. */
static void add_emitter(gb_photon_emission *emission, gb_photon_emitter_type type,
                        const gb_light *light, const double power[3])
{
    double lum = luminance(power);
    if (!(lum > 0.0) || !isfinite(lum))
        return;
    gb_photon_emitter *e = &emission->emitters[emission->emitter_count++];
    e->type = type;
    e->light = light;
    for (int k = 0; k < 3; ++k) {
        e->power[k] = power[k];
        emission->power[k] += power[k];
    }
}

static void find_bounding_sphere(const gb_scene *scene, gb_photon_emission *emission)
{
    gb_vec3 lo = gb_vec3_load(scene->bounds_min), hi = gb_vec3_load(scene->bounds_max);
    emission->centre = gb_vec3_scale(gb_vec3_add(lo, hi), 0.5f);
    float radius = 0.5f * gb_vec3_length(gb_vec3_sub(hi, lo));
    /* a flat or point-like scene still needs a disk of some size */
    emission->radius = fmaxf(radius, fmaxf(1e-6f, 1e-6f * gb_vec3_max_abs(emission->centre)));
}

static void add_emitters(const gb_scene *scene, gb_photon_emission *emission)
{
    double power[3];
    area_power(scene, &emission->area, power);
    add_emitter(emission, GB_EMITTER_AREA, NULL, power);
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        delta_light_power(emission, &scene->lights[i], power);
        add_emitter(emission, (gb_photon_emitter_type)(GB_EMITTER_POINT + scene->lights[i].type),
                    &scene->lights[i], power);
    }
    set_power(power, scene->environment, 4.0 * GB_PI * disk_area(emission));
    add_emitter(emission, GB_EMITTER_ENVIRONMENT, NULL, power);
}

static void build_cdf(gb_photon_emission *emission)
{
    double total = 0.0;
    emission->cdf[0] = 0.0;
    for (uint32_t i = 0; i < emission->emitter_count; ++i) {
        total += luminance(emission->emitters[i].power);
        emission->cdf[i + 1] = total;
    }
    for (uint32_t i = 1; i <= emission->emitter_count; ++i)
        emission->cdf[i] /= total;
    emission->cdf[emission->emitter_count] = 1.0;
}

gb_result gb_photon_emission_build(const gb_scene *scene, const gb_surface_table *surfaces,
                                   gb_photon_emission *emission, gb_error *error)
{
    *emission = (gb_photon_emission){.scene = scene, .surfaces = surfaces};
    gb_result result = gb_light_table_build(scene, &emission->area, error);
    if (result != GB_OK)
        return result;
    size_t most = (size_t)scene->light_count + MAX_EMITTERS_BEYOND_LIGHTS;
    emission->emitters = calloc(most, sizeof *emission->emitters);
    emission->cdf = calloc(most + 1, sizeof *emission->cdf);
    if (!emission->emitters || !emission->cdf) {
        gb_photon_emission_free(emission);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photons: out of memory");
    }
    find_bounding_sphere(scene, emission);
    add_emitters(scene, emission);
    if (emission->emitter_count)    /* none: a dark scene, nothing to emit */
        build_cdf(emission);
    return GB_OK;
}

void gb_photon_emission_free(gb_photon_emission *emission)
{
    gb_light_table_free(&emission->area);
    free(emission->emitters);
    free(emission->cdf);
    *emission = (gb_photon_emission){0};
}

/* ---- sampling ---- */

/* The emitter i with cdf[i] <= u < cdf[i + 1], skipping empty intervals. */
static uint32_t pick_emitter(const gb_photon_emission *emission, double u)
{
    uint32_t low = 0, high = emission->emitter_count;
    while (high - low > 1) {
        uint32_t middle = low + (high - low) / 2;
        if (emission->cdf[middle] <= u)
            low = middle;
        else
            high = middle;
    }
    return low;
}

/* A direction around axis whose cosine is uniform in [cos_max, 1]. */
static gb_vec3 sample_cone(gb_vec3 axis, float cos_max, float u1, float u2)
{
    float cos_theta = 1.0f - u1 * (1.0f - cos_max);
    float sin_theta = sqrtf(fmaxf(0.0f, 1.0f - cos_theta * cos_theta));
    float phi = 2.0f * GB_PI * u2;
    gb_vec3 t, b;
    gb_vec3_frame(axis, &t, &b);
    return gb_vec3_normalize(gb_vec3_from_frame(t, b, axis, sin_theta * cosf(phi),
                                                sin_theta * sinf(phi), cos_theta));
}

/* A cosine-weighted direction around n (Malley's method). */
static gb_vec3 sample_cosine(gb_vec3 n, float u1, float u2)
{
    float r = sqrtf(u1), phi = 2.0f * GB_PI * u2;
    gb_vec3 t, b;
    gb_vec3_frame(n, &t, &b);
    return gb_vec3_normalize(gb_vec3_from_frame(t, b, n, r * cosf(phi), r * sinf(phi),
                                                sqrtf(fmaxf(0.0f, 1.0f - u1))));
}

static gb_vec3 scaled_colour(const float colour[3], double scale)
{
    double power[3];
    set_power(power, colour, scale);
    return gb_vec3_make((float)power[0], (float)power[1], (float)power[2]);
}

/* Area light: Ke cos / (pdf_area cos / pi) = pi Ke / pdf_area, over the pick
 * probability and the photon count (`share`). */
static void emit_area(const gb_photon_emission *emission, double share, gb_random *rng,
                      gb_photon_ray *ray)
{
    float u_pick = gb_random_float(rng), u1 = gb_random_float(rng);
    float u2 = gb_random_float(rng), u3 = gb_random_float(rng), u4 = gb_random_float(rng);
    gb_area_light_sample s;
    gb_light_table_sample(&emission->area, emission->surfaces, u_pick, u1, u2, &s);
    ray->origin = gb_vec3_madd(s.position, s.normal, s.offset);
    ray->direction = sample_cosine(s.normal, u3, u4);
    float radiance[3];
    gb_vec3_store(s.radiance, radiance);
    ray->power = scaled_colour(radiance, GB_PI / (s.pdf_area * share));
}

static void emit_point(const gb_light *light, double share, gb_random *rng,
                       gb_photon_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    ray->origin = gb_vec3_load(light->position);
    ray->direction = sample_cone(gb_vec3_make(0.0f, 0.0f, 1.0f), -1.0f, u1, u2);
    ray->power = scaled_colour(light->intensity, 4.0 * GB_PI / share);
}

static void emit_spot(const gb_light *light, double share, gb_random *rng, gb_photon_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    gb_vec3 axis = gb_vec3_normalize(gb_vec3_load(light->direction));
    float cos_cone = cosf(light->cone_angle * (GB_PI / 180.0f));
    ray->origin = gb_vec3_load(light->position);
    ray->direction = sample_cone(axis, cos_cone, u1, u2);
    float falloff = gb_spot_falloff(gb_vec3_dot(axis, ray->direction), light->cone_angle,
                                    light->falloff_angle);
    double solid_angle = 2.0 * GB_PI * (1.0 - (double)cos_cone);
    ray->power = scaled_colour(light->intensity, falloff * solid_angle / share);
}

/* A point of the disk of the bounding sphere facing direction, 2R before the
 * centre. */
static gb_vec3 disk_point(const gb_photon_emission *emission, gb_vec3 direction, float u1, float u2)
{
    float r = emission->radius * sqrtf(u1), phi = 2.0f * GB_PI * u2;
    gb_vec3 t, b;
    gb_vec3_frame(direction, &t, &b);
    gb_vec3 centre = gb_vec3_madd(emission->centre, direction, -2.0f * emission->radius);
    return gb_vec3_add(centre, gb_vec3_from_frame(t, b, direction, r * cosf(phi),
                                                  r * sinf(phi), 0.0f));
}

static void emit_directional(const gb_photon_emission *emission, const gb_light *light,
                             double share, gb_random *rng, gb_photon_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    ray->direction = gb_vec3_normalize(gb_vec3_load(light->direction));
    ray->origin = disk_point(emission, ray->direction, u1, u2);
    ray->power = scaled_colour(light->intensity, disk_area(emission) / share);
}

static void emit_environment(const gb_photon_emission *emission, double share, gb_random *rng,
                             gb_photon_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    float u3 = gb_random_float(rng), u4 = gb_random_float(rng);
    ray->direction = sample_cone(gb_vec3_make(0.0f, 0.0f, 1.0f), -1.0f, u1, u2);
    ray->origin = disk_point(emission, ray->direction, u3, u4);
    ray->power = scaled_colour(emission->scene->environment,
                               4.0 * GB_PI * disk_area(emission) / share);
}

void gb_photon_emission_sample(const gb_photon_emission *emission, uint64_t count,
                               gb_random *rng, gb_photon_ray *ray)
{
    uint32_t i = pick_emitter(emission, gb_random_float(rng));
    const gb_photon_emitter *e = &emission->emitters[i];
    /* the probability of picking e, times the photons emitted */
    double share = (emission->cdf[i + 1] - emission->cdf[i]) * (double)count;
    switch (e->type) {
    case GB_EMITTER_AREA:
        emit_area(emission, share, rng, ray);
        return;
    case GB_EMITTER_POINT:
        emit_point(e->light, share, rng, ray);
        return;
    case GB_EMITTER_SPOT:
        emit_spot(e->light, share, rng, ray);
        return;
    case GB_EMITTER_DIRECTIONAL:
        emit_directional(emission, e->light, share, rng, ray);
        return;
    case GB_EMITTER_ENVIRONMENT:
        emit_environment(emission, share, rng, ray);
        return;
    }
}
