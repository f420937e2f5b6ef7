/* light_emission.c — rays leaving the scene's lights (light_emission.h). */
#include "light_emission.h"

#include <math.h>
#include <stdlib.h>

#include "brdf.h"
#include "direction_sampling.h"

enum { MOST_EMITTERS_BEYOND_LIGHTS = 2 };    /* the area lights, the environment */

double gb_power_luminance(const double power[3])
{
    return 0.2126 * power[0] + 0.7152 * power[1] + 0.0722 * power[2];
}

static void set_power(double power[3], const float colour[3], double scale)
{
    for (int k = 0; k < 3; ++k)
        power[k] = colour[k] > 0.0f ? scale * colour[k] : 0.0;
}

void gb_area_light_power(const gb_scene *scene, uint32_t t, double power[3])
{
    set_power(power, scene->materials[scene->triangle_material[t]].Ke,
              GB_PI * gb_triangle_area(scene, t));
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

/* pi R^2: the disc of directional and environment emission. */
static double disc_area(float R)
{
    return GB_PI * (double)R * (double)R;
}

void gb_delta_light_power(const gb_light *light, float R, double power[3])
{
    switch (light->type) {
    case GB_LIGHT_POINT:
        set_power(power, light->intensity, 4.0 * GB_PI);
        return;
    case GB_LIGHT_SPOT:
        set_power(power, light->intensity, spot_solid_angle(light));
        return;
    case GB_LIGHT_DIRECTIONAL:
        set_power(power, light->intensity, disc_area(R));
        return;
    }
    set_power(power, light->intensity, 0.0);
}

void gb_sky_power(const float L[3], float R, double power[3])
{
    set_power(power, L, 4.0 * GB_PI * disc_area(R));
}

float gb_scene_bounding_sphere(const gb_scene *scene, gb_vec3 *centre)
{
    gb_vec3 lo = gb_vec3_load(scene->bounds_min), hi = gb_vec3_load(scene->bounds_max);
    *centre = gb_vec3_scale(gb_vec3_add(lo, hi), 0.5f);
    float R = 0.5f * gb_vec3_length(gb_vec3_sub(hi, lo));
    /* a flat or point-like scene still needs a disc of some size */
    return fmaxf(R, fmaxf(1e-6f, 1e-6f * gb_vec3_max_abs(*centre)));
}

/* Appends an emitter whose power has positive, finite luminance. */
static void add_emitter(gb_light_emission *emission, gb_emitter_type type,
                        const gb_light *light, const double power[3])
{
    double luminance = gb_power_luminance(power);
    if (!(luminance > 0.0) || !isfinite(luminance))
        return;
    gb_emitter *e = &emission->emitters[emission->emitter_count++];
    e->type = type;
    e->light = light;
    for (int k = 0; k < 3; ++k) {
        e->power[k] = power[k];
        emission->power[k] += power[k];
    }
}

static void add_emitters(const gb_scene *scene, gb_sky_emission sky,
                         gb_light_emission *emission)
{
    double power[3] = {0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < emission->area.count; ++i) {
        double one[3];
        gb_area_light_power(scene, emission->area.triangles[i], one);
        for (int k = 0; k < 3; ++k)
            power[k] += one[k];
    }
    add_emitter(emission, GB_EMITTER_AREA, NULL, power);
    for (uint32_t i = 0; i < scene->light_count; ++i) {
        gb_delta_light_power(&scene->lights[i], emission->radius, power);
        add_emitter(emission, (gb_emitter_type)(GB_EMITTER_POINT + scene->lights[i].type),
                    &scene->lights[i], power);
    }
    if (sky == GB_SKY_EMITTED) {
        gb_sky_power(scene->environment, emission->radius, power);
        add_emitter(emission, GB_EMITTER_ENVIRONMENT, NULL, power);
    }
}

gb_result gb_light_emission_build(const gb_scene *scene, const gb_surface_table *surfaces,
                                  gb_sky_emission sky, gb_light_emission *emission,
                                  gb_error *error)
{
    *emission = (gb_light_emission){.scene = scene, .surfaces = surfaces};
    gb_result result = gb_light_table_build(scene, &emission->area, error);
    if (result != GB_OK)
        return result;
    size_t most = (size_t)scene->light_count + MOST_EMITTERS_BEYOND_LIGHTS;
    emission->emitters = calloc(most, sizeof *emission->emitters);
    double *luminance = calloc(most, sizeof *luminance);
    if (!emission->emitters || !luminance)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "light emission: out of memory");
    if (result == GB_OK) {
        emission->radius = gb_scene_bounding_sphere(scene, &emission->centre);
        add_emitters(scene, sky, emission);
        for (uint32_t i = 0; i < emission->emitter_count; ++i)
            luminance[i] = gb_power_luminance(emission->emitters[i].power);
        result = gb_cumulative_distribution_build(luminance, emission->emitter_count,
                                                  &emission->by_luminance, error);
    }
    free(luminance);
    if (result != GB_OK)
        gb_light_emission_free(emission);
    return result;
}

