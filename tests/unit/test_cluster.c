/* test_cluster.c — the light octree (tools/cluster, formats/light_octree):
 * leaves only where geometry is and their normals; chord-length k-means on
 * synthetic directions (bundles, degenerate input, irradiance conserved);
 * the normals a leaf is shaded at (its cell's and its neighbours'); the
 * VDL count chosen by the irradiance error against an analytic case; the
 * spread of rings and of a cosine-weighted
 * hemisphere against their analytic values, known clusters recovered,
 * centroids of unequally weighted directions at the minimisers by hand,
 * k-means restarts never worse; photons of one and two suns on a plane
 * clustered into VDLs of the analytic direction and irradiance; bytes the
 * same whatever the threads; a part's halo holds every photon within R of
 * its points (brute force) and gathers what the whole map gathers; bad
 * inputs and corrupt files refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../tools/cluster/cluster.h"
#include "../../tools/cluster/gathering.h"
#include "../../tools/cluster/halo.h"
#include "../../tools/cluster/kmeans.h"
#include "../../tools/cluster/octree.h"
#include "../../tools/cluster/vdl.h"
#include "../../tools/photons/photons.h"
#include "triangle_box_overlap.h"
#include "light_octree.h"
#include "scene_builder.h"
#include "tap.h"

#define PI 3.14159265358979323846

static double angle_degrees(const float a[3], const float b[3])
{
    double dot = (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
    return acos(fmax(-1.0, fmin(1.0, dot))) * 180.0 / PI;
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l, v[1] /= l, v[2] /= l;
}

/* ---- octree ---------------------------------------------------------------- */

static void build_one_triangle(gb_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    uint32_t grey = add_grey(scene, 0.5f, 0.0f);
    const float p[3][3] = {{0.1f, 0.2f, 0.3f}, {0.9f, 0.3f, 0.5f}, {0.3f, 0.8f, 0.7f}};
    scene->vertex_count = 3;
    scene->positions = builder_grow(NULL, 9, sizeof(float));
    memcpy(scene->positions, p, sizeof p);
    add_triangle(scene, 0, 1, 2, grey);
    scene_done(scene);
}

/* Every cell of the grid that the triangle touches is a leaf, and no other. */
static void test_octree_single_triangle(void)
{
    gb_scene scene;
    build_one_triangle(&scene);
    gb_octree_leaves leaves;
    gb_error error;
    CHECK(gb_octree_build(&scene, 4, &leaves, &error) == GB_OK, "octree of one triangle");
    double vertex[3][3], edge = gb_octree_leaf_edge(&leaves), half[3];
    for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 3; ++k)
            vertex[v][k] = scene.positions[3 * v + k];
    half[0] = half[1] = half[2] = 0.5 * edge;
    uint32_t expected = 0, matched = 0;
    for (uint32_t z = 0; z < 16; ++z)
        for (uint32_t y = 0; y < 16; ++y)
            for (uint32_t x = 0; x < 16; ++x) {
                double c[3] = {leaves.origin[0] + (x + 0.5) * edge,
                               leaves.origin[1] + (y + 0.5) * edge,
                               leaves.origin[2] + (z + 0.5) * edge};
                expected += gb_triangle_box_overlap((const double(*)[3])vertex, c, half);
            }
    int normals_ok = 1, touching = 1;
    float n[3] = {-0.08f, -0.28f, 0.46f}; /* (p1 - p0) x (p2 - p0) */
    normalize3(n);
    for (uint32_t i = 0; i < leaves.count; ++i) {
        uint32_t cell[3];
        gb_octree_leaf_cell(&leaves, i, cell);
        double cd[3];
        for (int k = 0; k < 3; ++k)
            cd[k] = leaves.origin[k] + (cell[k] + 0.5) * edge;
        touching &= gb_triangle_box_overlap((const double(*)[3])vertex, cd, half);
        matched += 1;
        /* the file's 2 x 16-bit octahedral normal: within 0.0025 degrees (methods.md) */
        normals_ok &= angle_degrees(&leaves.normals[3 * i], n) < 0.01;
    }
    CHECK(expected > 0 && leaves.count < 16 * 16 * 16 / 4, "a triangle touches a few cells");
    CHECK_EQ_INT(matched, expected, "leaves are exactly the cells the triangle touches");
    CHECK(touching, "every leaf touches the triangle");
    CHECK(normals_ok, "every leaf's normal is the triangle's");
    int increasing = 1;
    for (uint32_t i = 1; i < leaves.count; ++i)
        increasing &= leaves.keys[i] > leaves.keys[i - 1];
    CHECK(increasing, "leaves in increasing Morton order");
    gb_octree_leaves_free(&leaves);
    gb_scene_free(&scene);
}

/* Two faces of a box meeting in a cell: the normal leans to the larger one. */
static void test_octree_area_weighted_normal(void)
{
    gb_scene scene = {0};
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    /* floor 0..1 x 0..1 at y = 0 facing +y, wall at x = 0, y 0..0.5, facing +x */
    const float floor[4][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}};
    const float wall[4][3] = {{0, 0, 0}, {0, 0.5f, 0}, {0, 0.5f, 1}, {0, 0, 1}};
    const float above[3] = {0.5f, 1.0f, 0.5f}, right[3] = {1.0f, 0.25f, 0.5f};
    add_quad_facing(&scene, floor, above, grey);
    add_quad_facing(&scene, wall, right, grey);
    scene_done(&scene);
    gb_octree_leaves leaves;
    gb_error error;
    CHECK(gb_octree_build(&scene, 1, &leaves, &error) == GB_OK, "octree of floor and wall");
    /* depth 1: the cell at the corner holds the whole floor (area 1) and wall (0.5) */
    float expected[3] = {0.5f, 1.0f, 0.0f};
    normalize3(expected);
    CHECK(leaves.count >= 1 && angle_degrees(&leaves.normals[0], expected) < 0.1,
          "leaf normal is the area-weighted average (floor 1, wall 0.5)");
    gb_octree_leaves_free(&leaves);
    gb_scene_free(&scene);
}

/* The octree at depth 3 of the inside of a unit box (cells 0 and 7 hold
 * its faces). */
static void box_octree(gb_scene *scene, gb_octree_leaves *leaves)
{
    *scene = (gb_scene){0};
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    add_box(scene, lo, hi, 1, add_grey(scene, 0.5f, 0.0f));
    scene_done(scene);
    gb_error error;
    CHECK(gb_octree_build(scene, 3, leaves, &error) == GB_OK, "octree of a box");
}

