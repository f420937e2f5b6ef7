/* test_topo.c — the CPU passes of the topological method (runtime/topo/topo.h):
 * VPLs traced from the lights (count, validity, determinism, energy: a
 * point light, a sun, area lights), the gate cone tests, IUGC (one
 * visibility cluster per geometry cluster, the spheres bound their
 * fragments) and LA on two rooms joined by a door: a VPL in room A
 * reaches room B only inside the cone through the door gate; three rooms:
 * room C only through both doors' cones; a VPL at a door
 * lights through the disk only; the lookup off a tilted wall never lands in
 * the wall's voxels; a gate fitted to its opening lets light through its
 * edge (the fit itself: test_segment);
 * LA on the GPU gives the CPU's lists, and the GPU's visibility cluster of
 * each fragment is the CPU's; IL's bounded 1/r^2 under a VPL close to a
 * floor against the formula by hand (headless GL: a failed check without
 * it). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "random.h"
#include "scene_builder.h"
#include "tap.h"
#include "topo_quadrants.h"

static void test_vpls_cornell(void)
{
    gb_scene scene = {0};
    build_cornell_box(&scene, 32, 32);
    gb_error error;
    gb_vpl_set a, b;
    CHECK(gb_topo_vpls_generate(&scene, 300, 7, &a, &error) == GB_OK, "VPLs: Cornell box traced");
    CHECK(gb_topo_vpls_generate(&scene, 300, 7, &b, &error) == GB_OK, "VPLs: traced again");
    CHECK_EQ_INT(a.count, 300, "VPLs: exactly the count asked");
    CHECK(a.count == b.count && memcmp(a.vpls, b.vpls, a.count * sizeof *a.vpls) == 0,
          "VPLs: same seed, same bytes");
    CHECK(gb_vpl_check(&a, "cornell", &error) == GB_OK, "VPLs: a valid VPL set");
    CHECK(a.scene_hash == scene.hash, "VPLs: the scene's hash");
    int inside = 1;
    for (uint32_t i = 0; i < a.count; ++i)
        for (int c = 0; c < 3; ++c)
            inside &= a.vpls[i].position[c] >= scene.bounds_min[c] - 1e-3f &&
                      a.vpls[i].position[c] <= scene.bounds_max[c] + 1e-3f;
    CHECK(inside, "VPLs: on the scene's surfaces (within its bounds)");
    gb_vpl_free(&b);
    CHECK(gb_topo_vpls_generate(&scene, 0, 7, &b, &error) == GB_ERROR_ARGUMENT,
          "VPLs: 0 refused");
    gb_vpl_free(&a);
    gb_vpl_free(&b);
    gb_scene_free(&scene);
}

/* Channel c of the power summed over count VPLs traced in scene with
 * seed; the trace checked as what. */
static double vpl_power(const gb_scene *scene, uint32_t count, uint64_t seed, int c,
                        const char *what)
{
    gb_error error;
    gb_vpl_set set;
    double sum = 0.0;
    if (CHECK(gb_topo_vpls_generate(scene, count, seed, &set, &error) == GB_OK, what)) {
        for (uint32_t i = 0; i < set.count; ++i)
            sum += set.vpls[i].power[c];
        gb_vpl_free(&set);
    }
    return sum;
}

/* A closed grey box of albedo 1/2 around a point light: the VPLs' power sums
 * to Phi (a + a^2 + ...) = Phi in expectation. */
static void test_vpls_energy(void)
{
    gb_scene scene = {0};
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    add_box(&scene, (float[3]){-1, -1, -1}, (float[3]){1, 1, 1}, 1, grey);
    add_point_light(&scene, GB_LIGHT_POINT, (float[3]){0.1f, 0.2f, 0.3f},
                    (float[3]){0, 0, -1}, (float[3]){2, 2, 2});
    set_camera(&scene, (float[3]){0, 0, 0.9f}, (float[3]){0, 0, 0}, 60.0f, 16, 16);
    scene_done(&scene);
    CHECK_NEAR(vpl_power(&scene, 20000, 1, 0, "energy: traced"), 4.0 * M_PI * 2.0,
               0.06 * 4.0 * M_PI * 2.0,
               "energy: VPL powers sum to the light's power (albedo 1/2, closed box)");
    gb_scene_free(&scene);
}

/* A grey floor of 10 x 10 under a sun of irradiance 3 straight down: the
 * VPLs (first bounces; later ones escape upward) carry 3 x 100 x 1/2. */