void gb_light_emission_free(gb_light_emission *emission)
{
    gb_light_table_free(&emission->area);
    free(emission->emitters);
    gb_cumulative_distribution_free(&emission->by_luminance);
    *emission = (gb_light_emission){0};
}

/* ---- sampling ---- */

static gb_vec3 scaled_colour(const float colour[3], double scale)
{
    double power[3];
    set_power(power, colour, scale);
    return gb_vec3_make((float)power[0], (float)power[1], (float)power[2]);
}

/* Area light: pi Ke / pdf_area, over the pick probability and the ray
 * count (`share`). */
static void emit_area(const gb_light_emission *emission, double share, gb_random *rng,
                      gb_emitted_ray *ray)
{
    float u_pick = gb_random_float(rng), u1 = gb_random_float(rng);
    float u2 = gb_random_float(rng), u3 = gb_random_float(rng), u4 = gb_random_float(rng);
    gb_area_light_sample s;
    gb_light_table_sample(&emission->area, emission->surfaces, u_pick, u1, u2, &s);
    ray->origin = gb_vec3_madd(s.position, s.normal, s.offset);
    ray->direction = gb_cosine_direction(s.normal, u3, u4);
    float radiance[3];
    gb_vec3_store(s.radiance, radiance);
    ray->power = scaled_colour(radiance, GB_PI / (s.pdf_area * share));
}

static void emit_point(const gb_light *light, double share, gb_random *rng,
                       gb_emitted_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    ray->origin = gb_vec3_load(light->position);
    ray->direction = gb_cone_direction(gb_vec3_make(0.0f, 0.0f, 1.0f), -1.0f, u1, u2);
    ray->power = scaled_colour(light->intensity, 4.0 * GB_PI / share);
}

static void emit_spot(const gb_light *light, double share, gb_random *rng,
                      gb_emitted_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    gb_vec3 axis = gb_vec3_normalize(gb_vec3_load(light->direction));
    float cos_cone = cosf(light->cone_angle * (GB_PI / 180.0f));
    ray->origin = gb_vec3_load(light->position);
    ray->direction = gb_cone_direction(axis, cos_cone, u1, u2);
    float falloff = gb_spot_falloff(gb_vec3_dot(axis, ray->direction), light->cone_angle,
                                    light->falloff_angle);
    double solid_angle = 2.0 * GB_PI * (1.0 - (double)cos_cone);
    ray->power = scaled_colour(light->intensity, falloff * solid_angle / share);
}

/* A point of the disc of radius R facing direction, its centre 2R before
 * the sphere's. */
static gb_vec3 disc_origin(const gb_light_emission *emission, gb_vec3 direction, float u1,
                           float u2)
{
    gb_vec3 centre = gb_vec3_madd(emission->centre, direction, -2.0f * emission->radius);
    return gb_disc_point(centre, direction, emission->radius, u1, u2);
}

static void emit_directional(const gb_light_emission *emission, const gb_light *light,
                             double share, gb_random *rng, gb_emitted_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    ray->direction = gb_vec3_normalize(gb_vec3_load(light->direction));
    ray->origin = disc_origin(emission, ray->direction, u1, u2);
    ray->power = scaled_colour(light->intensity, disc_area(emission->radius) / share);
}

static void emit_environment(const gb_light_emission *emission, double share, gb_random *rng,
                             gb_emitted_ray *ray)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    float u3 = gb_random_float(rng), u4 = gb_random_float(rng);
    ray->direction = gb_cone_direction(gb_vec3_make(0.0f, 0.0f, 1.0f), -1.0f, u1, u2);
    ray->origin = disc_origin(emission, ray->direction, u3, u4);
    ray->power = scaled_colour(emission->scene->environment,
                               4.0 * GB_PI * disc_area(emission->radius) / share);
}

void gb_light_emission_sample(const gb_light_emission *emission, uint64_t count,
                              gb_random *rng, gb_emitted_ray *ray)
{
    uint32_t i = gb_cumulative_distribution_pick(&emission->by_luminance,
                                                 gb_random_float(rng));
    const gb_emitter *e = &emission->emitters[i];
    /* the probability of picking e, times the rays emitted */
    double share = gb_cumulative_distribution_probability(&emission->by_luminance, i) *
                   (double)count;
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