/* The six faces of a box: leaves on its shell only, none inside. */
static void test_octree_box_shell(void)
{
    gb_scene scene;
    gb_octree_leaves leaves;
    box_octree(&scene, &leaves);
    int shell = 1;
    for (uint32_t i = 0; i < leaves.count; ++i) {
        uint32_t c[3];
        gb_octree_leaf_cell(&leaves, i, c);
        shell &= c[0] == 0 || c[0] == 7 || c[1] == 0 || c[1] == 7 || c[2] == 0 || c[2] == 7;
    }
    CHECK_EQ_INT(leaves.count, 8 * 8 * 8 - 6 * 6 * 6, "a box at depth 3: the 296 shell cells");
    CHECK(shell, "... and no cell inside");
    gb_octree_leaves_free(&leaves);
    gb_scene_free(&scene);
}

/* ---- k-means and VDLs ---------------------------------------------------- */

/* An empty workspace for up to capacity photons and 8 VDLs (1), or 0. */
static int empty_workspace(gb_vdl_workspace *w, uint32_t capacity)
{
    gb_error error;
    if (gb_vdl_workspace_create(w, capacity, 8, &error) != GB_OK)
        return 0;
    w->count = 0;
    return 1;
}

/* n directions within `noise` (radians, roughly) of d, power p each. */
static void add_bundle(gb_vdl_workspace *w, const float d[3], uint32_t n, float noise,
                       const float power[3], gb_random *rng)
{
    for (uint32_t i = 0; i < n; ++i) {
        float *v = &w->directions[3 * (size_t)w->count];
        for (int k = 0; k < 3; ++k)
            v[k] = d[k] + noise * (2.0f * gb_random_float(rng) - 1.0f);
        normalize3(v);
        memcpy(&w->powers[3 * (size_t)w->count], power, 3 * sizeof(float));
        w->weights[w->count++] = power[0] + power[1] + power[2];
    }
}

/* A target (vdl.h) of the leaf normal and the further normals given. */
static vdl_target target_of(float radius, float tolerance, const float leaf_normal[3],
                            gb_surface_normal *normals, uint32_t count)
{
    vdl_target t = {.radius = radius, .normals = normals, .normal_count = count,
                    .tolerance = tolerance};
    memcpy(t.leaf_normal, leaf_normal, sizeof t.leaf_normal);
    return t;
}

