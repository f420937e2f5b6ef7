/* lightmap's final gather (tools/lightmap/final_gather.h) against analytic
 * answers:
 *  1. the furnace (a closed box of albedo ρ whose inside emits Le): the
 *     indirect irradiance is π Le ρ / (1 - ρ) everywhere, at the middle of
 *     a wall, near an edge and in a corner; the paths gather finds it;
 *  2. the same box with an octree that holds nothing: the octree gather
 *     keeps the light reflected once at the hits, π Le ρ, and with 2
 *     bounces before the octree, π Le (ρ + ρ²);
 *  3. the octree read at the hits: a point at height h above the floor of
 *     floor_octree.h, every leaf one VDL straight up of irradiance E_f, no
 *     lights: E = Kd E_f F, F the form factor of the floor's square seen
 *     from the point (Howell's catalogue: four rectangles with a corner
 *     below it);
 *  4. openness: a side facing a wall beyond near_distance is open, one in
 *     a gap, inside a solid, or facing out of a closed room is not.
 * Small ray counts, so that the file runs in seconds under the sanitizers. */
#include <math.h>
#include <string.h>

#include "embree_scene.h"
#include "floor_octree.h"
#include "light_sampling.h"
#include "photon_map.h"
#include "scene_builder.h"
#include "surface.h"
#include "tap.h"
#include "../../tools/lightmap/final_gather.h"

static const double PI = 3.14159265358979323846;

typedef struct gatherer {
    gb_path_tables tables;
    gb_final_gather gather;
} gatherer;

static void gatherer_make(gatherer *g, const gb_scene *scene, const gb_light_octree *octree)
{
    gb_error error;
    memset(g, 0, sizeof *g);
    if (gb_path_tables_build(scene, 1, &g->tables, &error) != GB_OK) {
        fprintf(stderr, "gatherer: %s\n", error.message);
        exit(2);
    }
    g->gather = (gb_final_gather){.paths = gb_path_tracer_over(scene, &g->tables),
                                  .octree = octree, .max_bounces = 1000, .octree_bounces = 1,
                                  .near_distance = 0.05f};
}

static void gatherer_free(gatherer *g)
{
    gb_path_tables_free(&g->tables);
}

static gb_texel_surface point_facing(float x, float y, float z, float nx, float ny, float nz)
{
    gb_texel_surface s = {{x, y, z}, {nx, ny, nz}, {nx, ny, nz}};
    return s;
}

/* The gathered irradiance's mean over RGB. */
static double gathered(const gatherer *g, const gb_texel_surface *p, int rays, uint64_t stream)
{
    gb_path_state state = {.rng = gb_random_make(5, stream)};
    float e[3];
    gb_final_gather_irradiance(&g->gather, p, 1e-4f, rays, &state, e);
    return (e[0] + e[1] + e[2]) / 3.0;
}

/* ---- 1, 2. the furnace ------------------------------------------------------ */

static void build_furnace(gb_scene *scene, float rho, float Le)
{
    memset(scene, 0, sizeof *scene);
    const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    add_box(scene, lo, hi, 1, add_grey(scene, rho, Le));
    scene_done(scene);
}

static void test_furnace(void)
{
    gb_scene scene;
    const float rho = 0.5f, Le = 1.0f;
    build_furnace(&scene, rho, Le);
    gatherer g;
    gatherer_make(&g, &scene, NULL);
    const double expected = PI * Le * rho / (1.0 - rho);
    const gb_texel_surface points[3] = {
        point_facing(0.0f, -1.0f, 0.0f, 0, 1, 0),           /* the floor's middle */
        point_facing(0.99f, -1.0f, 0.2f, 0, 1, 0),          /* 0.01 from the wall x = 1 */
        point_facing(-0.999f, -1.0f, -0.999f, 0, 1, 0),     /* a corner */
    };
    static const char *const names[3] = {"the middle of the floor", "0.01 from a wall",
                                         "a corner (0.001 from two walls)"};
    for (int k = 0; k < 3; ++k) {
        double e = gathered(&g, &points[k], 4096, (uint64_t)k);
        char what[160];
        snprintf(what, sizeof what, "furnace, paths: %s gathers pi Le rho / (1 - rho) = %.4f "
                 "within 2%% (got %.4f)", names[k], expected, e);
        CHECK_NEAR(e, expected, 0.02 * expected, what);
    }
    gatherer_free(&g);

    /* An octree of one node and no leaf: E_oct = 0 at every hit. */
    gb_light_octree_node root;
    for (int c = 0; c < 8; ++c)
        root.child[c] = GB_LIGHT_OCTREE_NONE;
    gb_light_octree empty = {.header = {.depth = 1, .node_count = 1, .origin = {-1, -1, -1},
                                        .size = 2.0f},
                             .nodes = &root};
    gatherer_make(&g, &scene, &empty);
    double once = gathered(&g, &points[0], 4096, 7);
    CHECK_NEAR(once, PI * Le * rho, 0.02 * PI * Le * rho,
               "furnace, an empty octree: the gather keeps the light reflected once at the "
               "hits, pi Le rho, within 2%");
    g.gather.octree_bounces = 2;
    double twice = gathered(&g, &points[0], 4096, 8);
    CHECK_NEAR(twice, PI * Le * (rho + rho * rho), 0.02 * PI * Le * (rho + rho * rho),
               "... with 2 bounces before the octree, the light reflected once or twice, "
               "pi Le (rho + rho^2), within 2%");
    gatherer_free(&g);
    gb_scene_free(&scene);
}

