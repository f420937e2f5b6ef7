/* surface_coverage.c — the share of a leaf's gathering disc its surfaces
 * cover seen from a direction, by parallel rays (surface_coverage.h). */
#include "surface_coverage.h"

#include <math.h>

#include "light_octree_shading.h"
#include "vec3.h"

static const float GOLDEN_ANGLE = 2.39996322972865f;   /* π (3 - √5) */

/* The part [*enter, *leave] of the ray origin + s down (down unit) inside
 * the region's ellipsoid, |t|² + (a / f)² <= r² with a the part along the
 * normal: a quadratic in s. 0 when the ray misses it. */
static int ellipsoid_span(const gb_gathering_region *region, gb_vec3 origin, gb_vec3 down,
                          float *enter, float *leave)
{
    gb_vec3 x = gb_vec3_sub(origin, gb_vec3_load(region->centre));
    gb_vec3 n = gb_vec3_load(region->normal);
    float k = 1.0f - 1.0f / (region->flattening * region->flattening);
    float a = gb_vec3_dot(x, n), along = gb_vec3_dot(down, n);
    float A = 1.0f - k * along * along;
    float B = gb_vec3_dot(x, down) - k * a * along;
    float C = gb_vec3_dot(x, x) - k * a * a - region->radius * region->radius;
    float discriminant = B * B - A * C;
    if (!(A > 0.0f) || discriminant < 0.0f)
        return 0;
    float root = sqrtf(discriminant);
    *enter = (-B - root) / A;
    *leave = (-B + root) / A;
    return *leave > 0.0f;
}

/* Whether the ray meets a surface inside the region: its first hit after
 * it enters the ellipsoid, before it leaves. Only what lies inside hides:
 * a light just under a ceiling hides the ceiling; an arch above a floor
 * does not, since a VDL's photons arrive from a cone around its direction,
 * not along one line. */
static int meets_surface(const gb_embree_scene *rays, const gb_gathering_region *region,
                         gb_vec3 origin, gb_vec3 down, uint64_t *traced)
{
    float enter, leave;
    gb_hit hit;
    return ellipsoid_span(region, origin, down, &enter, &leave) &&
           gb_embree_intersect(rays, origin, down, fmaxf(enter, 0.0f), leave, &hit, traced);
}

/* Whether the ray crosses the leaf's plane (through the centre) inside the
 * region. */
static int meets_plane(const gb_gathering_region *region, gb_vec3 origin, gb_vec3 down)
{
    gb_vec3 n = gb_vec3_load(region->normal);
    float cos_down = gb_vec3_dot(down, n);
    if (cos_down == 0.0f)
        return 0;
    float t = gb_vec3_dot(gb_vec3_sub(gb_vec3_load(region->centre), origin), n) / cos_down;
    float p[3];
    gb_vec3_store(gb_vec3_madd(origin, down, t), p);
    return t >= 0.0f && gb_gathering_region_contains(region, p);
}

/* The rays' counts along -w: on the scene's surfaces and on the plane. */
static void count_rays(const gb_embree_scene *rays, const gb_gathering_region *region,
                       gb_vec3 w, int *surface, int *plane)
{
    gb_vec3 a, b;
    gb_vec3_frame(w, &a, &b);
    float r = region->radius;
    gb_vec3 start = gb_vec3_madd(gb_vec3_load(region->centre), w, 2.0f * r);
    gb_vec3 down = gb_vec3_negate(w);
    uint64_t traced = 0;
    *surface = *plane = 0;
    for (int j = 0; j < GB_SURFACE_COVERAGE_RAYS; ++j) {
        /* Vogel's spiral: equal areas of the disc, no two rays aligned */
        float rho = r * sqrtf(((float)j + 0.5f) / GB_SURFACE_COVERAGE_RAYS);
        float phi = (float)j * GOLDEN_ANGLE;
        gb_vec3 origin = gb_vec3_madd(gb_vec3_madd(start, a, rho * cosf(phi)), b,
                                      rho * sinf(phi));
        *surface += meets_surface(rays, region, origin, down, &traced);
        *plane += meets_plane(region, origin, down);
    }
}

float gb_surface_coverage(const gb_embree_scene *rays, const gb_gathering_region *region,
                          const float direction[3])
{
    gb_vec3 w = gb_vec3_normalize(gb_vec3_load(direction)), n = gb_vec3_load(region->normal);
    if (fabsf(gb_vec3_dot(w, n)) < GB_LIGHT_OCTREE_MIN_COS)
        w = gb_vec3_dot(w, n) < 0.0f ? gb_vec3_negate(n) : n;
    int surface, plane;
    count_rays(rays, region, w, &surface, &plane);
    return surface > 0 && plane > 0 ? (float)surface / (float)plane : 1.0f;
}
