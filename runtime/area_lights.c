#include "area_lights.h"

#include <math.h>
#include <stdlib.h>

#include "mat4.h"
#include "scene_triangles.h"

float gb_radical_inverse2(uint32_t i)
{
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    return (float)(i >> 8) * 0x1p-24f;
}

static double mean_emission(const gb_scene *scene, uint32_t t)
{
    const float *Ke = scene->materials[scene->triangle_material[t]].Ke;
    return ((double)Ke[0] + Ke[1] + Ke[2]) / 3.0;
}

/* cumulative[i + 1] = power of emissive triangles 0..i, as fractions of the
 * total (whose value is returned). */
static double cumulative_power(const gb_scene *scene, double *cumulative)
{
    cumulative[0] = 0.0;
    for (uint32_t i = 0; i < scene->emissive_count; ++i) {
        uint32_t t = scene->emissive_triangles[i];
        double power = mean_emission(scene, t) * gb_triangle_area(scene, t);
        cumulative[i + 1] = cumulative[i] + (power > 0.0 ? power : 0.0);
    }
    double total = cumulative[scene->emissive_count];
    for (uint32_t i = 1; total > 0.0 && i <= scene->emissive_count; ++i)
        cumulative[i] /= total;
    return total;
}

static uint32_t find_interval(const double *cumulative, uint32_t count, double u)
{
    uint32_t low = 0, high = count - 1;
    while (low < high) {
        uint32_t middle = (low + high) / 2;
        if (cumulative[middle + 1] <= u)
            low = middle + 1;
        else
            high = middle;
    }
    return low;
}

/* Uniform by area: the square-root map of (u, v) onto triangle t. */
static gb_vec3 point_on_triangle(const gb_scene *scene, uint32_t t, float u, float v)
{
    float s = sqrtf(u);
    gb_vec3 a = gb_triangle_corner(scene, t, 0), b = gb_triangle_corner(scene, t, 1), c = gb_triangle_corner(scene, t, 2);
    gb_vec3 p = gb_vec3_scale(a, 1.0f - s);
    p = gb_vec3_add(p, gb_vec3_scale(b, s * (1.0f - v)));
    return gb_vec3_add(p, gb_vec3_scale(c, s * v));
}

static void make_emitter(const gb_scene *scene, uint32_t t, double probability, uint32_t count,
                         float u, float v, gb_point_emitter *e)
{
    gb_vec3 normal = gb_triangle_normal(scene, t);
    gb_vec3 p = point_on_triangle(scene, t, u, v);
    e->position[0] = p.x, e->position[1] = p.y, e->position[2] = p.z;
    e->normal[0] = normal.x, e->normal[1] = normal.y, e->normal[2] = normal.z;
    double scale = gb_triangle_area(scene, t) / (count * probability);
    e->area = (float)scale;
    const float *Ke = scene->materials[scene->triangle_material[t]].Ke;
    for (int c = 0; c < 3; ++c)
        e->intensity[c] = (float)(Ke[c] * scale);
}

gb_result gb_area_light_sample(const gb_scene *scene, uint32_t count,
                               gb_point_emitter **emitters, uint32_t *emitter_count,
                               gb_error *error)
{
    *emitters = NULL;
    *emitter_count = 0;
    if (count == 0 || scene->emissive_count == 0)
        return GB_OK;
    double *cumulative = malloc(((size_t)scene->emissive_count + 1) * sizeof *cumulative);
    *emitters = calloc(count, sizeof **emitters);
    if (!cumulative || !*emitters) {
        free(cumulative);
        free(*emitters);
        *emitters = NULL;
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "area lights: out of memory");
    }
    if (cumulative_power(scene, cumulative) > 0.0) {
        for (uint32_t i = 0; i < count; ++i) {
            double u = (i + 0.5) / count;
            uint32_t k = find_interval(cumulative, scene->emissive_count, u);
            double probability = cumulative[k + 1] - cumulative[k];
            float rest = (float)((u - cumulative[k]) / probability);
            make_emitter(scene, scene->emissive_triangles[k], probability, count,
                         fminf(fmaxf(rest, 0.0f), 1.0f), gb_radical_inverse2(i),
                         &(*emitters)[i]);
        }
        *emitter_count = count;
    }
    free(cumulative);
    return GB_OK;
}
