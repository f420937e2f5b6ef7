/* surface_coverage.c — the share of a leaf's gathering disc its surfaces
 * cover seen from a direction, by parallel rays (surface_coverage.h). */
#include "surface_coverage.h"

#include <math.h>

#include "light_octree_shading.h"
#include "scene_triangles.h"
#include "vec3.h"

static const float GOLDEN_ANGLE = 2.39996322972865f;   /* π (3 - √5) */
enum { MAX_WALLS_PASSED = 8 };

/* Whether the ray from origin along down (unit) first meets, within 4 r,
 * a surface inside the region: a triangle's back met before the region is
 * the outside of a wall the ray started behind, passed through; inside the
 * region either side counts, as photons land on both. */
static int meets_surface(const gb_embree_scene *rays, const gb_scene *scene,
                         const gb_gathering_region *region, gb_vec3 origin, gb_vec3 down,
                         uint64_t *traced)
{
    float tnear = 0.0f, tfar = 4.0f * region->radius, pass = 1e-4f * region->radius;
    for (int layer = 0; layer < MAX_WALLS_PASSED; ++layer) {
        gb_hit hit;
        float p[3];
        if (!gb_embree_intersect(rays, origin, down, tnear, tfar, &hit, traced))
            return 0;
        gb_vec3_store(gb_vec3_madd(origin, down, hit.t), p);
        if (gb_gathering_region_contains(region, p))
            return 1;
        if (gb_vec3_dot(gb_triangle_normal(scene, hit.triangle), down) < 0.0f)
            return 0;       /* a front outside the region hides it */
        tnear = hit.t + pass;
    }
    return 0;
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
static void count_rays(const gb_embree_scene *rays, const gb_scene *scene,
                       const gb_gathering_region *region, gb_vec3 w, int *surface, int *plane)
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
        *surface += meets_surface(rays, scene, region, origin, down, &traced);
        *plane += meets_plane(region, origin, down);
    }
}

float gb_surface_coverage(const gb_embree_scene *rays, const gb_scene *scene,
                          const gb_gathering_region *region, const float direction[3])
{
    gb_vec3 w = gb_vec3_normalize(gb_vec3_load(direction)), n = gb_vec3_load(region->normal);
    if (fabsf(gb_vec3_dot(w, n)) < GB_LIGHT_OCTREE_MIN_COS)
        w = gb_vec3_dot(w, n) < 0.0f ? gb_vec3_negate(n) : n;
    int surface, plane;
    count_rays(rays, scene, region, w, &surface, &plane);
    return surface > 0 && plane > 0 ? (float)surface / (float)plane : 1.0f;
}
