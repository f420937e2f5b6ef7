#include "environment_lights.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "environment.h"
#include "light_emission.h"
#include "vec3.h"

static const double PI = 3.14159265358979323846;

/* The environment on a lat-long grid: each cell's radiance and its energy
 * (luminance x solid angle), row 0 looking along +y. */
typedef struct environment_grid {
    int width, height;
    float *radiance;            /* width * height * 3 */
    double *energy;             /* width * height */
} environment_grid;

/* The unit direction toward the sky at lat-long (u, v) in [0, 1]^2. */
static void direction_at(double u, double v, double d[3])
{
    double phi = (u - 0.5) * 2.0 * PI, theta = v * PI;
    d[0] = sin(theta) * sin(phi);
    d[1] = cos(theta);
    d[2] = -sin(theta) * cos(phi);
}

static double cell_solid_angle(const environment_grid *g, int row)
{
    double theta0 = PI * row / g->height, theta1 = PI * (row + 1) / g->height;
    return 2.0 * PI / g->width * (cos(theta0) - cos(theta1));
}

static double luminance(const float *rgb)
{
    return gb_vec3_luminance(gb_vec3_load(rgb));
}

static gb_result make_grid(const gb_scene *scene, environment_grid *g, gb_error *error)
{
    const gb_texture *map = &scene->environment_texture;
    int has_map = map->rgb && map->width > 0 && map->height > 0;
    g->width = has_map ? map->width : GB_ENVIRONMENT_GRID_WIDTH;
    g->height = has_map ? map->height : GB_ENVIRONMENT_GRID_HEIGHT;
    size_t cells = (size_t)g->width * g->height;
    g->radiance = malloc(cells * 3 * sizeof *g->radiance);
    g->energy = malloc(cells * sizeof *g->energy);
    if (!g->radiance || !g->energy)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "environment lights: out of memory");
    for (int row = 0; row < g->height; ++row) {
        double solid_angle = cell_solid_angle(g, row);
        for (int column = 0; column < g->width; ++column) {
            size_t i = (size_t)row * g->width + column;
            float *L = &g->radiance[3 * i];
            if (has_map)
                memcpy(L, &map->rgb[3 * i], 3 * sizeof *L);
            else
                memcpy(L, scene->environment, 3 * sizeof *L);
            double y = luminance(L);
            g->energy[i] = y > 0.0 ? y * solid_angle : 0.0;
        }
    }
    return GB_OK;
}

/* A rectangle of cells, [column0, column1) x [row0, row1). */
typedef struct region {
    int column0, column1, row0, row1;
    double energy;
} region;

static double region_energy(const environment_grid *g, region r)
{
    double sum = 0.0;
    for (int row = r.row0; row < r.row1; ++row)
        for (int column = r.column0; column < r.column1; ++column)
            sum += g->energy[(size_t)row * g->width + column];
    return sum;
}

/* Whether r is wider than tall on the sphere: its width in radians shrinks
 * by the sine of its middle latitude. */
static int wider_than_tall(const environment_grid *g, region r)
{
    double middle = PI * 0.5 * (r.row0 + r.row1) / g->height;
    double width = 2.0 * PI * (r.column1 - r.column0) / g->width * sin(middle);
    double height = PI * (r.row1 - r.row0) / g->height;
    return width > height;
}

/* Splits r across its longer side where its energy halves; 0 when it is
 * one cell thick that way. */
static int split_region(const environment_grid *g, region r, region *a, region *b)
{
    int across_columns = wider_than_tall(g, r);
    if (across_columns ? r.column1 - r.column0 < 2 : r.row1 - r.row0 < 2)
        across_columns = !across_columns;
    int lo = across_columns ? r.column0 : r.row0, hi = across_columns ? r.column1 : r.row1;
    if (hi - lo < 2)
        return 0;
    double sum = 0.0;
    int cut = lo + 1;
    for (; cut < hi - 1; ++cut) {
        region slice = r;
        if (across_columns)
            slice.column0 = cut - 1, slice.column1 = cut;
        else
            slice.row0 = cut - 1, slice.row1 = cut;
        sum += region_energy(g, slice);
        if (sum >= 0.5 * r.energy)
            break;
    }
    *a = r, *b = r;
    if (across_columns)
        a->column1 = cut, b->column0 = cut;
    else
        a->row1 = cut, b->row0 = cut;
    a->energy = region_energy(g, *a);
    b->energy = region_energy(g, *b);
    return 1;
}

/* The region of most energy that can still be split, or -1. */
static int richest_region(const region *regions, const unsigned char *whole, uint32_t n)
{
    int best = -1;
    for (uint32_t i = 0; i < n; ++i)
        if (!whole[i] && regions[i].energy > 0.0 &&
            (best < 0 || regions[i].energy > regions[best].energy))
            best = (int)i;
    return best;
}

/* The region as a directional light: from its energy centroid, of
 * irradiance its sum of L dOmega. */