static void test_vpls_sun(void)
{
    gb_scene scene = {0};
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    const float floor[4][3] = {{-5, 0, -5}, {5, 0, -5}, {5, 0, 5}, {-5, 0, 5}};
    add_quad_facing(&scene, floor, (float[3]){0, 1, 0}, grey);
    add_point_light(&scene, GB_LIGHT_DIRECTIONAL, (float[3]){0, 0, 0}, (float[3]){0, -1, 0},
                    (float[3]){3, 3, 3});
    set_camera(&scene, (float[3]){0, 5, 8}, (float[3]){0, 0, 0}, 60.0f, 16, 16);
    scene_done(&scene);
    CHECK_NEAR(vpl_power(&scene, 8000, 2, 1, "sun: traced"), 150.0, 0.05 * 150.0,
               "sun: VPL powers sum to E x area x albedo");
    gb_scene_free(&scene);
}

/* Area lights in a closed grey box of albedo 1/2: two emissive panels (Kd
 * 1/2 as well, so every surface a path hits reflects half of what arrives)
 * of radiance Ke emit Phi = pi sum Ke area (a Lambertian emitter's exitance
 * is pi Ke), here pi (4 x 1/4 + 1 x 1/2) = 1.5 pi, from the scene's numbers
 * alone; the VPLs' power then sums to Phi (a + a^2 + ...) = Phi in
 * expectation, as for the point light above. */
static void test_vpls_area_lights(void)
{
    gb_scene scene = {0};
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    uint32_t bright = add_grey(&scene, 0.5f, 4.0f), dim = add_grey(&scene, 0.5f, 1.0f);
    add_box(&scene, (float[3]){-1, -1, -1}, (float[3]){1, 1, 1}, 1, grey);
    const float panel[4][3] = {{-0.25f, 0.9f, -0.25f}, {0.25f, 0.9f, -0.25f},
                               {0.25f, 0.9f, 0.25f}, {-0.25f, 0.9f, 0.25f}};
    const float strip[4][3] = {{-0.9f, -0.5f, -0.25f}, {-0.9f, 0.5f, -0.25f},
                               {-0.9f, 0.5f, 0.25f}, {-0.9f, -0.5f, 0.25f}};
    const float centre[3] = {0, 0, 0};
    add_quad_facing(&scene, panel, centre, bright);   /* area 1/4, facing down */
    add_quad_facing(&scene, strip, centre, dim);      /* area 1/2, facing +x */
    set_camera(&scene, (float[3]){0, 0, 0.9f}, (float[3]){0, 0, 0}, 60.0f, 16, 16);
    scene_done(&scene);
    double phi = M_PI * (4.0 * 0.25 + 1.0 * 0.5);
    double sum = vpl_power(&scene, 20000, 3, 1, "area lights: traced");
    printf("# area lights: VPL powers sum to %.4f, analytic Phi = %.4f\n", sum, phi);
    CHECK_NEAR(sum, phi, 0.06 * phi,
               "area lights: VPL powers sum to pi sum Ke area (albedo 1/2, closed box)");
    gb_scene_free(&scene);
}

/* Two rooms along x joined by a door at x = 0: cluster 0 (x < 0), cluster
 * 1 (x > 0), one gate of radius 0.5 at the origin. */
static gb_visibility_gate door = {{0, 0, 0}, {1, 0, 0}, 0.5f, {0, 1}, 0};

static void two_rooms(gb_segmentation *s)
{
    memset(s, 0, sizeof *s);
    s->cluster_count = 2;
    s->gate_count = 1;
    s->gates = &door;
}

static void test_cones(void)
{
    float p[3] = {-2, 0, 0};
    CHECK(gb_topo_cone_contains(p, &door, (float[3]){3, 1, 0}), "cone: point in the door's cone");
    CHECK(!gb_topo_cone_contains(p, &door, (float[3]){3, 1.5f, 0}),
          "cone: point beside it (cone radius 1.25 at x = 3)");
    CHECK(!gb_topo_cone_contains(p, &door, (float[3]){-3, 0, 0}), "cone: point behind the VPL");
    CHECK(gb_topo_cone_hits_sphere(p, &door, (float[3]){3, 1.5f, 0}, 0.3f),
          "cone: sphere overlapping its side");
    CHECK(!gb_topo_cone_hits_sphere(p, &door, (float[3]){3, 4, 0}, 0.3f),
          "cone: sphere away from it");
    CHECK(gb_topo_cone_hits_sphere(p, &door, (float[3]){-2, 0.1f, 0}, 0.3f),
          "cone: sphere around the apex");
}

static gb_geometry_cluster sphere_cluster(uint32_t visibility, float x, float y, float r)
{
    gb_geometry_cluster g = {.visibility_cluster = visibility, .centre = {x, y, 0}, .radius = r};
    return g;
}

/* A VPL in room A (cluster 0): at (-2, 0, 0), facing +x. */
static gb_vpl room_a_vpl = {{-2, 0, 0}, {1, 0, 0}, {1, 1, 1}};

