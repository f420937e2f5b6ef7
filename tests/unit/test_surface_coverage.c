/* cluster's surface coverage (tools/cluster/surface_coverage.h) against the
 * areas it stands for, on planes built in memory, and the light octree of
 * the furnace against its analytic irradiance:
 *  1. one plane across the whole disc: κ = 1 from every direction, exactly;
 *  2. a plane that ends at the centre: κ = 1/2 seen head on;
 *  3. a floor meeting a wall at the centre, the leaf's normal n between
 *     them: the ellipsoid (flattened along n) cuts the floor in an ellipse
 *     of half-axes r and r / √(1/2 + 1/(2 f²)); from straight above, half
 *     of it over the leaf's disc seen at 45°: (1/2) / √2.5 / cos 45° = 0.447
 *     (f = 1/2);
 *  4. a light just under a ceiling, both inside the ellipsoid: seen from
 *     below the light hides the ceiling, κ = 1 (2 without the hiding);
 *  5. a floor near a wall, seen from a direction whose rays start behind
 *     the wall: the wall's back is passed, κ = the floor's share;
 *  6. the furnace (a closed box of albedo ρ whose walls emit Le): photons,
 *     cluster, and the octree's irradiance π Le ρ / (1 - ρ) in the middle
 *     of a wall, near its edge and in a corner, where π r² put it 36 % low.
 */
#include <math.h>
#include <string.h>

#include "../../tools/cluster/cluster.h"
#include "../../tools/cluster/surface_coverage.h"
#include "../../tools/photons/photons.h"
#include "embree_scene.h"
#include "light_octree_shading.h"
#include "scene_builder.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

static gb_embree_scene *rays_of(const gb_scene *scene)
{
    gb_embree_scene *rays;
    gb_error error;
    if (gb_embree_scene_create(scene, 1, &rays, &error) != GB_OK) {
        printf("Bail out! embree: %s\n", error.message);
        exit(1);
    }
    return rays;
}

/* The quad x in x0..x1, z in -1..1 at height y, front toward `toward`. */
static void add_strip(gb_scene *scene, float x0, float x1, float y, const float toward[3],
                      uint32_t material)
{
    const float p[4][3] = {{x0, y, -1}, {x1, y, -1}, {x1, y, 1}, {x0, y, 1}};
    add_quad_facing(scene, p, toward, material);
}

static float coverage(const gb_embree_scene *rays, const gb_scene *scene,
                      const gb_gathering_region *region, float x, float y, float z)
{
    float w[3] = {x, y, z};
    float length = sqrtf(x * x + y * y + z * z);
    for (int k = 0; k < 3; ++k)
        w[k] /= length;
    return gb_surface_coverage(rays, scene, region, w);
}