/* ---- 3. the octree at the hits ------------------------------------------- */

static const float FLOOR_IRRADIANCE = 2.0f;

static uint32_t straight_up(uint32_t i, uint32_t k, gb_light_octree_vdl *vdls)
{
    (void)i, (void)k;
    static const float up[3] = {0.0f, 1.0f, 0.0f};
    for (int c = 0; c < 3; ++c)
        vdls[0].irradiance[c] = FLOOR_IRRADIANCE;
    vdls[0].direction = gb_photon_pack_direction(up);
    return 1;
}

/* Howell's form factor from a point to a parallel rectangle of sides X h
 * and Y h with a corner straight below it at height h. */
static double corner_form_factor(double X, double Y)
{
    double a = sqrt(1.0 + X * X), b = sqrt(1.0 + Y * Y);
    return (X / a * atan(Y / a) + Y / b * atan(X / b)) / (2.0 * PI);
}

static void test_octree_at_hits(void)
{
    gb_scene scene;
    static const float up[3] = {0.0f, 1.0f, 0.0f}, above[3] = {0.0f, 10.0f, 0.0f};
    floor_scene_begin(&scene, above);
    scene_done(&scene);
    floor_octree *h = calloc(1, sizeof *h);
    gb_light_octree octree;
    floor_octree_make(h, up, 1, straight_up, &scene, &octree);
    gatherer g;
    gatherer_make(&g, &scene, &octree);
    const double height = 1.0, ratio = FLOOR_HALF / height;
    gb_texel_surface p = point_facing(0.0f, (float)height, 0.0f, 0, -1, 0);
    double expected = FLOOR_KD * FLOOR_IRRADIANCE * 4.0 * corner_form_factor(ratio, ratio);
    double e = gathered(&g, &p, 4096, 3);
    char what[200];
    snprintf(what, sizeof what, "octree gather: 1 above the floor, Kd E_f F = %.4f within 1%% "
             "(got %.4f; F the square's form factor, %.4f)", expected, e,
             4.0 * corner_form_factor(ratio, ratio));
    CHECK_NEAR(e, expected, 0.01 * expected, what);
    gatherer_free(&g);
    free(h);
    gb_scene_free(&scene);
}

/* ---- 4. openness ------------------------------------------------------------ */

static void test_openness(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    const float room_lo[3] = {-1, -1, -1}, room_hi[3] = {1, 1, 1};
    add_box(&scene, room_lo, room_hi, 1, grey);
    const float solid_lo[3] = {-0.5f, -1, -0.5f}, solid_hi[3] = {-0.1f, -0.6f, -0.1f};
    add_box(&scene, solid_lo, solid_hi, 0, grey);
    scene_done(&scene);
    gatherer g;
    gatherer_make(&g, &scene, NULL);
    const int rays = 64;
    struct {
        gb_texel_surface p;
        int low, high;
        const char *what;
    } cases[] = {
        {point_facing(0.5f, 0.99f, 0.5f, 0, -1, 0), rays, rays,
         "a point under the ceiling facing the room: every direction open"},
        {point_facing(0.5f, 0.99f, 0.5f, 0, 1, 0), -rays, -rays / 2,
         "... facing the ceiling 0.01 away (near_distance 0.05): mostly closed"},
        {point_facing(-0.3f, -0.8f, -0.3f, 0, 1, 0), -rays, -rays,
         "a point inside a solid: every direction meets a back"},
        {point_facing(0.5f, 1.01f, 0.5f, 0, 1, 0), 0, 0,
         "a point above the room facing out: nothing met, 0"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        gb_path_state state = {.rng = gb_random_make(1, k)};
        int openness = gb_final_gather_openness(&g.gather, &cases[k].p, 1e-4f, rays, &state);
        char what[200];
        snprintf(what, sizeof what, "openness: %s (%d of %d)", cases[k].what, openness, rays);
        CHECK(openness >= cases[k].low && openness <= cases[k].high, what);
    }
    gatherer_free(&g);
    gb_scene_free(&scene);
}

int main(void)
{
    test_furnace();
    test_octree_at_hits();
    test_openness();
    return tap_done();
}