/* LA of room A's VPL alone over count geometry clusters. */
static gb_result assign_room_a(gb_geometry_cluster *list, uint32_t count,
                               const gb_segmentation *s, const gb_topo_gates *gates,
                               gb_topo_visibility visibility, gb_topo_assignment *a)
{
    gb_geometry_clusters clusters = {count, count, list};
    gb_vpl_set vpls = {0, 1, &room_a_vpl};
    int32_t vpl_cluster = 0;
    gb_error error;
    return gb_topo_assign(&clusters, &vpls, &vpl_cluster, s, gates, visibility, a, &error);
}

static void test_two_rooms_assignment(void)
{
    gb_segmentation s;
    two_rooms(&s);
    gb_topo_gates gates;
    gb_error error;
    CHECK(gb_topo_gates_build(&s, &gates, &error) == GB_OK, "LA: gates per cluster");
    gb_geometry_cluster list[3] = {sphere_cluster(1, 3, 0, 0.2f), sphere_cluster(1, 3, 4, 0.2f),
                                   sphere_cluster(0, -3, 3, 0.2f)};
    gb_topo_assignment a = {0};
    CHECK(assign_room_a(list, 3, &s, &gates, GB_TOPO_FULL, &a) == GB_OK,
          "LA: two rooms assigned");
    CHECK(a.ranges[1] == 1 && a.entries[a.ranges[0]].vpl == 0 &&
              a.entries[a.ranges[0]].group == 0,
          "LA: room B in the door's cone gets the VPL with the door gate");
    CHECK_EQ_INT(a.ranges[3], 0, "LA: room B outside the cone gets nothing");
    CHECK(a.ranges[5] == 1 && a.entries[a.ranges[4]].group == GB_TOPO_NO_GATE,
          "LA: room A gets its own VPL without a gate");
    CHECK(assign_room_a(list, 3, &s, &gates, GB_TOPO_CLUSTERS, &a) == GB_OK &&
              a.ranges[1] == 0 && a.ranges[5] == 1,
          "LA, gates off: room B gets nothing, room A its VPL");
    gb_topo_assignment_free(&a);
    gb_topo_gates_free(&gates);
}

/* Three rooms along x: cluster 0 (x < 0), 1 (0 < x < 4), 2 (x > 4); door
 * gates of radius 0.5 at x = 0 and x = 4. */
static gb_visibility_gate doors[2] = {{{0, 0, 0}, {1, 0, 0}, 0.5f, {0, 1}, 0},
                                      {{4, 0, 0}, {1, 0, 0}, 0.5f, {1, 2}, 1}};

static void test_routes(void)
{
    gb_segmentation s = {.cluster_count = 3, .gate_count = 2, .gates = doors};
    gb_topo_gates gates;
    gb_error error;
    CHECK(gb_topo_gates_build(&s, &gates, &error) == GB_OK, "routes: built for three rooms");
    /* out of room 0: door 0 into room 1, doors 0 then 1 into room 2 */
    int two_gate = 0;
    for (uint32_t k = gates.route_offsets[0]; k < gates.route_offsets[1]; ++k)
        two_gate += gates.routes[k].target == 2 && gates.routes[k].gates[0] == 0 &&
                    gates.routes[k].gates[1] == 1;
    CHECK(gates.route_offsets[1] == 2 && two_gate == 1,
          "routes: room 0 reaches room 1 through one door, room 2 through both");
    gb_geometry_cluster list[2] = {sphere_cluster(2, 8, 0, 0.2f), sphere_cluster(2, 8, 3, 0.2f)};
    gb_topo_assignment a = {0};
    CHECK(assign_room_a(list, 2, &s, &gates, GB_TOPO_FULL, &a) == GB_OK && a.ranges[1] == 1 &&
              a.ranges[3] == 0,
          "LA: room 2 in line with both doors gets the VPL, off the line nothing");
    const gb_topo_route_group *group = &gates.groups[a.entries[0].group];
    const gb_topo_route *route = &gates.routes[group->first];
    CHECK(group->target == 2 && group->count == 1 && route->gates[0] == 0 &&
              route->gates[1] == 1,
          "LA: ... with the group of routes to room 2: through both doors");
    CHECK(a.entries[0].group == gb_topo_group_of(&gates, 0, 2) &&
              gb_topo_group_of(&gates, 2, 0) != GB_TOPO_NO_GATE &&
              gb_topo_group_of(&gates, 0, 0) == GB_TOPO_NO_GATE,
          "LA: groups found by source and target (none from a room to itself)");
    CHECK(gb_topo_group_contains(room_a_vpl.position, &s, &gates, a.entries[0].group,
                                 (float[3]){8, 0.2f, 0}),
          "IL: a point seen through both doors is lit");
    /* in the cone of the first door (8.5 degrees off its axis, half-angle
     * 14) but not of the second (half-angle 4.8): the paper's test, one
     * cone through a gate of the VPL's cluster, would light it */
    float beside[3] = {8, 1.5f, 0};
    CHECK(gb_topo_cone_contains(room_a_vpl.position, &doors[0], beside) &&
              !gb_topo_route_contains(room_a_vpl.position, &s, route, beside),
          "IL: a point behind the wall between the doors stays dark");
    gb_topo_assignment_free(&a);
    gb_topo_gates_free(&gates);
}