static void test_two_bundles(void)
{
    gb_vdl_workspace w;
    CHECK(empty_workspace(&w, 300), "workspace");
    gb_random rng = gb_random_make(7, 0);
    float a[3] = {0.0f, 1.0f, 0.0f}, b[3] = {0.7f, 0.7f, 0.1f};
    normalize3(b);
    const float pa[3] = {1.0f, 0.5f, 0.25f}, pb[3] = {0.2f, 0.2f, 0.4f};
    add_bundle(&w, a, 200, 0.01f, pa, &rng);
    add_bundle(&w, b, 100, 0.01f, pb, &rng);
    gb_light_octree_vdl vdls[8];
    double error;
    gb_random seed = gb_random_make(1, 2);
    gb_surface_normal normals[2] = {{{0, 1, 0}, 1}, {{1, 0, 0}, 1}};
    vdl_target target = target_of(0.5f, 0.02f, a, normals, 2);
    uint32_t n = gb_vdls_from_photons(&w, &target, &seed, vdls, &error);
    CHECK_EQ_INT(n, 2, "two tight bundles, shaded on +y and +x: two VDLs");
    float da[3], db[3];
    gb_photon_unpack_direction(vdls[0].direction, da);
    gb_photon_unpack_direction(vdls[n > 1].direction, db);
    CHECK(angle_degrees(da, a) < 1.0 && angle_degrees(db, b) < 1.0,
          "... brightest first, each along its bundle (within 1 degree)");
    double area = PI * 0.25;
    CHECK_NEAR(vdls[0].irradiance[0], 200.0 * 1.0 / area, 1e-3, "... irradiance of bundle A: "
               "sum of its powers / (pi r^2)");
    double total[3] = {0, 0, 0};
    for (uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            total[k] += vdls[i].irradiance[k];
    CHECK(fabs(total[0] - 220.0 / area) < 1e-3 && fabs(total[2] - 90.0 / area) < 1e-3,
          "... irradiance summed over VDLs is the density estimate: conserved");
    CHECK(error <= 0.02, "... within the tolerance (one VDL leaves 0.047 on +x)");
    gb_vdl_workspace_free(&w);
}

static void test_identical_directions(void)
{
    gb_vdl_workspace w;
    empty_workspace(&w, 300);
    gb_random rng = gb_random_make(7, 1);
    const float d[3] = {0.0f, 0.0f, 1.0f}, p[3] = {1.0f, 1.0f, 1.0f};
    add_bundle(&w, d, 300, 0.0f, p, &rng);
    gb_light_octree_vdl vdls[8];
    double error;
    gb_random seed = gb_random_make(1, 3);
    gb_surface_normal normals[1] = {{{0, 0, 1}, 1}};
    vdl_target always = target_of(1.0f, -1.0f, d, normals, 1);
    uint32_t n = gb_vdls_from_photons(&w, &always, &seed, vdls, &error);
    float v[3];
    gb_photon_unpack_direction(vdls[0].direction, v);
    CHECK_EQ_INT(n, 1, "identical directions, K_max asked: one VDL");
    CHECK(isfinite(vdls[0].irradiance[0]) && isfinite(error) && error == 0.0 &&
              angle_degrees(v, d) < 0.01,
          "... finite, along the direction, error 0 (no NaN)");
    CHECK_NEAR(vdls[0].irradiance[1], 300.0 / PI, 1e-3, "... irradiance sum / (pi r^2)");
    w.count = 0;
    vdl_target some = target_of(1.0f, 0.2f, d, normals, 1);
    CHECK_EQ_INT(gb_vdls_from_photons(&w, &some, &seed, vdls, &error), 0, "no photon: no VDL");
    gb_vdl_workspace_free(&w);
}

/* Half the power from a = (0.6, 0, 0.8), half from b = (-0.6, 0, 0.8), on
 * a floor of normal +z. At the floor's normal any k is exact. On a wall of
 * normal +x, a brings 0.6 / 0.8 = 0.75 of its irradiance and b none: 0.375
 * of the leaf's; one VDL, along +z, brings none there: error 0.375. Two
 * VDLs, one a direction, are exact. */
static void test_count_by_error(void)
{
    gb_vdl_workspace w;
    empty_workspace(&w, 200);
    gb_random rng = gb_random_make(9, 0);
    const float a[3] = {0.6f, 0.0f, 0.8f}, b[3] = {-0.6f, 0.0f, 0.8f}, p[3] = {1, 1, 1};
    const float up[3] = {0.0f, 0.0f, 1.0f};
    add_bundle(&w, a, 100, 0.0f, p, &rng);
    add_bundle(&w, b, 100, 0.0f, p, &rng);
    gb_light_octree_vdl vdls[8];
    double error;
    gb_surface_normal floor_only[1] = {{{0, 0, 1}, 1}};
    gb_surface_normal floor_and_wall[2] = {{{0, 0, 1}, 1}, {{1, 0, 0}, 1}};
    vdl_target target = target_of(1.0f, 0.0f, up, floor_only, 1);
    gb_random seed = gb_random_make(3, 0);
    CHECK_EQ_INT(gb_vdls_from_photons(&w, &target, &seed, vdls, &error), 1,
                 "a floor shaded at its own normal: one VDL, even at tolerance 0");
    printf("# one VDL on the floor: error %g\n", error);
    CHECK(error < 1e-6, "... exact there");
    target = target_of(1.0f, 0.3f, up, floor_and_wall, 2);
    CHECK_EQ_INT(gb_vdls_from_photons(&w, &target, &seed, vdls, &error), 2,
                 "floor and wall, tolerance 0.3: two VDLs (one leaves 0.375)");
    printf("# two VDLs on floor and wall: error %g\n", error);
    CHECK(error < 1e-4, "... exact at both normals");
    target = target_of(1.0f, 0.4f, up, floor_and_wall, 2);
    CHECK_EQ_INT(gb_vdls_from_photons(&w, &target, &seed, vdls, &error), 1,
                 "tolerance 0.4: one VDL");
    CHECK_NEAR(error, 0.375, 1e-4, "... whose error on the wall is 0.375 of the leaf's light");
    gb_vdl_workspace_free(&w);
}

/* The normals a leaf is shaded at, on the inside of a unit box (box_octree):
 * a cell in the middle of the floor and
 * its neighbours see the floor alone; one cell in from the x = 0 wall, the
 * floor and that wall; one cell in from two walls, three normals; the
 * corner cell itself, its three faces. */
static void test_shading_normals(void)
{
    gb_scene scene;
    gb_octree_leaves leaves;
    box_octree(&scene, &leaves);
    const uint32_t cells[4][3] = {{3, 0, 3}, {1, 0, 3}, {1, 0, 1}, {0, 0, 0}};
    const uint32_t expected[4] = {1, 2, 3, 3};
    const char *names[4] = {"middle of the floor", "one cell from a wall",
                            "one cell from two walls", "the corner"};
    for (int c = 0; c < 4; ++c) {
        uint32_t leaf = UINT32_MAX, count = 0;
        for (uint32_t i = 0; i < leaves.count; ++i) {
            uint32_t at[3];
            gb_octree_leaf_cell(&leaves, i, at);
            if (!memcmp(at, cells[c], sizeof at))
                leaf = i;
        }
        gb_surface_normal normals[GB_SURFACE_NORMALS];
        if (leaf != UINT32_MAX)
            count = gb_octree_shading_normals(&leaves, leaf, normals);
        int axis_aligned = count > 0;
        for (uint32_t j = 0; j < count; ++j)
            axis_aligned &= fabsf(normals[j].normal[0]) + fabsf(normals[j].normal[1]) +
                                    fabsf(normals[j].normal[2]) > 0.9999f;
        printf("# %s: %u normals, %u expected\n", names[c], count, expected[c]);
        CHECK(count == expected[c] && axis_aligned, "a cell of a box's inside: as many normals "
              "as faces within a cell of it, each a face's");
    }
    gb_octree_leaves_free(&leaves);
    gb_scene_free(&scene);
}

/* ---- k-means quality and the spread ---------------------------------------- */

/* Appends n directions on the cone of half-angle theta (degrees) about +z,
 * equally spaced in azimuth, weight w each. */
static uint32_t add_ring(float *d, float *weights, uint32_t at, uint32_t n, double theta,
                         float w)
{
    double t = theta * PI / 180.0;
    for (uint32_t i = 0; i < n; ++i, ++at) {
        double phi = 2.0 * PI * i / n;
        d[3 * at] = (float)(sin(t) * cos(phi));
        d[3 * at + 1] = (float)(sin(t) * sin(phi));
        d[3 * at + 2] = (float)cos(t);
        weights[at] = w;
    }
    return at;
}

/* The spread is the power-weighted RMS chord to the centroid, as an angle:
 * a ring at 20 degrees spreads 20 degrees; rings at 10 (weight 3) and 30
 * (weight 1) spread 2 asin(sqrt((3 c10² + c30²) / 4) / 2), c = 2 sin(θ/2). */
static void test_spread_of_rings(void)
{
    enum { N = 360 };
    float d[3 * 2 * N], w[2 * N], c[3];
    uint32_t a[2 * N];
    double scratch[2 * N];
    uint32_t n = add_ring(d, w, 0, N, 20.0, 1.0f);
    gb_random rng = gb_random_make(5, 0);
    CHECK_EQ_INT(gb_kmeans_directions(d, w, n, 1, NULL, &rng, c, a, scratch), 1, "a ring: one "
                 "cluster");
    const float z[3] = {0.0f, 0.0f, 1.0f};
    CHECK(angle_degrees(c, z) < 0.01, "... its centroid is the ring's axis");
    CHECK_NEAR(gb_kmeans_spread(d, w, n, c, a), 20.0, 1e-3, "... a ring at 20 degrees spreads "
               "20 degrees");
    n = add_ring(d, w, 0, N, 10.0, 3.0f);
    n = add_ring(d, w, n, N, 30.0, 1.0f);
    gb_kmeans_directions(d, w, n, 1, NULL, &rng, c, a, scratch);
    double c10 = 2.0 * sin(5.0 * PI / 180.0), c30 = 2.0 * sin(15.0 * PI / 180.0);
    double expected = 2.0 * asin(sqrt((3.0 * c10 * c10 + c30 * c30) / 4.0) / 2.0) * 180.0 / PI;
    CHECK_NEAR(gb_kmeans_spread(d, w, n, c, a), expected, 1e-3, "rings at 10 (weight 3) and 30 "
               "degrees: the power-weighted RMS chord as an angle (17.23)");
}

/* n directions of a cosine-weighted hemisphere about +z: what a surface
 * receives under uniform incident radiance. */
static void cosine_hemisphere(float *d, float *w, uint32_t n, gb_random *rng)
{
    for (uint32_t i = 0; i < n; ++i) {
        float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
        float r = sqrtf(u1), phi = 2.0f * (float)PI * u2;
        d[3 * i] = r * cosf(phi);
        d[3 * i + 1] = r * sinf(phi);
        d[3 * i + 2] = sqrtf(fmaxf(0.0f, 1.0f - u1));
        w[i] = 1.0f;
    }
}

static int assigned_to_nearest(const float *d, uint32_t n, const float *c, uint32_t k,
                               const uint32_t *a)
{
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < k; ++j) {
            const float *x = &d[3 * i], *m = &c[3 * j], *mine = &c[3 * a[i]];
            if (x[0] * m[0] + x[1] * m[1] + x[2] * m[2] >
                x[0] * mine[0] + x[1] * mine[1] + x[2] * mine[2] + 1e-6f)
                return 0;
        }
    return 1;
}