static void region_light(const environment_grid *g, region r, gb_light *light)
{
    double centre[3] = {0, 0, 0}, irradiance[3] = {0, 0, 0};
    for (int row = r.row0; row < r.row1; ++row) {
        double solid_angle = cell_solid_angle(g, row);
        for (int column = r.column0; column < r.column1; ++column) {
            size_t i = (size_t)row * g->width + column;
            double d[3];
            direction_at((column + 0.5) / g->width, (row + 0.5) / g->height, d);
            for (int c = 0; c < 3; ++c) {
                centre[c] += g->energy[i] * d[c];
                irradiance[c] += g->radiance[3 * i + c] * solid_angle;
            }
        }
    }
    double length = sqrt(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
    memset(light, 0, sizeof *light);
    light->type = GB_LIGHT_DIRECTIONAL;
    for (int c = 0; c < 3; ++c) {
        light->direction[c] = length > 0.0 ? (float)(-centre[c] / length) : (c == 1 ? -1.0f : 0.0f);
        light->intensity[c] = (float)irradiance[c];
    }
}

static uint32_t median_cut(const environment_grid *g, uint32_t count, region *regions,
                           unsigned char *whole)
{
    regions[0] = (region){0, g->width, 0, g->height, 0.0};
    regions[0].energy = region_energy(g, regions[0]);
    if (!(regions[0].energy > 0.0))
        return 0;
    uint32_t n = 1;
    whole[0] = 0;
    while (n < count) {
        int i = richest_region(regions, whole, n);
        if (i < 0)
            break;
        region a, b;
        if (!split_region(g, regions[i], &a, &b)) {
            whole[i] = 1;
            continue;
        }
        regions[i] = a;
        regions[n] = b;
        whole[n++] = 0;
    }
    return n;
}

gb_result gb_environment_lights(const gb_scene *scene, uint32_t count, gb_light *lights,
                                uint32_t *made, gb_error *error)
{
    *made = 0;
    if (count == 0)
        return GB_OK;
    environment_grid g = {0};
    region *regions = malloc(count * sizeof *regions);
    unsigned char *whole = malloc(count);
    gb_result result = regions && whole ? make_grid(scene, &g, error)
                                        : gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                                                  "environment lights: out of memory");
    if (result == GB_OK) {
        uint32_t n = median_cut(&g, count, regions, whole);
        for (uint32_t i = 0; i < n; ++i)    /* a dark region lights nothing */
            if (regions[i].energy > 0.0)
                region_light(&g, regions[i], &lights[(*made)++]);
    }
    free(g.radiance);
    free(g.energy);
    free(regions);
    free(whole);
    return result;
}

/* The mean radiance of the environment over the sphere. */
static void mean_environment(const gb_scene *scene, float L[3])
{
    const gb_texture *map = &scene->environment_texture;
    if (!map->rgb || map->width <= 0 || map->height <= 0) {
        memcpy(L, scene->environment, 3 * sizeof *L);
        return;
    }
    environment_grid g = {.width = map->width, .height = map->height};
    double sum[3] = {0.0, 0.0, 0.0};
    for (int row = 0; row < g.height; ++row)
        for (int column = 0; column < g.width; ++column)
            for (int c = 0; c < 3; ++c)
                sum[c] += map->rgb[3 * ((size_t)row * g.width + column) + c] *
                          cell_solid_angle(&g, row);
    for (int c = 0; c < 3; ++c)
        L[c] = (float)(sum[c] / (4.0 * PI));
}

double gb_environment_share(const gb_scene *scene)
{
    gb_vec3 centre;
    float R = gb_scene_bounding_sphere(scene, &centre), L[3];
    mean_environment(scene, L);
    double power[3];
    gb_sky_power(L, R, power);
    double sky = gb_power_luminance(power), others = 0.0;
    for (uint32_t i = 0; i < gb_scene_own_light_count(scene); ++i) {
        gb_delta_light_power(&scene->lights[i], R, power);
        others += gb_power_luminance(power);
    }
    for (uint32_t i = 0; i < scene->emissive_count; ++i) {
        gb_area_light_power(scene, scene->emissive_triangles[i], power);
        others += gb_power_luminance(power);
    }
    return sky > 0.0 ? sky / (sky + others) : 0.0;
}

uint32_t gb_environment_light_count(const gb_scene *scene, uint32_t most)
{
    return (uint32_t)ceil(most * gb_environment_share(scene) - 1e-9);
}

gb_result gb_scene_add_environment_lights(gb_scene *scene, uint32_t count, gb_error *error)
{
    gb_light *lights = realloc(scene->lights, (scene->light_count + (size_t)count + 1) *
                                                  sizeof *lights);
    if (!lights)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "environment lights: out of memory");
    scene->lights = lights;
    uint32_t made = 0;
    gb_result result = gb_environment_lights(scene, count, &lights[scene->light_count], &made,
                                             error);
    scene->light_count += made;
    scene->environment_light_count += made;
    return result;
}