static void test_vpl_at_the_door(void)
{
    float p[3] = {-0.2f, 0, 0};     /* within the door's radius of its centre */
    CHECK(gb_topo_cone_contains(p, &door, (float[3]){3, 0.3f, 0}),
          "gate: from inside its radius, light through the disk passes");
    CHECK(!gb_topo_cone_contains(p, &door, (float[3]){-3, 2, 0}) &&
              !gb_topo_cone_contains(p, &door, (float[3]){1, 4, 0}),
          "gate: ... but not to its own side, nor past the disk's rim");
}

/* A frame of n^3 unit voxels at the origin. */
static gb_segmentation unit_frame(int32_t nx, int32_t ny, int32_t nz)
{
    gb_segmentation s = {.voxel_size = 1.0, .grid_size = {nx, ny, nz}};
    return s;
}

/* A wall through a 16^3 grid, plane x + 2y + 3z = 24 (tilted: its voxels
 * are up to |n|_1 = 1.6 voxels thick along n), clusters 0 on the normal's
 * side, 1 behind; the wall's own voxels get cluster 1, as thin's grid may
 * give them (the node of their best empty neighbour). */
static void test_lookup_off_the_wall(void)
{
    enum { N = 16 };
    gb_segmentation s = unit_frame(N, N, N);
    float n[3] = {1, 2, 3}, len = sqrtf(14.0f), reach = 0.0f;
    for (int a = 0; a < 3; ++a) {
        n[a] /= len;
        reach += 0.5f * fabsf(n[a]);
    }
    int32_t *clusters = malloc(N * N * N * sizeof *clusters);
    uint8_t *surface = malloc(N * N * N);
    for (int i = 0; i < N * N * N; ++i) {
        float c[3] = {i % N + 0.5f, (i / N) % N + 0.5f, i / (N * N) + 0.5f};
        float d = (c[0] + 2 * c[1] + 3 * c[2] - 24.0f) / len;
        surface[i] = fabsf(d) <= reach;
        clusters[i] = d > reach ? 0 : 1;
    }
    int wrong_now = 0, wrong_before = 0, points = 0;
    gb_random rng = gb_random_make(5, 0);
    for (int k = 0; k < 400; ++k) {
        float y = 2 + 4 * gb_random_float(&rng), z = 2 + 2 * gb_random_float(&rng);
        float x[3] = {24 - 2 * y - 3 * z, y, z};
        if (!(x[0] > 3 && x[0] < N - 3))
            continue;
        ++points;
        wrong_now += gb_topo_surface_cluster(&s, clusters, x, n) != 0;
        float one_voxel[3] = {x[0] + n[0], x[1] + n[1], x[2] + n[2]};
        int32_t v[3] = {(int32_t)one_voxel[0], (int32_t)one_voxel[1], (int32_t)one_voxel[2]};
        wrong_before += clusters[v[0] + N * (v[1] + N * v[2])] != 0;
    }
    printf("# lookup: %d points on the wall, one voxel off: %d in the far cluster, now %d\n",
           points, wrong_before, wrong_now);
    CHECK(points > 50 && wrong_before > 0, "lookup: one voxel off a tilted wall can land in it");
    CHECK_EQ_INT(wrong_now, 0, "lookup: |n|_1 voxels off, always the cluster on the normal's side");
    gb_topo_voxel_clusters_mark_surface(&s, clusters, surface);
    int marked = 0;
    for (int i = 0; i < N * N * N; ++i)
        marked += surface[i] ? clusters[i] == GB_TOPO_SURFACE_CLUSTER(1) : clusters[i] >= 0;
    CHECK_EQ_INT(marked, N * N * N, "mark_surface: surface voxels coded, the others untouched");
    /* another surface's voxel where the first offset of a point lands (a
     * corner), with the far side's cluster: used as is it misleads the
     * lookup, marked it is skipped */
    float x[3] = {24 - 2 * 4.0f - 3 * 3.0f, 4.0f, 3.0f}, t = 1.01f * 6.0f / len;
    int32_t v[3] = {(int32_t)(x[0] + t * n[0]), (int32_t)(x[1] + t * n[1]),
                    (int32_t)(x[2] + t * n[2])};
    int32_t *in_the_way = &clusters[v[0] + N * (v[1] + N * v[2])];
    *in_the_way = 1;
    int misled = gb_topo_surface_cluster(&s, clusters, x, n) == 1;
    *in_the_way = GB_TOPO_SURFACE_CLUSTER(1);
    CHECK(misled && gb_topo_surface_cluster(&s, clusters, x, n) == 0,
          "lookup: a marked surface voxel in the way is skipped");
    free(clusters);
    free(surface);
}