/* One cluster of a cosine-weighted hemisphere: E[chord²] = 2 - 2 E[cos θ] =
 * 2/3, so the spread is 2 asin(sqrt(2/3) / 2) = 48.19 degrees. Four
 * clusters: every photon on its nearest centroid; restarts never worse than
 * one run from the same stream, and better for some streams. */
static void test_cosine_hemisphere(void)
{
    enum { N = 20000 };
    float *d = malloc(3 * N * sizeof *d), *w = malloc(N * sizeof *w), c[3 * 4];
    uint32_t *a = malloc(N * sizeof *a);
    double *scratch = malloc(N * sizeof *scratch);
    gb_random rng = gb_random_make(11, 0);
    cosine_hemisphere(d, w, N, &rng);
    gb_kmeans_directions(d, w, N, 1, NULL, &rng, c, a, scratch);
    double expected = 2.0 * asin(sqrt(2.0 / 3.0) / 2.0) * 180.0 / PI;
    double spread = gb_kmeans_spread(d, w, N, c, a);
    printf("# cosine hemisphere, k = 1: spread %.2f, analytic %.2f degrees\n", spread, expected);
    CHECK_NEAR(spread, expected, 0.5, "cosine hemisphere, k = 1: spread 48.19 degrees");
    int never_worse = 1, better = 0, nearest = 1;
    for (uint64_t stream = 0; stream < 6; ++stream) {
        gb_random one = gb_random_make(12, stream), many = one;
        gb_kmeans_directions(d, w, N, 4, NULL, &one, c, a, scratch);
        double single = gb_kmeans_spread(d, w, N, c, a);
        gb_kmeans_options o = {.restarts = 4};
        gb_kmeans_directions(d, w, N, 4, &o, &many, c, a, scratch);
        double best = gb_kmeans_spread(d, w, N, c, a);
        never_worse &= best <= single + 1e-9;
        better += best < single - 1e-6;
        nearest &= assigned_to_nearest(d, N, c, 4, a);
    }
    CHECK(nearest, "k = 4: every photon assigned to its nearest centroid");
    printf("# 4 restarts spread less than 1 run for %d of 6 streams\n", better);
    CHECK(never_worse && better > 0, "... 4 restarts never spread more than 1 run from the "
          "same stream, and less for some streams");
    free(d);
    free(w);
    free(a);
    free(scratch);
}

/* Five bundles of unequal sizes and powers (the heaviest 500 times the
 * lightest), 2 degrees of noise: k = 5 with 8 restarts puts each bundle in
 * its own cluster, centroid on the bundle's direction, for every stream. One
 * k-means++ run alone misses about a quarter of the time (splits the heavy
 * bundle, merges the two light ones: a local minimum). */
static void test_known_clusters(void)
{
    gb_vdl_workspace w;
    CHECK(empty_workspace(&w, 500), "workspace");
    const float axes[5][3] = {{0, 0, 1}, {0.8f, 0, 0.6f}, {-0.6f, 0.64f, 0.48f},
                              {0, -0.8f, 0.6f}, {-0.5f, -0.5f, 0.707f}};
    const uint32_t sizes[5] = {200, 120, 80, 60, 40};
    const float powers[5][3] = {{1, 1, 1}, {0.1f, 0.1f, 0.1f}, {3, 2, 1}, {0.5f, 0, 0},
                                {0.05f, 0.05f, 0.2f}};
    gb_random rng = gb_random_make(13, 0);
    for (int b = 0; b < 5; ++b) {
        float axis[3] = {axes[b][0], axes[b][1], axes[b][2]};
        normalize3(axis);
        add_bundle(&w, axis, sizes[b], 0.035f, powers[b], &rng);
    }
    int recovered = 1, on_axis = 1;
    for (uint64_t stream = 0; stream < 8; ++stream) {
        gb_random seed = gb_random_make(14, stream);
        gb_kmeans_options o = {.restarts = 8};
        uint32_t made = gb_kmeans_directions(w.directions, w.weights, w.count, 5, &o, &seed,
                                             w.centroids, w.assignment, w.scratch);
        uint32_t first = 0, used = 0;
        for (int b = 0; b < 5; ++b) {
            uint32_t cluster = w.assignment[first];
            for (uint32_t i = first; i < first + sizes[b]; ++i)
                recovered &= w.assignment[i] == cluster;
            recovered &= !(used & 1u << cluster);
            used |= 1u << cluster;
            float axis[3] = {axes[b][0], axes[b][1], axes[b][2]};
            normalize3(axis);
            on_axis &= angle_degrees(&w.centroids[3 * cluster], axis) < 1.0;
            first += sizes[b];
        }
        recovered &= made == 5;
    }
    CHECK(recovered, "five bundles, k = 5, 8 restarts, 8 streams: each bundle is one cluster of "
          "its own");
    CHECK(on_axis, "... whose centroid lies within 1 degree of the bundle's direction");
    gb_vdl_workspace_free(&w);
}

/* Directions at angles theta_i in one plane, weights w_i: Σ w |d - c|² =
 * Σ w (2 - 2 cos(theta_i - theta)) is least where Σ w sin(theta_i - theta)
 * = 0, tan theta = Σ w sin theta_i / Σ w cos theta_i (by hand, not
 * kmeans.c's normalised sum). Group A: +z (power 9) and 40 degrees from it
 * toward +x (power 1), so theta = atan2(sin 40, 9 + cos 40) = 3.77 degrees
 * from +z; group B: -z (power 1) and 40 degrees from it toward +y (power
 * 4), 32.33 degrees. Unweighted means would put both at 20 degrees. */