static void test_planes(void)
{
    const float above[3] = {0, 5, 0}, below[3] = {0, -5, 0};
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    add_strip(&scene, -1, 1, 0, above, grey);
    scene_done(&scene);
    gb_embree_scene *rays = rays_of(&scene);
    gb_gathering_region region = {{0, 0, 0}, {0, 1, 0}, 0.2f, 0.5f};
    float worst = 0.0f;
    const float directions[5][3] = {{0, 1, 0}, {0.6f, 0.8f, 0}, {-0.3f, 0.5f, 0.8f},
                                    {0.95f, 0.1f, 0.2f}, {0, -1, 0}};
    for (int k = 0; k < 5; ++k)
        worst = fmaxf(worst, fabsf(coverage(rays, &scene, &region, directions[k][0],
                                            directions[k][1], directions[k][2]) - 1.0f));
    CHECK(worst == 0.0f, "one plane across the disc: coverage exactly 1 from 5 directions, "
          "grazing and from below included");
    gb_embree_scene_destroy(rays);
    gb_scene_free(&scene);

    memset(&scene, 0, sizeof scene);
    grey = add_grey(&scene, 0.5f, 0.0f);
    add_strip(&scene, -1, 0, 0, above, grey);
    scene_done(&scene);
    rays = rays_of(&scene);
    float half = coverage(rays, &scene, &region, 0, 1, 0);
    CHECK_NEAR(half, 0.5, 0.05, "a plane ending at the centre: coverage 1/2 seen head on");
    gb_embree_scene_destroy(rays);
    gb_scene_free(&scene);

    /* The floor x < 0 meets the wall x = 0 (facing -x); the leaf's normal
     * is between their normals. */
    memset(&scene, 0, sizeof scene);
    grey = add_grey(&scene, 0.5f, 0.0f);
    add_strip(&scene, -1, 0, 0, above, grey);
    const float wall[4][3] = {{0, 0, -1}, {0, 1, -1}, {0, 1, 1}, {0, 0, 1}};
    const float room[3] = {-5, 0.5f, 0};
    add_quad_facing(&scene, wall, room, grey);
    scene_done(&scene);
    rays = rays_of(&scene);
    gb_gathering_region corner = {{0, 0, 0}, {-0.70710678f, 0.70710678f, 0}, 0.2f, 0.5f};
    float floor_share = coverage(rays, &scene, &corner, 0, 1, 0);
    CHECK_NEAR(floor_share, 0.5 / sqrt(2.5) / cos(PI / 4), 0.05,
               "a floor meeting a wall: from above, half the floor's section over the leaf's "
               "disc seen at 45 degrees, 0.447");
    gb_embree_scene_destroy(rays);
    gb_scene_free(&scene);

    /* A light at y = 0 facing down, a ceiling 0.04 above it (inside the
     * ellipsoid, whose normal half-axis is 0.1). */
    memset(&scene, 0, sizeof scene);
    grey = add_grey(&scene, 0.5f, 0.0f);
    add_strip(&scene, -1, 1, 0, below, grey);
    add_strip(&scene, -1, 1, 0.04f, below, grey);
    scene_done(&scene);
    rays = rays_of(&scene);
    gb_gathering_region light = {{0, 0, 0}, {0, -1, 0}, 0.2f, 0.5f};
    CHECK_NEAR(coverage(rays, &scene, &light, 0, -1, 0), 1.0, 1e-6,
               "a light just under a ceiling, seen from below: the light hides the ceiling, "
               "coverage 1");
    gb_embree_scene_destroy(rays);
    gb_scene_free(&scene);

    /* A floor in a room whose wall x = 0.15 faces -x: from up and toward
     * the wall, the rays start behind it. */
    memset(&scene, 0, sizeof scene);
    grey = add_grey(&scene, 0.5f, 0.0f);
    add_strip(&scene, -1, 0.15f, 0, above, grey);
    const float near_wall[4][3] = {{0.15f, 0, -1}, {0.15f, 1, -1}, {0.15f, 1, 1},
                                   {0.15f, 0, 1}};
    add_quad_facing(&scene, near_wall, room, grey);
    scene_done(&scene);
    rays = rays_of(&scene);
    gb_gathering_region floor = {{0, 0, 0}, {0, 1, 0}, 0.2f, 0.5f};
    float behind = coverage(rays, &scene, &floor, 0.6f, 0.8f, 0);
    float head_on = coverage(rays, &scene, &floor, 0, 1, 0);
    CHECK(behind > 0.7f * head_on && head_on > 0.8f && head_on < 1.0f,
          "rays that start behind a wall pass its back: the floor seen toward the wall "
          "keeps most of its coverage");
    gb_embree_scene_destroy(rays);
    gb_scene_free(&scene);
}

/* ---- 6. the furnace through the octree ----------------------------------- */

static void test_furnace(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    const float rho = 0.5f, Le = 1.0f, lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    add_box(&scene, lo, hi, 1, add_grey(&scene, rho, Le));
    scene_done(&scene);
    gb_photons_options po = {.count = 400000, .seed = 3, .threads = 2};
    gb_photon_map map;
    gb_error error;
    gb_cluster_options co = {.depth = 5, .threads = 2, .seed = 1};
    gb_light_octree octree;
    if (gb_photons_trace(&scene, &po, &map, NULL, &error) != GB_OK ||
        gb_cluster_build(&scene, &map, &co, &octree, NULL, &error) != GB_OK) {
        printf("Bail out! %s\n", error.message);
        exit(1);
    }
    const double expected = PI * Le * rho / (1.0 - rho);
    const float up[3] = {0, 1, 0};
    const float points[3][3] = {{0.1f, -1, 0.2f}, {0.97f, -1, 0.3f}, {-0.98f, -1, -0.98f}};
    static const char *const names[3] = {"the floor's middle", "0.03 from a wall",
                                         "a corner, 0.02 from two walls"};
    for (int k = 0; k < 3; ++k) {
        float e[3];
        gb_light_octree_irradiance(&octree, points[k], up, up, e);
        double mean = (e[0] + e[1] + e[2]) / 3.0;
        char what[200];
        snprintf(what, sizeof what, "furnace through the octree: %s within 15%% of "
                 "pi Le rho / (1 - rho) = %.3f (got %.3f)", names[k], expected, mean);
        CHECK_NEAR(mean, expected, 0.15 * expected, what);
    }
    gb_light_octree_free(&octree);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

int main(void)
{
    test_planes();
    test_furnace();
    return tap_done();
}