/* The door of tests/unit/test_segment.c's two rooms (a 6 x 6 opening in a
 * wall at x = 10): the paper's disk there has radius 0.5, the disk segment
 * fits to the opening radius sqrt(35 / 3) (its faces' second moment). A
 * VPL's light through the opening's edge passes the fitted disk only. */
static void test_fitted_gate_cone(void)
{
    gb_visibility_gate paper = {{10, 5, 5}, {1, 0, 0}, 0.5f, {0, 1}, 0};
    gb_visibility_gate fitted = paper;
    fitted.radius = sqrtf(35.0f / 3.0f);
    float vpl[3] = {4, 5, 5}, lit[3] = {16, 9.5f, 5};
    CHECK(!gb_topo_cone_contains(vpl, &paper, lit) && gb_topo_cone_contains(vpl, &fitted, lit),
          "fitted gate: light through the opening's edge, cut by the paper's disk, passes");
}

/* 64 x 40 pixels, camera at the origin looking down -z: columns < 20 see
 * visibility cluster 3 at depth 1, 20..31 cluster 7 at depth 1, the right
 * half cluster 7 at depth 2; pixel (5, 5) sees nothing. */
static void test_iugc(void)
{
    enum { W = 64, H = 40 };
    static float depth[W * H];
    static uint32_t ids[2 * W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            depth[y * W + x] = x < 32 ? 0.1f : 0.05f;
            ids[2 * (y * W + x)] = x < 20 ? 3u : 7u;
        }
    depth[5 * W + 5] = 0.0f;
    gb_topo_frame_input frame = {W, H, depth, ids, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                                 {0.8f, 0.5f}, 0.1f};
    gb_geometry_clusters clusters = {0};
    gb_error error;
    CHECK(gb_topo_geometry_clusters_build(&frame, &clusters, &error) == GB_OK, "IUGC: built");
    CHECK_EQ_INT(clusters.count, 6, "IUGC: 2 + 1 geometry clusters in each row of tiles");
    int one_visibility = 1, bounded = 1;
    for (int i = 0; i < W * H; ++i) {
        uint32_t g = ids[2 * i + 1];
        if (depth[i] == 0.0f) {
            one_visibility &= g == GB_NO_CLUSTER;
            continue;
        }
        if (g >= clusters.count) {
            one_visibility = 0;
            continue;
        }
        const gb_geometry_cluster *c = &clusters.clusters[g];
        one_visibility &= c->visibility_cluster == ids[2 * i];
        float p[3], d2 = 0.0f;
        gb_topo_pixel_position(&frame, i % W, i / W, depth[i], p);
        for (int a = 0; a < 3; ++a)
            d2 += (p[a] - c->centre[a]) * (p[a] - c->centre[a]);
        bounded &= sqrtf(d2) <= c->radius * 1.0001f + 1e-6f;
    }
    CHECK(one_visibility, "IUGC: each geometry cluster has one visibility cluster; none "
                          "where nothing is seen");
    CHECK(bounded, "IUGC: bounding spheres contain their fragments");
    gb_geometry_clusters_free(&clusters);
}

/* The Cornell box cut into four visibility clusters (topo_quadrants.h),
 * the gates at mid-height; geometry clusters on a grid. */
typedef struct quadrants {
    float mid[3], size[3];
    gb_visibility_gate gates[4];
    gb_segmentation s;
} quadrants;

static int32_t quadrant_of(const quadrants *q, const float p[3])
{
    return (p[0] >= q->mid[0]) + 2 * (p[2] >= q->mid[2]);
}

static void make_quadrants(const gb_scene *scene, quadrants *q)
{
    memset(q, 0, sizeof *q);
    for (int a = 0; a < 3; ++a) {
        q->mid[a] = 0.5f * (scene->bounds_min[a] + scene->bounds_max[a]);
        q->size[a] = scene->bounds_max[a] - scene->bounds_min[a];
    }
    quadrant_gates(q->gates, q->mid, q->size, q->mid[1], &q->s);
}

static void grid_clusters(const gb_scene *scene, const quadrants *q, gb_geometry_clusters *out)
{
    enum { N = 12 };
    out->count = out->capacity = N * N * N;
    out->clusters = calloc(out->count, sizeof *out->clusters);
    for (uint32_t i = 0; i < out->count; ++i) {
        gb_geometry_cluster *g = &out->clusters[i];
        uint32_t index[3] = {i % N, (i / N) % N, i / (N * N)};
        for (int a = 0; a < 3; ++a)
            g->centre[a] = scene->bounds_min[a] + ((float)index[a] + 0.5f) / N * q->size[a];
        g->radius = 0.02f * q->size[0] * (float)(1 + i % 3);
        g->visibility_cluster = (uint32_t)quadrant_of(q, g->centre);
    }
}

