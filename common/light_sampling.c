#include "light_sampling.h"

#include <math.h>
#include <stdlib.h>

#include "brdf.h"
#include "surface.h"

static double triangle_power(const gb_scene *scene, uint32_t t)
{
    const gb_material *material = &scene->materials[scene->triangle_material[t]];
    double luminance = gb_vec3_luminance(gb_vec3_load(material->Ke));
    return luminance > 0.0 ? (double)GB_PI * luminance * gb_triangle_area(scene, t) : 0.0;
}

gb_result gb_light_table_build(const gb_scene *scene, gb_light_table *table, gb_error *error)
{
    *table = (gb_light_table){0};
    uint32_t most = scene->emissive_count;
    double *power = malloc((most ? most : 1) * sizeof *power);
    table->triangles = malloc((most ? most : 1) * sizeof *table->triangles);
    table->area_pdf = calloc(scene->triangle_count ? scene->triangle_count : 1,
                             sizeof *table->area_pdf);
    gb_result result = power && table->triangles && table->area_pdf
                           ? GB_OK
                           : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "light table: out of memory");
    for (uint32_t i = 0; result == GB_OK && i < most; ++i) {
        uint32_t t = scene->emissive_triangles[i];
        power[table->count] = triangle_power(scene, t);
        if (power[table->count] > 0.0)
            table->triangles[table->count++] = t;
    }
    if (result == GB_OK)
        result = gb_cumulative_distribution_build(power, table->count, &table->by_power, error);
    for (uint32_t i = 0; result == GB_OK && i < table->count; ++i) {
        uint32_t t = table->triangles[i];
        double pick = gb_cumulative_distribution_probability(&table->by_power, i);
        table->area_pdf[t] = (float)(pick / gb_triangle_area(scene, t));
    }
    free(power);
    if (result != GB_OK)
        gb_light_table_free(table);
    return result;
}

void gb_light_table_free(gb_light_table *table)
{
    free(table->triangles);
    gb_cumulative_distribution_free(&table->by_power);
    free(table->area_pdf);
    *table = (gb_light_table){0};
}

int gb_light_table_sample(const gb_light_table *table, const gb_surface_table *surfaces,
                          float u_pick, float u1, float u2, gb_area_light_sample *sample)
{
    if (table->count == 0)
        return 0;
    uint32_t t = table->triangles[gb_cumulative_distribution_pick(&table->by_power, u_pick)];
    const gb_triangle_record *r = &surfaces->records[t];
    float root = sqrtf(u1);
    gb_vec3 p = gb_vec3_madd(gb_vec3_load(r->v0), gb_vec3_load(r->e1), u2 * root);
    sample->triangle = t;
    sample->position = gb_vec3_madd(p, gb_vec3_load(r->e2), 1.0f - root);
    sample->normal = gb_vec3_load(r->normal);
    sample->radiance = gb_vec3_load(surfaces->scene->materials[r->material].Ke);
    sample->pdf_area = table->area_pdf[t];
    sample->offset = r->offset;
    return 1;
}

float gb_light_table_pdf_area(const gb_light_table *table, uint32_t t)
{
    return table->area_pdf[t];
}

static void point_light(const gb_light *light, gb_vec3 x, gb_delta_light_sample *sample)
{
    gb_vec3 to_light = gb_vec3_sub(gb_vec3_load(light->position), x);
    float r2 = gb_vec3_dot(to_light, to_light);
    sample->distance = sqrtf(r2);
    sample->wi = gb_vec3_scale(to_light, 1.0f / sample->distance);
    sample->irradiance = gb_vec3_scale(gb_vec3_load(light->intensity), gb_inverse_square(r2));
}

int gb_delta_light_arriving(const gb_light *light, gb_vec3 x, gb_delta_light_sample *sample)
{
    switch (light->type) {
    case GB_LIGHT_POINT:
        point_light(light, x, sample);
        break;
    case GB_LIGHT_SPOT: {
        point_light(light, x, sample);
        gb_vec3 axis = gb_vec3_normalize(gb_vec3_load(light->direction));
        float falloff = gb_spot_falloff(-gb_vec3_dot(axis, sample->wi), light->cone_angle,
                                        light->falloff_angle);
        sample->irradiance = gb_vec3_scale(sample->irradiance, falloff);
        break;
    }
    case GB_LIGHT_DIRECTIONAL:
        sample->wi = gb_vec3_negate(gb_vec3_normalize(gb_vec3_load(light->direction)));
        sample->distance = INFINITY;
        sample->irradiance = gb_vec3_load(light->intensity);
        break;
    default:
        return 0;
    }
    return sample->distance > 0.0f && gb_vec3_max(sample->irradiance) > 0.0f;
}