static void weighted_groups(gb_vdl_workspace *w, float expected[2][3])
{
    const double t = 40.0 * PI / 180.0;
    const float a0[3] = {0, 0, 1}, a1[3] = {(float)sin(t), 0, (float)cos(t)};
    const float b0[3] = {0, 0, -1}, b1[3] = {0, (float)sin(t), -(float)cos(t)};
    const float nine[3] = {3, 3, 3}, one[3] = {0.5f, 0.25f, 0.25f}, four[3] = {1, 2, 1};
    gb_random rng = gb_random_make(17, 0);
    add_bundle(w, a0, 1, 0.0f, nine, &rng);
    add_bundle(w, a1, 1, 0.0f, one, &rng);
    add_bundle(w, b0, 1, 0.0f, one, &rng);
    add_bundle(w, b1, 1, 0.0f, four, &rng);
    double ta = atan2(sin(t), 9.0 + cos(t)), tb = atan2(4.0 * sin(t), 1.0 + 4.0 * cos(t));
    const float a[3] = {(float)sin(ta), 0, (float)cos(ta)};
    const float b[3] = {0, (float)sin(tb), -(float)cos(tb)};
    memcpy(expected[0], a, sizeof a);
    memcpy(expected[1], b, sizeof b);
}

/* The centroids k-means makes of weighted_groups, and the VDLs of the
 * same photons, against the minimisers worked out by hand there; the VDLs'
 * irradiance is each group's power over pi r² (r = 1). */
static void test_weighted_centroids(void)
{
    gb_vdl_workspace w;
    CHECK(empty_workspace(&w, 4), "workspace");
    float expected[2][3];
    weighted_groups(&w, expected);
    gb_kmeans_options o = {.restarts = 4};
    gb_random seed = gb_random_make(18, 0);
    uint32_t made = gb_kmeans_directions(w.directions, w.weights, w.count, 2, &o, &seed,
                                         w.centroids, w.assignment, w.scratch);
    uint32_t a = w.assignment[0], b = w.assignment[2];
    CHECK(made == 2 && a != b && w.assignment[1] == a && w.assignment[3] == b,
          "weighted groups, k = 2: each group one cluster");
    double off_a = angle_degrees(&w.centroids[3 * a], expected[0]);
    double off_b = angle_degrees(&w.centroids[3 * b], expected[1]);
    printf("# weighted centroids: %.4f and %.4f degrees from the minimisers by hand\n", off_a,
           off_b);
    CHECK(off_a < 0.1 && off_b < 0.1, "... centroids at the power-weighted minimisers of "
          "Σ w |d - c|² (3.77 and 32.33 degrees into each group), within 0.1 degree");
    gb_light_octree_vdl vdls[8];
    double error;
    w.kmeans.restarts = 4;
    w.vdls_max = 2;
    seed = gb_random_make(18, 1);
    gb_surface_normal normals[1] = {{{0, 0, 1}, 1}};
    vdl_target always = target_of(1.0f, -1.0f, expected[0], normals, 1);
    CHECK_EQ_INT(gb_vdls_from_photons(&w, &always, &seed, vdls, &error), 2,
                 "... as VDLs, K_max 2 always: two");
    float da[3], db[3];
    gb_photon_unpack_direction(vdls[0].direction, da);
    gb_photon_unpack_direction(vdls[1].direction, db);
    printf("# weighted VDLs: %.4f and %.4f degrees from the minimisers by hand\n",
           angle_degrees(da, expected[0]), angle_degrees(db, expected[1]));
    CHECK(angle_degrees(da, expected[0]) < 0.1 && angle_degrees(db, expected[1]) < 0.1,
          "... brightest (A) first, each along its group's minimiser (within 0.1 degree)");
    CHECK(fabs(vdls[0].irradiance[0] - 3.5 / PI) < 1e-5 &&
              fabs(vdls[1].irradiance[1] - 2.25 / PI) < 1e-5,
          "... irradiance: the group's power / (pi r²)");
    gb_vdl_workspace_free(&w);
}

/* ---- photons of suns on a plane -------------------------------------------- */

/* A black 2 x 2 plane at y = 0 facing +y, lit by `suns` suns of irradiance 1
 * from directions (+-0.6, -0.8, 0): each brings E cos(theta) = 0.8. */
static void build_sunny_plane(gb_scene *scene, int suns)
{
    memset(scene, 0, sizeof *scene);
    uint32_t black = add_grey(scene, 0.0f, 0.0f);
    const float plane[4][3] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    const float above[3] = {0, 1, 0}, one[3] = {1, 1, 1};
    add_quad_facing(scene, plane, above, black);
    const float from_right[3] = {-0.6f, -0.8f, 0.0f}, from_left[3] = {0.6f, -0.8f, 0.0f};
    add_point_light(scene, GB_LIGHT_DIRECTIONAL, NULL, from_left, one);
    if (suns == 2)
        add_point_light(scene, GB_LIGHT_DIRECTIONAL, NULL, from_right, one);
    scene_done(scene);
}

static gb_photon_map trace_plane(const gb_scene *scene, uint64_t count)
{
    gb_photons_options o = {.count = count, .bounces = 1, .store = GB_PHOTON_STORE_ALL,
                            .seed = 5, .threads = 2};
    gb_photon_map map;
    gb_error error;
    if (gb_photons_trace(scene, &o, &map, NULL, &error) != GB_OK) {
        printf("Bail out! photons: %s\n", error.message);
        exit(1);
    }
    return map;
}

static int interior(const gb_light_octree *octree, const gb_light_octree_leaf *leaf)
{
    const gb_light_octree_header *h = &octree->header;
    float edge = h->size / (float)(1u << h->depth);
    uint32_t cell[3];
    gb_light_octree_leaf_cell(leaf, cell);
    float x = h->origin[0] + (cell[0] + 0.5f) * edge;
    float z = h->origin[2] + (cell[2] + 0.5f) * edge;
    return fabsf(x) < 0.55f && fabsf(z) < 0.55f;
}

/* The relation checked: on a plane lit by suns, a leaf's VDLs point to the
 * suns and their irradiances sum to the analytic E cos(theta) per sun (the
 * density estimate is unbiased on a plane away from its edges): mean within
 * 3 %, every leaf within 30 % (K = 300: 1/sqrt(K) = 6 % noise). */