static void test_la_cpu_equals_gpu(void)
{
    gb_error error;
    gb_context context;
    if (!gpu_context(&context, "LA"))
        return;
    gb_scene scene = {0};
    build_cornell_box(&scene, 32, 32);
    gb_vpl_set vpls;
    gb_topo_vpls_generate(&scene, 512, 3, &vpls, &error);
    quadrants q;
    make_quadrants(&scene, &q);
    int32_t *vpl_cluster = malloc(vpls.count * sizeof *vpl_cluster);
    for (uint32_t i = 0; i < vpls.count; ++i)
        vpl_cluster[i] = quadrant_of(&q, vpls.vpls[i].position);
    gb_geometry_clusters clusters;
    grid_clusters(&scene, &q, &clusters);
    gb_topo_gates gates;
    gb_topo_gates_build(&q.s, &gates, &error);
    gb_topo_assignment cpu = {0}, gpu = {0};
    CHECK(gb_topo_assign(&clusters, &vpls, vpl_cluster, &q.s, &gates, GB_TOPO_FULL, &cpu,
                         &error) == GB_OK, "LA on the CPU: Cornell box VPLs, 4 clusters");
    gb_topo_gather_pass gather;
    gb_topo_la_gpu la;
    gb_result result = gb_topo_gather_create(&vpls, &q.s, &gates, 1.0f, &gather, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_create(&vpls, vpl_cluster, &gates, &la, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_run(&la, &clusters, GB_TOPO_FULL, &gather, &gpu, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_read(&gather, &gpu, &error);
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    CHECK(result == GB_OK, "LA on the GPU: ran");
    CHECK(cpu.entry_count > clusters.count && cpu.entry_count < clusters.count * vpls.count,
          "LA: some VPLs assigned, not every one everywhere");
    int gated = 0;
    for (uint32_t i = 0; i < cpu.entry_count; ++i)
        gated += cpu.entries[i].group != GB_TOPO_NO_GATE;
    CHECK(gated > 0, "LA: some VPLs assigned through a gate");
    CHECK(result == GB_OK && gpu.entry_count == cpu.entry_count &&
              memcmp(gpu.ranges, cpu.ranges, 2 * cpu.cluster_count * sizeof *cpu.ranges) == 0 &&
              memcmp(gpu.entries, cpu.entries, cpu.entry_count * sizeof *cpu.entries) == 0,
          "LA: the GPU's VPL lists are the CPU's, entry for entry");
    printf("# LA: %u geometry clusters, %u entries (%d through a gate), GPU %u entries\n",
           clusters.count, cpu.entry_count, gated, gpu.entry_count);
    gb_topo_la_gpu_destroy(&la);
    gb_topo_gather_destroy(&gather);
    gb_topo_assignment_free(&cpu);
    gb_topo_assignment_free(&gpu);
    gb_topo_gates_free(&gates);
    gb_geometry_clusters_free(&clusters);
    free(vpl_cluster);
    gb_vpl_free(&vpls);
    gb_scene_free(&scene);
    gb_context_destroy(&context);
}

/* ---- IL's bounded geometric term ---------------------------------------
 * A grey floor (Kd 1/2, y = 0, facing +y) seen straight down from height
 * CLAMP_EYE, and one VPL of power CLAMP_POWER at height CLAMP_HEIGHT above
 * its centre, facing down. By hand, at a floor point rho from the VPL's
 * foot, d^2 = rho^2 + h^2 and both cosines are h / d: the VPL sends
 * P (h/d) / pi (vpl.h), the floor reflects Kd / pi of the irradiance, and
 * IL makes the VPL a virtual spherical light of radius R (Hasan et al.
 * 2009): 1/d^2 becomes the solid angle the sphere subtends,
 * Omega = 2 pi (1 - cos alpha) with sin alpha = R / d (2 pi, the
 * hemisphere, for d <= R), over pi R^2, so
 *   L = Kd P h^2 Omega(d) / (pi^3 d^2 R^2).
 * R (CLAMP_RADIUS) is five times h: under the VPL the sphere cuts L by
 * 12.5 from the unbounded 1/d^2, and doubles the old 1/max(d, R)^2. */
enum { CLAMP_SIZE = 64 };
static const float CLAMP_EYE = 1.0f, CLAMP_FOV = 60.0f, CLAMP_HEIGHT = 0.05f,
                   CLAMP_RADIUS = 0.25f, CLAMP_POWER = 2.0f;

static void build_lit_floor(gb_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    uint32_t grey = add_grey(scene, 0.5f, 0.0f);
    const float floor[4][3] = {{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}};
    add_quad_facing(scene, floor, (float[3]){0, 1, 0}, grey);
    set_camera(scene, (float[3]){0, CLAMP_EYE, 0}, (float[3]){0, 0, 0}, CLAMP_FOV, CLAMP_SIZE,
               CLAMP_SIZE);
    scene_done(scene);
}

/* The hand formula above at pixel (x, y): the pinhole's ray through the
 * pixel's centre meets the floor rho = EYE tan(fov / 2) |ndc| from the
 * VPL's foot (the image is square, the VPL under the eye). */
static double clamped_radiance(int x, int y)
{
    double nx = 2.0 * (x + 0.5) / CLAMP_SIZE - 1.0, ny = 2.0 * (y + 0.5) / CLAMP_SIZE - 1.0;
    double reach = CLAMP_EYE * tan(0.5 * CLAMP_FOV * M_PI / 180.0);
    double h2 = (double)CLAMP_HEIGHT * CLAMP_HEIGHT, r2 = (double)CLAMP_RADIUS * CLAMP_RADIUS;
    double d2 = reach * reach * (nx * nx + ny * ny) + h2;
    double omega = d2 <= r2 ? 2.0 * M_PI : 2.0 * M_PI * (1.0 - sqrt(1.0 - r2 / d2));
    return 0.5 * CLAMP_POWER * h2 * omega / (M_PI * M_PI * M_PI * d2 * r2);
}

/* IL alone (every VPL, no gate) of the one VPL on the floor's G-buffer,
 * read back as RGBA into pixels (CLAMP_SIZE^2 x 4). */
static gb_result gather_floor(const gb_scene *scene, float *pixels, gb_error *error)
{
    gb_vpl vpl = {{0, CLAMP_HEIGHT, 0}, {0, -1, 0}, {CLAMP_POWER, CLAMP_POWER, CLAMP_POWER}};
    gb_vpl_set vpls = {scene->hash, 1, &vpl};
    gb_segmentation s = {0};
    gb_topo_gates gates = {0};
    gb_gpu_scene gpu = {0};
    gb_gbuffer gbuffer = {0};
    gb_topo_gather_pass gather = {0};
    gb_gl_target target = {0};
    gb_view view;
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gb_result result = gb_gpu_scene_create(scene, &gpu, error);
    if (result == GB_OK)
        result = gb_gbuffer_create(CLAMP_SIZE, CLAMP_SIZE, &gbuffer, error);
    if (result == GB_OK)
        result = gb_scene_view(scene, 0, &view, error);
    if (result == GB_OK)
        result = gb_topo_gather_create(&vpls, &s, &gates, CLAMP_RADIUS, &gather, error);
    if (result == GB_OK) {
        gb_mat4 world_to_view = gb_view_matrix(&view);
        gb_mat4 projection = gb_view_projection(&view, CLAMP_SIZE, CLAMP_SIZE);
        gb_gbuffer_draw(&gbuffer, &gpu, &world_to_view, &projection);
        gb_topo_frame_input frame = gb_topo_frame_input_of_view(&view, CLAMP_SIZE, CLAMP_SIZE);
        gb_gl_target_resize(&target, GL_RGBA32F, CLAMP_SIZE, CLAMP_SIZE);
        glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
        glViewport(0, 0, CLAMP_SIZE, CLAMP_SIZE);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        gb_gbuffer_bind(&gbuffer);
        gb_topo_gather_draw(&gather, frame.view_to_world, frame.tan_half_fov, frame.near, 1);
        glGetTextureImage(target.color, 0, GL_RGBA, GL_FLOAT,
                          CLAMP_SIZE * CLAMP_SIZE * 4 * sizeof *pixels, pixels);
    }
    gb_gl_target_release(&target);
    gb_topo_gather_destroy(&gather);
    gb_gbuffer_destroy(&gbuffer);
    gb_gpu_scene_destroy(&gpu);
    return result;
}

/* IL's image of the VPL over the floor against the hand formula, pixel by
 * pixel: independent of the shader (it knows neither the G-buffer nor the
 * shader's reconstruction). The pattern is radially symmetric about the
 * image's centre, so the image's orientation does not matter. */
static void test_gather_clamp(void)
{
    gb_context context;
    if (!gpu_context(&context, "IL clamp"))
        return;
    gb_scene scene;
    build_lit_floor(&scene);
    static float pixels[CLAMP_SIZE * CLAMP_SIZE * 4];
    gb_error error;
    gb_result result = gather_floor(&scene, pixels, &error);
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    CHECK(result == GB_OK, "IL clamp: one VPL over a floor gathered");
    double worst = 0.0, peak = 0.0, expected_peak = 0.0;
    for (int y = 0; result == GB_OK && y < CLAMP_SIZE; ++y)
        for (int x = 0; x < CLAMP_SIZE; ++x) {
            double expected = clamped_radiance(x, y), got = pixels[4 * (y * CLAMP_SIZE + x) + 1];
            worst = fmax(worst, fabs(got - expected) / expected);
            peak = fmax(peak, got);
            expected_peak = fmax(expected_peak, expected);
        }
    printf("# IL clamp: brightest pixel %.5f, by hand %.5f; worst relative error %.2g\n", peak,
           expected_peak, worst);
    CHECK(result == GB_OK && worst < 0.01,
          "IL clamp: every pixel within 1 % of Kd P h^2 Omega(d) / (pi^3 d^2 R^2), a "
          "spherical light of radius R");
    gb_scene_free(&scene);
    gb_context_destroy(&context);
}

static void oct_decode(float x, float y, float n[3])
{
    n[0] = x;
    n[1] = y;
    n[2] = 1.0f - fabsf(x) - fabsf(y);
    if (n[2] < 0.0f) {
        n[0] = (1.0f - fabsf(y)) * (x >= 0.0f ? 1.0f : -1.0f);
        n[1] = (1.0f - fabsf(x)) * (y >= 0.0f ? 1.0f : -1.0f);
    }
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; ++a)
        n[a] /= l;
}

/* Compares the GPU's cluster of each fragment with gb_topo_surface_cluster
 * on the fragment read back; returns how many differ, *seen the fragments. */
static int compare_cluster_lookup(const gb_gbuffer *gbuffer, const gb_segmentation *s,
                                  const int32_t *voxels, const gb_topo_frame_input *frame,
                                  int *seen, unsigned *kinds)
{
    int w = frame->width, h = frame->height, differ = 0;
    float *depth = malloc((size_t)w * h * sizeof *depth);
    float *normal = malloc((size_t)w * h * 4 * sizeof *normal);
    uint32_t *ids = malloc((size_t)w * h * 2 * sizeof *ids);
    glGetTextureImage(gbuffer->depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, w * h * 4, depth);
    glGetTextureImage(gbuffer->normal, 0, GL_RGBA, GL_FLOAT, w * h * 16, normal);
    glGetTextureImage(gbuffer->clusters, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, w * h * 8, ids);
    *seen = 0;
    *kinds = 0;
    for (int i = 0; i < w * h; ++i) {
        if (!(depth[i] > 0.0f))
            continue;
        ++*seen;
        float x[3], ng_view[3], ng[3] = {0, 0, 0};
        gb_topo_pixel_position(frame, i % w, i / w, depth[i], x);
        oct_decode(normal[4 * i + 2], normal[4 * i + 3], ng_view);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                ng[r] += frame->view_to_world[4 * c + r] * ng_view[c];
        int32_t cpu = gb_topo_surface_cluster(s, voxels, x, ng);
        differ += (cpu < 0 ? GB_NO_CLUSTER : (uint32_t)cpu) != ids[2 * i];
        *kinds |= 1u << (ids[2 * i] < 4 ? ids[2 * i] : 4);
    }
    free(depth);
    free(normal);
    free(ids);
    return differ;
}

static void test_cluster_lookup_gpu(void)
{
    gb_error error;
    gb_context context;
    if (!gpu_context(&context, "cluster lookup"))
        return;
    enum { W = 96, H = 80 };
    gb_scene scene = {0};
    build_cornell_box(&scene, W, H);
    gb_segmentation s;
    int32_t *voxels = quadrant_voxels(&scene, &s);
    cluster_frame f;
    gb_result result = cluster_frame_draw(&f, &scene, &s, voxels, W, H, &error);
    CHECK(result == GB_OK, "GP: G-buffer and cluster pass made");
    if (result == GB_OK) {
        int seen;
        unsigned kinds;
        int differ = compare_cluster_lookup(&f.gbuffer, &s, voxels, &f.frame, &seen, &kinds);
        CHECK(kinds == 0x1f, "GP: fragments in all four clusters, and some in none");
        printf("# GP: %d of %d fragments differ from the CPU lookup\n", differ, seen);
        CHECK(seen > W * H / 2 && differ <= seen / 200,
              "GP: the GPU's visibility cluster of each fragment is the CPU's (but at most "
              "0.5 %, on voxel borders)");
    }
    cluster_frame_destroy(&f);
    free(voxels);
    gb_scene_free(&scene);
    gb_context_destroy(&context);
}

int main(void)
{
    test_vpls_cornell();
    test_vpls_energy();
    test_vpls_sun();
    test_vpls_area_lights();
    test_cones();
    test_two_rooms_assignment();
    test_routes();
    test_vpl_at_the_door();
    test_lookup_off_the_wall();
    test_fitted_gate_cone();
    test_iugc();
    test_la_cpu_equals_gpu();
    test_cluster_lookup_gpu();
    test_gather_clamp();
    return tap_done();
}