static void check_suns(const gb_light_octree *octree, int suns, const char *what)
{
    const float toward[2][3] = {{-0.6f, 0.8f, 0.0f}, {0.6f, 0.8f, 0.0f}};
    uint32_t counted = 0, right_count = 0, right_direction = 0, within = 0;
    double mean = 0.0;
    for (uint32_t i = 0; i < octree->header.leaf_count; ++i) {
        const gb_light_octree_leaf *leaf = &octree->leaves[i];
        if (!interior(octree, leaf))
            continue;
        ++counted;
        right_count += leaf->vdl_count == (uint32_t)suns;
        double sum = 0.0;
        int directions_ok = 1;
        for (uint32_t j = 0; j < leaf->vdl_count; ++j) {
            const gb_light_octree_vdl *v = &octree->vdls[leaf->first_vdl + j];
            float d[3];
            gb_photon_unpack_direction(v->direction, d);
            double best = 180.0;
            for (int s = 0; s < suns; ++s)
                best = fmin(best, angle_degrees(d, toward[s]));
            directions_ok &= best < 0.1;
            sum += v->irradiance[0];
        }
        right_direction += directions_ok;
        within += fabs(sum - 0.8 * suns) < 0.3 * 0.8 * suns;
        mean += sum;
    }
    char text[160];
    snprintf(text, sizeof text, "%s: every interior leaf has %d VDL(s)", what, suns);
    CHECK(counted > 0 && right_count == counted, text);
    snprintf(text, sizeof text, "%s: ... pointing to the suns (within 0.1 degree)", what);
    CHECK(right_direction == counted, text);
    snprintf(text, sizeof text, "%s: mean irradiance is %d x E cos(theta) = %.1f", what, suns,
             0.8 * suns);
    CHECK_NEAR(mean / (counted ? counted : 1), 0.8 * suns, 0.03 * 0.8 * suns, text);
    snprintf(text, sizeof text, "%s: every leaf within 30 %%", what);
    CHECK(within == counted, text);
}

/* With K_max suns VDLs a leaf, always (the paper's fixed count), or with
 * vdls_max 0: the defaults, the count chosen by the error. */
static gb_light_octree cluster_plane(const gb_scene *scene, const gb_photon_map *map,
                                     int threads, uint32_t vdls_max)
{
    gb_cluster_options o = {.depth = 4, .threads = threads, .seed = 11, .vdls_max = vdls_max,
                            .tolerance = vdls_max ? -1.0f : 0.0f};
    gb_light_octree octree;
    gb_error error;
    if (gb_cluster_build(scene, map, &o, &octree, NULL, &error) != GB_OK) {
        printf("Bail out! cluster: %s\n", error.message);
        exit(1);
    }
    return octree;
}

/* Every leaf of the plane y = 0 stores that plane (light_octree.h): its
 * offset from the leaf's centre along the normal (+y) is -centre_y, in
 * cell edges, within the 16-bit step. */
static void check_planes_hold_y0(const gb_light_octree *octree)
{
    const gb_light_octree_header *h = &octree->header;
    double edge = h->size / (double)(1u << h->depth), worst = 0.0;
    for (uint32_t i = 0; i < h->leaf_count; ++i) {
        uint32_t cell[3];
        gb_light_octree_leaf_cell(&octree->leaves[i], cell);
        double centre_y = h->origin[1] + (cell[1] + 0.5) * edge;
        worst = fmax(worst, fabs(octree->leaves[i].plane / 32767.0 + centre_y / edge));
    }
    CHECK(h->leaf_count > 0 && worst < 1e-4, "every leaf's plane is the plane y = 0");
}

static void test_one_sun(void)
{
    gb_scene scene;
    build_sunny_plane(&scene, 1);
    gb_photon_map map = trace_plane(&scene, 40000);
    gb_light_octree octree = cluster_plane(&scene, &map, 2, 1);
    check_suns(&octree, 1, "one sun");
    check_planes_hold_y0(&octree);
    gb_light_octree_free(&octree);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

static int write_and_load(const gb_light_octree *octree, const char *path, unsigned char **bytes,
                          long *size)
{
    gb_error error;
    if (gb_light_octree_write(path, octree, &error) != GB_OK)
        return 0;
    FILE *file = fopen(path, "rb");
    if (!file)
        return 0;
    fseek(file, 0, SEEK_END);
    *size = ftell(file);
    fseek(file, 0, SEEK_SET);
    *bytes = aligned_alloc(16, ((size_t)*size + 15) / 16 * 16);
    int ok = *bytes && fread(*bytes, 1, (size_t)*size, file) == (size_t)*size;
    fclose(file);
    return ok;
}

/* Corruptions of a valid octree that the checker must refuse. */
static void test_corrupt(const gb_light_octree *good)
{
    const gb_light_octree_header *h = &good->header;
    size_t node_bytes = h->node_count * sizeof(gb_light_octree_node);
    size_t leaf_bytes = h->leaf_count * sizeof(gb_light_octree_leaf);
    size_t vdl_bytes = h->vdl_count * sizeof(gb_light_octree_vdl);
    gb_light_octree_node *nodes = malloc(node_bytes);
    gb_light_octree_leaf *leaves = malloc(leaf_bytes);
    gb_light_octree_vdl *vdls = malloc(vdl_bytes);
    gb_light_octree bad = {.header = *h, .nodes = nodes, .leaves = leaves, .vdls = vdls};
    gb_error error;
#define RESET() (memcpy(nodes, good->nodes, node_bytes), memcpy(leaves, good->leaves, leaf_bytes), \
                 memcpy(vdls, good->vdls, vdl_bytes), bad.header = *h)
    RESET();
    CHECK(gb_light_octree_check(&bad, "copy", &error) == GB_OK, "a copy checks");
    uint32_t c = 0;
    while (nodes[0].child[c] == GB_LIGHT_OCTREE_NONE)
        ++c;
    nodes[0].child[c] = h->node_count;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "child index out of range refused");
    RESET();
    for (uint32_t k = 0; k < 8; ++k)
        if (nodes[0].child[k] == GB_LIGHT_OCTREE_NONE) {
            nodes[0].child[k] = nodes[0].child[c];
            break;
        }
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "a node reached twice refused");
    RESET();
    leaves[0].vdl_count += 1;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "VDL ranges that do not follow each other refused");
    RESET();
    vdls[0].irradiance[1] = NAN;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT, "NaN irradiance refused");
    RESET();
    leaves[0].normal &= 0xFFFF0000u;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "a packed normal with a zero field refused");
    RESET();
    leaves[1].normal &= 0x0000FFFFu;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "a packed normal with a zero y field refused");
    RESET();
    bad.header.depth = 11;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT, "depth 11 refused");
    RESET();
    bad.header.interpolation = GB_LIGHT_OCTREE_SURFACE + 1;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "an interpolation other than trilinear or surface refused");
    RESET();
    leaves[1].cell ^= 1;
    CHECK(gb_light_octree_check(&bad, "x", &error) == GB_ERROR_FORMAT,
          "a leaf naming another cell refused");
#undef RESET
    free(nodes);
    free(leaves);
    free(vdls);
}

static void test_file_corruption(const unsigned char *bytes, long size)
{
    gb_light_octree octree;
    gb_error error;
    CHECK(gb_light_octree_parse(bytes, (size_t)size, "good", &octree, &error) == GB_OK,
          "the file parses");
    gb_light_octree_free(&octree);
    unsigned char *copy = aligned_alloc(16, ((size_t)size + 15) / 16 * 16);
    memcpy(copy, bytes, (size_t)size);
    copy[size / 2] ^= 0x40;
    CHECK(gb_light_octree_parse(copy, (size_t)size, "flip", &octree, &error) != GB_OK,
          "a flipped byte refused");
    CHECK(gb_light_octree_parse(bytes, (size_t)size - 8, "cut", &octree, &error) != GB_OK,
          "a truncated file refused");
    free(copy);
}

/* Two suns; bytes with 1 and 2 threads; then the corruptions. */
static void test_two_suns_and_determinism(void)
{
    gb_scene scene;
    build_sunny_plane(&scene, 2);
    gb_photon_map map = trace_plane(&scene, 60000);
    gb_light_octree two = cluster_plane(&scene, &map, 2, 2);
    gb_light_octree one = cluster_plane(&scene, &map, 1, 2);
    check_suns(&two, 2, "two suns, K_max 2 always");
    gb_light_octree chosen = cluster_plane(&scene, &map, 2, 0);
    uint32_t single = 0, counted = 0;
    double same = 0.0;
    for (uint32_t i = 0; i < chosen.header.leaf_count; ++i)
        if (interior(&chosen, &chosen.leaves[i])) {
            const gb_light_octree_leaf *leaf = &chosen.leaves[i], *paper = &two.leaves[i];
            double sum = 0.0, paper_sum = 0.0;
            for (uint32_t j = 0; j < leaf->vdl_count; ++j)
                sum += chosen.vdls[leaf->first_vdl + j].irradiance[0];
            for (uint32_t j = 0; j < paper->vdl_count; ++j)
                paper_sum += two.vdls[paper->first_vdl + j].irradiance[0];
            single += leaf->vdl_count == 1;
            same = fmax(same, fabs(sum - paper_sum) / paper_sum);
            ++counted;
        }
    CHECK(counted > 0 && single == counted, "two suns, the count chosen by the error: one VDL a "
          "leaf of the plane, exact at its one normal");
    CHECK(same < 1e-5, "... bringing the irradiance of the two");
    gb_light_octree_free(&chosen);
    char path_one[64], path_two[64];
    snprintf(path_one, sizeof path_one, "/tmp/test_cluster_%d_1.lot", (int)getpid());
    snprintf(path_two, sizeof path_two, "/tmp/test_cluster_%d_2.lot", (int)getpid());
    unsigned char *bytes_one = NULL, *bytes_two = NULL;
    long size_one = 0, size_two = 0;
    int written = write_and_load(&one, path_one, &bytes_one, &size_one) &&
                  write_and_load(&two, path_two, &bytes_two, &size_two);
    CHECK(written && size_one == size_two && memcmp(bytes_one, bytes_two, (size_t)size_one) == 0,
          "the same file bytes with 1 and 2 threads");
    gb_light_octree read;
    gb_error error;
    CHECK(gb_light_octree_read(path_two, &read, &error) == GB_OK &&
              gb_light_octree_check_scene(&read, scene.hash, path_two, &error) == GB_OK,
          "the file reads back, made from this scene");
    CHECK_EQ_INT(gb_light_octree_check_scene(&read, scene.hash ^ 1, path_two, &error),
                 GB_ERROR_STALE, "... and is stale for another scene");
    const float centre[3] = {0.01f, 0.0f, 0.01f}, outside[3] = {5.0f, 0.0f, 0.0f};
    uint32_t leaf = gb_light_octree_find_leaf(&read, centre);
    CHECK(leaf != GB_LIGHT_OCTREE_NONE && read.leaves[leaf].vdl_count == 2 &&
              gb_light_octree_find_leaf(&read, outside) == GB_LIGHT_OCTREE_NONE,
          "find_leaf walks depth nodes to the leaf of a point on the plane");
    gb_light_octree_free(&read);
    if (written)
        test_file_corruption(bytes_two, size_two);
    test_corrupt(&two);
    remove(path_one);
    remove(path_two);
    free(bytes_one);
    free(bytes_two);
    gb_light_octree_free(&one);
    gb_light_octree_free(&two);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* The Cornell box with indirect photons only: every leaf that gathers gets
 * 1..K_max VDLs, all finite; the walls near the light are lit. */
static void test_cornell_box(void)
{
    gb_scene scene = {0};
    build_cornell_box(&scene, 64, 64);
    gb_photons_options po = {.count = 20000, .seed = 3, .threads = 2};
    gb_photon_map map;
    gb_error error;
    CHECK(gb_photons_trace(&scene, &po, &map, NULL, &error) == GB_OK, "Cornell box photons");
    gb_cluster_options o = {.depth = 4, .threads = 2, .knn = 100};
    gb_light_octree octree;
    gb_cluster_stats stats;
    CHECK(gb_cluster_build(&scene, &map, &o, &octree, &stats, &error) == GB_OK,
          "Cornell box clustered");
    uint32_t lit = 0, bounded = 1;
    for (uint32_t i = 0; i < octree.header.leaf_count; ++i) {
        lit += octree.leaves[i].vdl_count > 0;
        bounded &= octree.leaves[i].vdl_count <= 8;
    }
    CHECK(lit > 0.9 * octree.header.leaf_count && bounded,
          "more than 90 % of the leaves lit, none with more than K_max VDLs");
    CHECK(gb_light_octree_check(&octree, "cornell", &error) == GB_OK, "... a valid octree");
    CHECK_EQ_INT(stats.leaves, octree.header.leaf_count, "... stats count the leaves");
    gb_light_octree_free(&octree);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}

/* A map of another scene, or with a NaN, is refused; K above the photons and
 * leaves without photons are fine. */
static void test_bad_inputs(void)
{
    gb_scene scene;
    build_sunny_plane(&scene, 1);
    gb_photon_map map = trace_plane(&scene, 200);
    gb_light_octree octree;
    gb_error error;
    gb_cluster_options o = {.depth = 3, .knn = 100000, .threads = 2};
    CHECK(gb_cluster_build(&scene, &map, &o, &octree, NULL, &error) == GB_OK,
          "K above the photon count works");
    uint32_t empty = 0;
    for (uint32_t i = 0; i < octree.header.leaf_count; ++i)
        empty += octree.leaves[i].vdl_count == 0;
    CHECK(octree.header.vdl_count > 0, "... and gives VDLs");
    gb_light_octree_free(&octree);
    o.radius = 0.01f;
    o.knn = 300;
    CHECK(gb_cluster_build(&scene, &map, &o, &octree, NULL, &error) == GB_OK,
          "a tiny radius works");
    empty = 0;
    for (uint32_t i = 0; i < octree.header.leaf_count; ++i)
        empty += octree.leaves[i].vdl_count == 0;
    CHECK(empty > 0, "... leaves with no photon have no VDL");
    gb_light_octree_free(&octree);
    o.radius = 0.0f;
    map.header.scene_hash ^= 1;
    CHECK_EQ_INT(gb_cluster_build(&scene, &map, &o, &octree, NULL, &error), GB_ERROR_STALE,
                 "a map of another scene refused");
    map.header.scene_hash ^= 1;
    gb_photon_map nan_map;
    gb_photon_arrays a;
    gb_photon_map_allocate(&nan_map, map.count, &a, &error);
    nan_map.header = map.header;
    memcpy(a.positions, map.positions, map.count * 12);
    memcpy(a.powers, map.powers, map.count * 12);
    memcpy(a.directions, map.directions, map.count * 4);
    memcpy(a.normals, map.normals, map.count * 4);
    a.positions[4] = NAN;
    CHECK(gb_cluster_build(&scene, &nan_map, &o, &octree, NULL, &error) != GB_OK,
          "a NaN photon position refused");
    o.depth = 11;
    CHECK_EQ_INT(gb_cluster_build(&scene, &map, &o, &octree, NULL, &error), GB_ERROR_ARGUMENT,
                 "depth 11 refused");
    gb_photon_map_free(&nan_map);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
}


/* count photons at random in the unit cube, in one cluster of a tenth of
 * them near the corner (so that a halo can hold fewer than K). */
static gb_photon_map random_photons(uint64_t count)
{
    gb_photon_map map;
    gb_photon_arrays a;
    gb_error error;
    if (gb_photon_map_allocate(&map, count, &a, &error) != GB_OK) {
        printf("Bail out! %s\n", error.message);
        exit(1);
    }
    gb_random rng = gb_random_make(11, 0);
    for (uint64_t i = 0; i < count; ++i) {
        float scale = i % 10 == 0 ? 0.05f : 1.0f;
        for (int k = 0; k < 3; ++k) {
            a.positions[3 * i + k] = scale * gb_random_float(&rng);
            a.powers[3 * i + k] = 1.0f;
        }
        a.directions[i] = a.normals[i] = (uint32_t)i;
    }
    return map;
}

static double distance2(const float *a, const float *b)
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/* Brute force: every photon within R of one of the points is in the halo,
 * and the halo keeps the map's order (the directions hold the index). */
static int halo_is_superset(const gb_photon_map *map, const gb_photon_map *halo,
                            const float *points, uint32_t first, uint32_t end, float R)
{
    uint64_t at = 0;
    for (uint64_t i = 0; i < map->count; ++i) {
        int near = 0;
        for (uint32_t j = first; j < end && !near; ++j)
            near = distance2(&map->positions[3 * i], &points[3 * (size_t)j]) <= (double)R * R;
        while (at < halo->count && halo->directions[at] < i)
            ++at;
        if (near && (at == halo->count || halo->directions[at] != i))
            return 0;
    }
    for (uint64_t k = 1; k < halo->count; ++k)
        if (halo->directions[k] <= halo->directions[k - 1])
            return 0;
    return 1;
}

/* One point's gathering: the photons kept (as map indices, from the
 * directions) and the radius. */
static uint32_t gather_one(const gb_gathering *g, const float point[3], float R, int *indices,
                           float *distances2, uint32_t *kept, float *radius)
{
    gb_error error;
    const float normal[3] = {0.0f, 1.0f, 0.0f};
    if (gb_gathering_knn(g, point, 1, indices, distances2, &error) != GB_OK)
        return UINT32_MAX;
    uint32_t n = gb_gather_ellipsoid(g, point, normal, indices, distances2, R, 1e-6f, 2.0f,
                                     kept, radius);
    for (uint32_t i = 0; i < n; ++i)
        kept[i] = g->map->directions[kept[i]];
    return n;
}

static void test_halo(void)
{
    gb_photon_map map = random_photons(4000);
    enum { POINTS = 64, K = 60 };
    float points[3 * POINTS];
    gb_random rng = gb_random_make(12, 0);
    for (int group = 0; group < POINTS / 8; ++group) {  /* 8 points within 0.03 */
        float centre[3];
        for (int k = 0; k < 3; ++k)
            centre[k] = group == 0 ? 0.02f : 0.1f + 0.8f * gb_random_float(&rng);
        for (int i = 8 * group; i < 8 * group + 8; ++i)
            for (int k = 0; k < 3; ++k)
                points[3 * i + k] = centre[k] + 0.03f * gb_random_float(&rng);
    }
    const float R = 0.08f;
    gb_error error;
    gb_gathering whole, part;
    int built = gb_gathering_build(&map, K, 1, &whole, &error) == GB_OK;
    int superset = 1, same = built, short_halo = 0;
    for (uint32_t first = 0; first < POINTS; first += 8) {
        gb_photon_map halo;
        if (gb_cluster_halo(&map, points, first, first + 8, R, &halo, &error) != GB_OK ||
            gb_gathering_build(&halo, K, 1, &part, &error) != GB_OK) {
            same = 0;
            break;
        }
        superset &= halo_is_superset(&map, &halo, points, first, first + 8, R);
        short_halo |= halo.count < K;
        for (uint32_t j = first; j < first + 8; ++j) {
            int i1[K], i2[K];
            float d1[K], d2[K], r1, r2;
            uint32_t k1[K], k2[K];
            uint32_t n1 = gather_one(&whole, &points[3 * j], R, i1, d1, k1, &r1);
            uint32_t n2 = gather_one(&part, &points[3 * j], R, i2, d2, k2, &r2);
            same &= n1 == n2 && n1 != UINT32_MAX && r1 == r2 &&
                    memcmp(k1, k2, n1 * sizeof *k1) == 0;
        }
        gb_gathering_free(&part);
        gb_photon_map_free(&halo);
    }
    CHECK(superset, "each halo holds every photon within R of its points, in the map's order");
    CHECK(same, "... and gathers the photons and radius of the whole map at each point");
    CHECK(short_halo, "... a halo of fewer photons than K among them");
    gb_photon_map none;
    CHECK(gb_cluster_halo(&map, points, 5, 5, R, &none, &error) == GB_OK && none.count == 0,
          "no leaves: an empty halo");
    gb_photon_map_free(&none);
    if (built)
        gb_gathering_free(&whole);
    gb_photon_map_free(&map);
}

int main(void)
{
    test_octree_single_triangle();
    test_octree_area_weighted_normal();
    test_octree_box_shell();
    test_two_bundles();
    test_identical_directions();
    test_count_by_error();
    test_shading_normals();
    test_spread_of_rings();
    test_cosine_hemisphere();
    test_known_clusters();
    test_weighted_centroids();
    test_one_sun();
    test_two_suns_and_determinism();
    test_bad_inputs();
    test_cornell_box();
    test_halo();
    return tap_done();
}
