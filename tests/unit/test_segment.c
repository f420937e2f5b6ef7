/* test_segment.c — unit tests of tools/segment and formats/segmentation on
 * hand-built skeletons: each rule of noel-biri-2014 §IV.B (topology,
 * curvature and coverage nodes; visibility clusters with alpha) and §IV.C
 * (visibility gates) on a graph where the answer is known, the cases the
 * paper leaves open (rings, loops, coincident nodes, isolated nodes, equal
 * radii), the invariants on a random graph, the .seg file (same bytes, bad
 * files refused; fitted gates), the gates fitted to the voxels' openings
 * (on a wall with a door; on a real bake, against the faces counted here),
 * the point -> cluster lookup (and its fold over every voxel) and the
 * evaluation against
 * Embree in a box. */
#include "../../tools/segment/coverage_nodes.h"
#include "../../tools/segment/curvature_nodes.h"
#include "../../tools/segment/gate_openings.h"
#include "../../tools/segment/segment.h"
#include "../../tools/thin/thin.h"
#include "../../tools/voxelize/voxelize.h"
#include "container.h"
#include "random.h"
#include "scene_builder.h"
#include "segmentation.h"
#include "scratch.h"
#include "tap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- building skeletons ---- */

typedef struct test_node {
    float x, y, z, radius;
} test_node;

static int compare_edges(const void *a, const void *b)
{
    const uint32_t *p = a, *q = b;
    if (p[0] != q[0])
        return p[0] < q[0] ? -1 : 1;
    return p[1] < q[1] ? -1 : p[1] > q[1];
}

/* A skeleton of the given nodes and edges (any order, either direction). */
static gb_skeleton make_skeleton(uint32_t node_count, const test_node *nodes,
                                 uint32_t edge_count, const uint32_t (*edges)[2])
{
    gb_skeleton s;
    memset(&s, 0, sizeof s);
    s.node_count = node_count;
    s.edge_count = edge_count;
    s.nodes = calloc(node_count + 1, sizeof *s.nodes);
    s.edges = calloc(2 * (size_t)edge_count + 1, sizeof *s.edges);
    for (uint32_t n = 0; n < node_count; ++n) {
        s.nodes[n].position[0] = nodes[n].x;
        s.nodes[n].position[1] = nodes[n].y;
        s.nodes[n].position[2] = nodes[n].z;
        s.nodes[n].radius = nodes[n].radius;
    }
    for (uint32_t e = 0; e < edge_count; ++e) {
        uint32_t a = edges[e][0], b = edges[e][1];
        s.edges[2 * e] = a < b ? a : b;
        s.edges[2 * e + 1] = a < b ? b : a;
    }
    qsort(s.edges, edge_count, 2 * sizeof *s.edges, compare_edges);
    s.voxel_size = 1.0;
    s.grid_size[0] = s.grid_size[1] = s.grid_size[2] = 4;
    s.resolution = 4;
    s.scene_hash = 0x1234;
    return s;
}

/* A path 0-1-...-(count-1). */
static gb_skeleton make_path(uint32_t count, const test_node *nodes)
{
    uint32_t (*edges)[2] = calloc(count, sizeof *edges);
    for (uint32_t i = 0; i + 1 < count; ++i) {
        edges[i][0] = i;
        edges[i][1] = i + 1;
    }
    gb_skeleton s = make_skeleton(count, nodes, count ? count - 1 : 0, edges);
    free(edges);
    return s;
}

static gb_result segment_with(const gb_skeleton *s, double alpha, gb_segmentation *out,
                              gb_segment_stats *stats)
{
    gb_segment_options options = {alpha == 0.0 ? -1.0 : alpha};
    gb_error error;
    gb_result result = gb_segment(s, &options, out, stats, &error);
    if (result)
        printf("# gb_segment: %s\n", error.message);
    return result;
}

/* The class of skeleton node k in the segmentation (0 when removed). */
static uint32_t class_of(const gb_segmentation *seg, uint32_t k)
{
    uint32_t n = seg->node_map[k];
    return seg->nodes[n].skeleton_node == k ? seg->nodes[n].node_class : 0;
}

static uint32_t cluster_of(const gb_segmentation *seg, uint32_t k)
{
    return seg->cluster[seg->node_map[k]];
}

static uint32_t count_class(const gb_segmentation *seg, uint32_t node_class)
{
    uint32_t count = 0;
    for (uint32_t n = 0; n < seg->node_count; ++n)
        count += seg->nodes[n].node_class == node_class;
    return count;
}

/* Whether segmented nodes a and b (skeleton indices) share an edge. */
static int has_edge(const gb_segmentation *seg, uint32_t ka, uint32_t kb)
{
    uint32_t a = seg->node_map[ka], b = seg->node_map[kb];
    for (uint32_t e = 0; e < seg->edge_count; ++e)
        if ((seg->edges[2 * e] == a && seg->edges[2 * e + 1] == b) ||
            (seg->edges[2 * e] == b && seg->edges[2 * e + 1] == a))
            return 1;
    return 0;
}

/* ---- the measures ---- */

static void test_measures(void)
{
    const test_node nodes[] = {
        {0, 0, 0, 1}, {2, 0, 0, 1}, {0, 1, 0, 0.5f}, {3, 0, 0, 0.5f}, {1, 0, 0, 0}, {1, 1, 0, 0},
    };
    const uint32_t edges[][2] = {{0, 1}};
    gb_skeleton s = make_skeleton(6, nodes, 1, edges);
    CHECK_NEAR(gb_curv(&s, 2, 0, 1), 2.0, 1e-12, "curv: distance 1 to L1Lk over maxball 0.5");
    CHECK_NEAR(gb_curv(&s, 3, 0, 1), 2.0, 1e-12,
               "curv: beyond Lk, the distance is to the segment, not the infinite line");
    CHECK_NEAR(gb_curv(&s, 2, 0, 0), 2.0, 1e-12, "curv: L1 = Lk measures to the point");
    CHECK_NEAR(gb_curv(&s, 4, 0, 1), 0.0, 0.0, "curv: on the line with maxball 0 is 0");
    CHECK(isinf(gb_curv(&s, 5, 0, 1)), "curv: off the line with maxball 0 is infinite");
    CHECK_NEAR(gb_coverage(&s, 3, 0, 1), 1.0, 1e-12,
               "coverage: min over the extrema of distance / maxball (3/1, 1/1)");
    CHECK_NEAR(gb_coverage(&s, 2, 0, 1), 1.0, 1e-12, "coverage: on the sphere of L1 is 1");
    gb_skeleton_free(&s);
}

/* ---- §IV.B.1 rules ---- */

/* An L: 0..10 along x, then 10..20 along y; maxball 6. The corner is 7.07
 * from L1Lk (curv 1.18) and is the only node to split; both legs are then
 * straight and covered by the balls of 6 at their ends. */
static void test_bent_line(void)
{
    test_node nodes[21];
    for (int i = 0; i <= 20; ++i)
        nodes[i] = (test_node){i <= 10 ? (float)i : 10.0f, i <= 10 ? 0.0f : (float)(i - 10), 0,
                               6};
    gb_skeleton s = make_path(21, nodes);
    gb_segmentation seg;
    gb_segment_stats stats;
    if (!CHECK(segment_with(&s, 20, &seg, &stats) == GB_OK, "bent line: segments"))
        return;
    CHECK_EQ_INT(class_of(&seg, 10), GB_NODE_CURVATURE, "bent line: the corner is a curvature node");
    CHECK_EQ_INT(stats.curvature_nodes, 1, "bent line: one curvature node");
    CHECK_EQ_INT(stats.coverage_nodes, 0, "bent line: no coverage node");
    CHECK_EQ_INT(class_of(&seg, 0), GB_NODE_TOPOLOGY, "bent line: the ends are topology nodes");
    CHECK_EQ_INT(seg.node_count, 3, "bent line: 3 segmented nodes");
    CHECK_EQ_INT(seg.edge_count, 2, "bent line: 2 segmented edges");
    CHECK(has_edge(&seg, 0, 10) && has_edge(&seg, 10, 20), "bent line: end - corner - end");
    CHECK(seg.node_map[4] == seg.node_map[0] && seg.node_map[6] == seg.node_map[10] &&
              seg.node_map[14] == seg.node_map[10] && seg.node_map[16] == seg.node_map[20],
          "bent line: nodes map to the nearer extremum of their line");
    CHECK_EQ_INT(seg.node_map[5], seg.node_map[0],
                 "bent line: a node halfway maps to the extremum of smaller index");
    /* clusters: the corner is a curvature node, so the first end does not
     * take it; the corner then takes the other end (same maxball) */
    CHECK_EQ_INT(seg.cluster_count, 2, "bent line: 2 visibility clusters, even at alpha 20");
    CHECK(cluster_of(&seg, 10) == cluster_of(&seg, 20) && cluster_of(&seg, 0) != cluster_of(&seg, 10),
          "bent line: the corner joins the later end, not the first");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* A straight line 0..10 with maxball 5 - 0.45 x: the balls of the extrema
 * (5 and 0.5) leave 6..9 uncovered. coverage = min(x / 5, (10 - x) / 0.5)
 * peaks at node 9 (1.8); then on 0..9 (r9 = 0.95) at node 7 (1.4); then
 * 0..7 (r7 = 1.85) has no node above 1 (node 5: exactly 1, on the sphere). */
static void test_shrinking_balls(void)
{
    test_node nodes[11];
    for (int i = 0; i <= 10; ++i)
        nodes[i] = (test_node){(float)i, 0, 0, 5.0f - 0.45f * (float)i};
    gb_skeleton s = make_path(11, nodes);
    gb_segmentation seg;
    gb_segment_stats stats;
    if (!CHECK(segment_with(&s, 20, &seg, &stats) == GB_OK, "shrinking balls: segments"))
        return;
    CHECK_EQ_INT(stats.curvature_nodes, 0, "shrinking balls: a straight line has no curvature node");
    CHECK_EQ_INT(stats.coverage_nodes, 2, "shrinking balls: two coverage nodes");
    CHECK(class_of(&seg, 9) == GB_NODE_COVERAGE && class_of(&seg, 7) == GB_NODE_COVERAGE,
          "shrinking balls: nodes 9 and 7 are coverage nodes");
    CHECK_EQ_INT(class_of(&seg, 5), 0, "shrinking balls: node 5, on the sphere of L1, is covered");
    CHECK_EQ_INT(seg.edge_count, 3, "shrinking balls: 0-7, 7-9, 9-10");
    CHECK(has_edge(&seg, 0, 7) && has_edge(&seg, 7, 9) && has_edge(&seg, 9, 10),
          "shrinking balls: the edges follow the line");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* A T: node 0 at the origin, three straight arms of 5 nodes (maxball 3). */
static void test_t_junction(void)
{
    test_node nodes[16];
    uint32_t edges[15][2];
    nodes[0] = (test_node){0, 0, 0, 3};
    const float dir[3][2] = {{1, 0}, {-1, 0}, {0, 1}};
    uint32_t e = 0;
    for (int arm = 0; arm < 3; ++arm)
        for (int i = 1; i <= 5; ++i) {
            uint32_t n = (uint32_t)(1 + 5 * arm + i - 1);
            nodes[n] = (test_node){dir[arm][0] * (float)i, dir[arm][1] * (float)i, 0, 3};
            edges[e][0] = i == 1 ? 0 : n - 1;
            edges[e++][1] = n;
        }
    gb_skeleton s = make_skeleton(16, nodes, 15, (const uint32_t(*)[2])edges);
    gb_segmentation seg;
    gb_segment_stats stats;
    if (!CHECK(segment_with(&s, 20, &seg, &stats) == GB_OK, "T junction: segments"))
        return;
    CHECK_EQ_INT(stats.topology_nodes, 4, "T junction: the junction and three ends");
    CHECK_EQ_INT(stats.lines, 3, "T junction: three lines");
    CHECK_EQ_INT(class_of(&seg, 0), GB_NODE_TOPOLOGY, "T junction: node 0 is a topology node");
    uint32_t degree = 0;
    for (uint32_t i = 0; i < seg.edge_count; ++i)
        degree += seg.edges[2 * i] == seg.node_map[0] || seg.edges[2 * i + 1] == seg.node_map[0];
    CHECK_EQ_INT(degree, 3, "T junction: degree 3 in the segmented skeleton");
    CHECK_EQ_INT(seg.node_count, 4, "T junction: 4 segmented nodes");
    CHECK_EQ_INT(seg.cluster_count, 1, "T junction: equal balls make one cluster");
    CHECK_EQ_INT(seg.gate_count, 0, "T junction: no gate inside a cluster");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* ---- §IV.B.2 clusters and §IV.C gates ---- */

/* A path of 6 nodes 10 apart with maxballs below 5: every interior node is
 * uncovered, so the segmented skeleton is the whole path, and no ball holds
 * a neighbour. */
static gb_skeleton spaced_path(const float radii[6])
{
    test_node nodes[6];
    for (int i = 0; i < 6; ++i)
        nodes[i] = (test_node){10.0f * (float)i, 0, 0, radii[i]};
    return make_path(6, nodes);
}

static void test_alpha_extremes(void)
{
    const float radii[6] = {4, 4, 3.5f, 3.3f, 2, 4};
    gb_skeleton s = spaced_path(radii);
    gb_segmentation seg;
    if (!CHECK(segment_with(&s, 0, &seg, NULL) == GB_OK, "alpha 0: segments"))
        return;
    CHECK_EQ_INT(seg.node_count, 6, "spaced path: every node is kept");
    CHECK_EQ_INT(seg.cluster_count, 5, "alpha 0: only the two equal neighbours share a cluster");
    CHECK(cluster_of(&seg, 0) == cluster_of(&seg, 1), "alpha 0: maxball 4 and 4 join");
    CHECK_EQ_INT(seg.gate_count, 4, "alpha 0: a gate between every two clusters");
    gb_segmentation_free(&seg);

    segment_with(&s, 20, &seg, NULL);
    CHECK_EQ_INT(seg.cluster_count, 3, "alpha 20: {4, 4, 3.5, 3.3}, {2}, {4}");
    CHECK(cluster_of(&seg, 3) == cluster_of(&seg, 0) && cluster_of(&seg, 4) != cluster_of(&seg, 3),
          "alpha 20: within 0.8 of the largest maxball 4");
    gb_segmentation_free(&seg);

    segment_with(&s, 100, &seg, NULL);
    CHECK_EQ_INT(seg.cluster_count, 1, "alpha 100: one cluster");
    CHECK_EQ_INT(seg.gate_count, 0, "alpha 100: no gate");
    CHECK_NEAR(seg.alpha, 100.0, 0.0, "alpha is recorded");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* A cluster of more nodes than a byte counts (the reader once miscounted). */
static void test_big_cluster(void)
{
    enum { COUNT = 600 };
    test_node nodes[COUNT];
    for (int i = 0; i < COUNT; ++i)
        nodes[i] = (test_node){10.0f * (float)i, 0, 0, 4};
    gb_skeleton s = make_path(COUNT, nodes);
    gb_segmentation seg;
    if (CHECK(segment_with(&s, 100, &seg, NULL) == GB_OK, "big cluster: segments")) {
        CHECK(seg.node_count == COUNT && seg.cluster_count == 1,
              "big cluster: 600 nodes in one cluster, valid");
        gb_segmentation_free(&seg);
    }
    gb_skeleton_free(&s);
}

/* The maximal-ball rule: a node inside the ball of another joins its
 * cluster whatever its maxball, if reachable inside the ball. */
static void test_ball_rule(void)
{
    /* 0 (maxball 25) - 1 (2) - 2 (2) - 3 (24), 10 apart, with a leaf of
     * maxball 1 on 1 and on 2 (so that every node is a topology node): 1, 2
     * and the leaves are inside the ball of 0 (10 to 20.2 away), 3 is not
     * (30) and differs from 25 (alpha 0). */
    const test_node nodes[6] = {{0, 0, 0, 25}, {10, 0, 0, 2},  {20, 0, 0, 2},
                                {30, 0, 0, 24}, {10, 3, 0, 1}, {20, 3, 0, 1}};
    const uint32_t edges[][2] = {{0, 1}, {1, 2}, {2, 3}, {1, 4}, {2, 5}};
    gb_skeleton s = make_skeleton(6, nodes, 5, edges);
    gb_segmentation seg;
    if (!CHECK(segment_with(&s, 0, &seg, NULL) == GB_OK, "ball rule: segments"))
        return;
    CHECK_EQ_INT(seg.node_count, 6, "ball rule: junctions and leaves are topology nodes");
    CHECK(cluster_of(&seg, 1) == cluster_of(&seg, 0) && cluster_of(&seg, 2) == cluster_of(&seg, 0) &&
              cluster_of(&seg, 4) == cluster_of(&seg, 0),
          "ball rule: nodes inside the ball of node 0 join it at alpha 0");
    CHECK(cluster_of(&seg, 3) != cluster_of(&seg, 0),
          "ball rule: node 3, outside the ball, does not");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* Maxballs 5, 1, 5 at x = 0, 10, 20 (y, z tilted): three clusters and two
 * gates at the middles of the edges, along them, radius 1. */
static void test_gates(void)
{
    const test_node nodes[3] = {{0, 0, 0, 5}, {8, 6, 0, 1}, {8, 6, 10, 5}};
    gb_skeleton s = make_path(3, nodes);
    gb_segmentation seg;
    if (!CHECK(segment_with(&s, 20, &seg, NULL) == GB_OK, "gates: segments"))
        return;
    CHECK_EQ_INT(class_of(&seg, 1), GB_NODE_CURVATURE, "gates: node 1 is a curvature node");
    CHECK_EQ_INT(seg.cluster_count, 3, "gates: three clusters");
    CHECK(cluster_of(&seg, 0) == 0 && cluster_of(&seg, 2) == 1 && cluster_of(&seg, 1) == 2,
          "gates: clusters numbered by maxball, then index");
    CHECK_EQ_INT(seg.gate_count, 2, "gates: two gates");
    if (seg.gate_count != 2) {
        gb_segmentation_free(&seg);
        return;
    }
    const gb_visibility_gate *g = seg.gates;
    CHECK(g[0].centre[0] == 4.0f && g[0].centre[1] == 3.0f && g[0].centre[2] == 0.0f,
          "gates: the first at the middle of edge 0-1");
    CHECK_NEAR(g[0].normal[0], 0.8, 1e-6, "gates: normal along the edge (x)");
    CHECK_NEAR(g[0].normal[1], 0.6, 1e-6, "gates: normal along the edge (y)");
    CHECK_NEAR(g[0].normal[2], 0.0, 1e-6, "gates: normal along the edge (z)");
    CHECK_NEAR(g[0].radius, 1.0, 0.0, "gates: radius min(5, 1)");
    CHECK(g[0].clusters[0] == 0 && g[0].clusters[1] == 2 && g[0].edge == 0,
          "gates: the first joins clusters 0 and 2 on edge 0");
    CHECK(g[1].centre[0] == 8.0f && g[1].centre[1] == 6.0f && g[1].centre[2] == 5.0f &&
              g[1].normal[2] == 1.0f && g[1].radius == 1.0f,
          "gates: the second at (8, 6, 5), normal z, radius 1");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* ---- invariants on a random graph ---- */

/* A random connected graph on a 8 x 8 x 2 lattice (spacing 2): a spanning
 * tree plus extra edges, random maxballs in [0.3, 3]. */
static gb_skeleton random_graph(uint64_t seed)
{
    enum { NX = 8, NY = 8, NZ = 2, N = NX * NY * NZ };
    test_node nodes[N];
    uint32_t edges[3 * N][2], count = 0;
    gb_random rng = gb_random_make(seed, 0);
    for (uint32_t n = 0; n < N; ++n)
        nodes[n] = (test_node){2.0f * (float)(n % NX), 2.0f * (float)(n / NX % NY),
                               2.0f * (float)(n / (NX * NY)), 0.3f + 2.7f * gb_random_float(&rng)};
    for (uint32_t n = 1; n < N; ++n) {
        /* a tree: each node to an earlier lattice neighbour */
        uint32_t x = n % NX, y = n / NX % NY;
        uint32_t parent = x ? n - 1 : y ? n - NX : n - NX * NY;
        edges[count][0] = parent;
        edges[count++][1] = n;
    }
    for (uint32_t n = 0; n < N; ++n) {
        uint32_t y = n / NX % NY;
        if (n % NX && y + 1 < NY && gb_random_float(&rng) < 0.2f) {
            edges[count][0] = n;
            edges[count++][1] = n + NX;
        }
    }
    return make_skeleton(N, nodes, count, (const uint32_t(*)[2])edges);
}

/* Every cluster is connected in the segmented skeleton. */
static int clusters_connected(const gb_segmentation *seg)
{
    uint32_t count = seg->node_count;
    uint32_t *parent = malloc((count + 1) * sizeof *parent);
    for (uint32_t n = 0; n < count; ++n)
        parent[n] = n;
    for (uint32_t e = 0; e < seg->edge_count; ++e) {
        uint32_t a = seg->edges[2 * e], b = seg->edges[2 * e + 1];
        if (seg->cluster[a] != seg->cluster[b])
            continue;
        while (parent[a] != a)
            a = parent[a];
        while (parent[b] != b)
            b = parent[b];
        parent[a] = b;
    }
    uint32_t components = 0;
    for (uint32_t n = 0; n < count; ++n)
        components += parent[n] == n;
    free(parent);
    return components == seg->cluster_count;
}

/* Gates at the middle of their edge, normal along it, radius the min. */
static int gates_on_edges(const gb_segmentation *seg)
{
    for (uint32_t g = 0; g < seg->gate_count; ++g) {
        const gb_visibility_gate *gate = &seg->gates[g];
        const gb_segmented_node *a = &seg->nodes[seg->edges[2 * gate->edge]];
        const gb_segmented_node *b = &seg->nodes[seg->edges[2 * gate->edge + 1]];
        double d[3], length = 0.0, dot = 0.0;
        for (int i = 0; i < 3; ++i) {
            d[i] = (double)b->position[i] - a->position[i];
            length += d[i] * d[i];
            if (fabs(gate->centre[i] - 0.5 * (a->position[i] + b->position[i])) > 1e-5)
                return 0;
        }
        length = sqrt(length);
        for (int i = 0; i < 3; ++i)
            dot += gate->normal[i] * d[i] / length;
        if (fabs(dot - 1.0) > 1e-6 || gate->radius != fminf(a->radius, b->radius) ||
            gate->clusters[0] == gate->clusters[1])
            return 0;
    }
    return 1;
}

/* Each segmented node maps to itself; every other node maps to a classified
 * node; the classes are the ones kept. */
static int map_consistent(const gb_segmentation *seg)
{
    for (uint32_t n = 0; n < seg->node_count; ++n)
        if (seg->node_map[seg->nodes[n].skeleton_node] != n ||
            seg->nodes[n].node_class == GB_NODE_UNCLASSIFIED)
            return 0;
    for (uint32_t k = 0; k < seg->skeleton_node_count; ++k)
        if (seg->node_map[k] >= seg->node_count)
            return 0;
    return 1;
}

static void test_invariants(void)
{
    const double alphas[4] = {0, 20, 50, 100};
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        gb_skeleton s = random_graph(seed);
        for (int a = 0; a < 4; ++a) {
            gb_segmentation seg;
            char what[128];
            snprintf(what, sizeof what, "random graph %d, alpha %g: segments", (int)seed,
                     alphas[a]);
            if (!CHECK(segment_with(&s, alphas[a], &seg, NULL) == GB_OK, what))
                continue;
            snprintf(what, sizeof what, "random graph %d, alpha %g: clusters connected",
                     (int)seed, alphas[a]);
            CHECK(clusters_connected(&seg), what);
            snprintf(what, sizeof what, "random graph %d, alpha %g: gates on their edges",
                     (int)seed, alphas[a]);
            CHECK(gates_on_edges(&seg), what);
            snprintf(what, sizeof what, "random graph %d, alpha %g: node map", (int)seed,
                     alphas[a]);
            CHECK(map_consistent(&seg), what);
            gb_error error;
            snprintf(what, sizeof what, "random graph %d, alpha %g: valid (one cluster per "
                     "node, every cluster used)", (int)seed, alphas[a]);
            CHECK(gb_segmentation_validate(&seg, "random", &error) == GB_OK, what);
            gb_segmentation_free(&seg);
        }
        gb_skeleton_free(&s);
    }
}

/* ---- open cases ---- */

/* Eight nodes on a circle of radius 10 (45 degrees apart), maxball 8 and
 * 8.5 for node 3: the anchor is node 3; the loop opens at the opposite
 * node 7 (curv 20 / 8); the halves split at 5 and 1 (curv 10 / 8). */
static void test_ring(void)
{
    test_node nodes[8];
    uint32_t edges[8][2];
    for (int i = 0; i < 8; ++i) {
        double angle = i * M_PI / 4.0;
        nodes[i] = (test_node){(float)(10.0 * cos(angle)), (float)(10.0 * sin(angle)), 0,
                               i == 3 ? 8.5f : 8.0f};
        edges[i][0] = (uint32_t)i;
        edges[i][1] = (uint32_t)(i + 1) % 8;
    }
    gb_skeleton s = make_skeleton(8, nodes, 8, (const uint32_t(*)[2])edges);
    gb_segmentation seg;
    gb_segment_stats stats;
    if (!CHECK(segment_with(&s, 20, &seg, &stats) == GB_OK, "ring: segments"))
        return;
    CHECK_EQ_INT(stats.rings, 1, "ring: one ring anchored");
    CHECK_EQ_INT(class_of(&seg, 3), GB_NODE_TOPOLOGY, "ring: the largest maxball is the anchor");
    CHECK_EQ_INT(stats.loops, 1, "ring: its loop is opened");
    CHECK_EQ_INT(class_of(&seg, 7), GB_NODE_CURVATURE, "ring: at the opposite node");
    CHECK(class_of(&seg, 1) == GB_NODE_CURVATURE && class_of(&seg, 5) == GB_NODE_CURVATURE,
          "ring: the halves split at curv 1.25");
    CHECK_EQ_INT(count_class(&seg, GB_NODE_CURVATURE), 3, "ring: 3 curvature nodes");
    CHECK_EQ_INT(seg.node_count, 4, "ring: 4 segmented nodes");
    CHECK_EQ_INT(seg.edge_count, 4, "ring: the cycle is kept (4 edges)");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);

    /* two nodes alone in a cycle cannot exist (no multi-edges); three with
     * big balls: the loop is opened by a topology node, the two lines between
     * the same pair become one edge */
    const test_node small[3] = {{0, 0, 0, 5}, {1, 0, 0, 5}, {0, 1, 0, 5}};
    const uint32_t triangle[3][2] = {{0, 1}, {1, 2}, {0, 2}};
    s = make_skeleton(3, small, 3, triangle);
    if (!CHECK(segment_with(&s, 20, &seg, &stats) == GB_OK, "small ring: segments"))
        return;
    CHECK_EQ_INT(class_of(&seg, 0), GB_NODE_TOPOLOGY, "small ring: equal radii, anchor node 0");
    CHECK_EQ_INT(class_of(&seg, 1), GB_NODE_TOPOLOGY,
                 "small ring: curv <= 1, opened by a topology node (tie: smaller index)");
    CHECK_EQ_INT(seg.edge_count, 1, "small ring: one edge, no loop edge");
    CHECK_EQ_INT(seg.cluster_count, 1, "small ring: one cluster");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* A lollipop: a stick 0 - 1 - 2 (x < 0) and a loop 2 - 3 - 4 - 5 - 2 whose
 * two extremities are the junction 2. */
static void test_loop_line(float radius, int expect_curvature)
{
    const test_node nodes[6] = {{-10, 0, 0, radius}, {-5, 0, 0, radius}, {0, 0, 0, radius},
                                {5, -5, 0, radius},  {10, 0, 0, radius}, {5, 5, 0, radius}};
    const uint32_t edges[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {2, 5}};
    gb_skeleton s = make_skeleton(6, nodes, 6, edges);
    gb_segmentation seg;
    gb_segment_stats stats;
    if (!CHECK(segment_with(&s, 20, &seg, &stats) == GB_OK, "loop line: segments"))
        return;
    CHECK_EQ_INT(stats.loops, 1, "loop line: one line from the junction back to itself");
    CHECK_EQ_INT(class_of(&seg, 4), expect_curvature ? GB_NODE_CURVATURE : GB_NODE_TOPOLOGY,
                 expect_curvature ? "loop line: opened at the farthest node, curv 10/3 > 1"
                                  : "loop line: opened at the farthest node, a topology node");
    int self_edge = 0;
    for (uint32_t e = 0; e < seg.edge_count; ++e)
        self_edge |= seg.edges[2 * e] == seg.edges[2 * e + 1];
    CHECK(!self_edge, "loop line: no edge from a node to itself");
    CHECK(has_edge(&seg, 2, 4) || (has_edge(&seg, 2, 3) && has_edge(&seg, 3, 4)),
          "loop line: the junction reaches the opener");
    if (expect_curvature)
        CHECK(class_of(&seg, 3) == GB_NODE_CURVATURE && class_of(&seg, 5) == GB_NODE_CURVATURE,
              "loop line: the halves split (curv 5/3)");
    else
        CHECK_EQ_INT(seg.edge_count, 2, "loop line: stick edge and one edge to the opener");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* Coincident nodes: two junctions at the same point joined by an edge of
 * length 0, each with two leaves; and a line whose extremities coincide. */
static void test_coincident_nodes(void)
{
    const test_node nodes[6] = {{0, 0, 0, 1}, {0, 0, 0, 3}, {-5, 0, 0, 0.5f},
                                {-5, 5, 0, 0.5f}, {5, 0, 0, 0.5f}, {5, 5, 0, 0.5f}};
    const uint32_t edges[][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 4}, {1, 5}};
    gb_skeleton s = make_skeleton(6, nodes, 5, edges);
    gb_segmentation seg;
    if (!CHECK(segment_with(&s, 0, &seg, NULL) == GB_OK, "zero-length edge: segments"))
        return;
    CHECK(has_edge(&seg, 0, 1), "zero-length edge: kept in the segmented skeleton");
    CHECK(cluster_of(&seg, 0) == cluster_of(&seg, 1),
          "zero-length edge: coincident nodes share a cluster even at alpha 0");
    int gate_on_it = 0;
    for (uint32_t g = 0; g < seg.gate_count; ++g) {
        uint32_t e = seg.gates[g].edge;
        gate_on_it |= seg.nodes[seg.edges[2 * e]].skeleton_node == 0 &&
                      seg.nodes[seg.edges[2 * e + 1]].skeleton_node == 1;
    }
    CHECK(!gate_on_it, "zero-length edge: no gate on it");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);

    /* 0 - 1 - 2 - 3 - 4 with 0 and 4 at the same point, 1 and 2 coincident */
    const test_node path[5] = {{0, 0, 0, 1}, {3, 4, 0, 1}, {3, 4, 0, 1}, {1, 1, 0, 1},
                               {0, 0, 0, 1}};
    s = make_path(5, path);
    if (!CHECK(segment_with(&s, 20, &seg, NULL) == GB_OK, "coincident extrema: segments"))
        return;
    CHECK_EQ_INT(class_of(&seg, 1), GB_NODE_CURVATURE,
                 "coincident extrema: distance to the point, curv 5 (tie to the smaller index)");
    CHECK_EQ_INT(class_of(&seg, 2), 0, "coincident extrema: its twin is then on the line");
    CHECK_EQ_INT(seg.node_map[2], seg.node_map[1], "coincident extrema: and maps to it");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

static void test_isolated_nodes(void)
{
    const test_node nodes[4] = {{0, 0, 0, 1}, {10, 0, 0, 1}, {20, 0, 0, 1}, {21, 0, 0, 1}};
    const uint32_t edges[][2] = {{2, 3}};
    gb_skeleton s = make_skeleton(4, nodes, 1, edges);
    gb_segmentation seg;
    if (!CHECK(segment_with(&s, 20, &seg, NULL) == GB_OK, "isolated nodes: segment"))
        return;
    CHECK(class_of(&seg, 0) == GB_NODE_TOPOLOGY && class_of(&seg, 1) == GB_NODE_TOPOLOGY,
          "isolated nodes: degree 0 is a topology node");
    CHECK(cluster_of(&seg, 0) == 0 && cluster_of(&seg, 1) == 1 && cluster_of(&seg, 2) == 2,
          "isolated nodes: a cluster each, numbered by index at equal maxball");
    CHECK_EQ_INT(seg.cluster_count, 3, "isolated nodes: 3 clusters (2-3 together)");
    CHECK_EQ_INT(seg.edge_count, 1, "isolated nodes: one edge");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);

    gb_skeleton empty = make_skeleton(0, NULL, 0, NULL);
    if (CHECK(segment_with(&empty, 20, &seg, NULL) == GB_OK, "empty skeleton: segments")) {
        CHECK(seg.node_count == 0 && seg.cluster_count == 0 && seg.gate_count == 0,
              "empty skeleton: nothing");
        gb_segmentation_free(&seg);
    }
    gb_skeleton_free(&empty);
}

/* Equal values are ordered by node index, whatever the walk direction. */
static void test_equal_radii(void)
{
    /* a trapezoid 0 (0,0) - (3,4) - (7,4) - 3 (10,0), maxball 2.5: both top
     * nodes have curv 4 / 2.5; the one of smaller index splits, the other
     * then has curv 0.79 and becomes a coverage node. Numbered both ways. */
    const test_node a[4] = {{0, 0, 0, 2.5f}, {3, 4, 0, 2.5f}, {7, 4, 0, 2.5f}, {10, 0, 0, 2.5f}};
    const test_node b[4] = {{0, 0, 0, 2.5f}, {7, 4, 0, 2.5f}, {3, 4, 0, 2.5f}, {10, 0, 0, 2.5f}};
    const uint32_t edges_a[][2] = {{0, 1}, {1, 2}, {2, 3}};
    const uint32_t edges_b[][2] = {{0, 2}, {2, 1}, {1, 3}};
    gb_skeleton sa = make_skeleton(4, a, 3, edges_a), sb = make_skeleton(4, b, 3, edges_b);
    gb_segmentation seg_a, seg_b;
    if (!CHECK(segment_with(&sa, 20, &seg_a, NULL) == GB_OK &&
                   segment_with(&sb, 20, &seg_b, NULL) == GB_OK,
               "equal curv: segments"))
        return;
    CHECK(class_of(&seg_a, 1) == GB_NODE_CURVATURE && class_of(&seg_a, 2) == GB_NODE_COVERAGE,
          "equal curv: node 1 at (3,4) splits first");
    CHECK(class_of(&seg_b, 1) == GB_NODE_CURVATURE && class_of(&seg_b, 2) == GB_NODE_COVERAGE,
          "equal curv: numbered the other way, node 1 at (7,4) splits first");
    gb_segmentation_free(&seg_a);
    gb_segmentation_free(&seg_b);
    gb_skeleton_free(&sa);
    gb_skeleton_free(&sb);

    /* maxballs 2, 1, 2 on a spaced path: the first 2 seeds cluster 0 */
    const float radii[6] = {2, 1, 2, 1, 2, 1};
    gb_skeleton s = spaced_path(radii);
    gb_segmentation seg;
    segment_with(&s, 20, &seg, NULL);
    CHECK(cluster_of(&seg, 0) == 0 && cluster_of(&seg, 2) == 1 && cluster_of(&seg, 4) == 2 &&
              cluster_of(&seg, 1) == 3 && cluster_of(&seg, 3) == 4 && cluster_of(&seg, 5) == 5,
          "equal maxballs: clusters seeded in index order");
    gb_segmentation_free(&seg);
    gb_skeleton_free(&s);
}

/* ---- the .seg file ---- */

static int segmentations_equal(const gb_segmentation *a, const gb_segmentation *b)
{
    return a->skeleton_node_count == b->skeleton_node_count && a->node_count == b->node_count &&
           a->edge_count == b->edge_count && a->cluster_count == b->cluster_count &&
           a->gate_count == b->gate_count && a->alpha == b->alpha &&
           a->scene_hash == b->scene_hash && a->voxel_size == b->voxel_size &&
           a->gates_fitted == b->gates_fitted &&
           !memcmp(a->grid_size, b->grid_size, sizeof a->grid_size) &&
           !memcmp(a->nodes, b->nodes, a->node_count * sizeof *a->nodes) &&
           !memcmp(a->edges, b->edges, 2 * a->edge_count * sizeof *a->edges) &&
           !memcmp(a->cluster, b->cluster, a->node_count * sizeof *a->cluster) &&
           !memcmp(a->node_map, b->node_map, a->skeleton_node_count * sizeof *a->node_map) &&
           !memcmp(a->gates, b->gates, a->gate_count * sizeof *a->gates);
}

/* Rewrites a valid file as format version, with one section's bytes changed
 * by edit (the container checksums then match: only the .seg checks can
 * refuse it). */
static gb_result parse_rewritten(const unsigned char *bytes, size_t size, uint32_t version,
                                 const char *section, void (*edit)(uint8_t *data, uint64_t size),
                                 const char *path, gb_error *error)
{
    gb_container c;
    gb_container_parse(bytes, size, "valid", "SEGM", &c, NULL);
    gb_container_writer *w = gb_container_writer_create("SEGM", version);
    uint8_t *copies[8] = {0};
    for (uint32_t i = 0; i < c.section_count; ++i) {
        copies[i] = malloc(c.sections[i].size + 1);
        memcpy(copies[i], c.sections[i].data, c.sections[i].size);
        if (edit && !strcmp(c.sections[i].name, section))
            edit(copies[i], c.sections[i].size);
        gb_container_add(w, c.sections[i].name, copies[i], c.sections[i].size, NULL);
    }
    gb_container_commit(w, path, NULL);
    gb_container_writer_destroy(w);
    for (uint32_t i = 0; i < c.section_count; ++i)
        free(copies[i]);
    gb_container_close(&c);
    gb_segmentation seg;
    gb_result result = gb_segmentation_read(path, &seg, error);
    gb_segmentation_free(&seg);
    return result;
}

static void cluster_out_of_range(uint8_t *d, uint64_t size) { (void)size; d[0] = 0xff; }
static void map_out_of_range(uint8_t *d, uint64_t size) { d[size - 1] = 0x7f; }
static void node_radius_nan(uint8_t *d, uint64_t size)
{
    (void)size;
    memset(d + 20, 0xff, 4);
}
static void gate_normal_long(uint8_t *d, uint64_t size)
{
    (void)size;
    float two = 2.0f;
    memcpy(d + 12, &two, 4);
}
static void gate_other_edge(uint8_t *d, uint64_t size) { (void)size; d[36] ^= 1; }
static void edge_reversed(uint8_t *d, uint64_t size)
{
    (void)size;
    uint8_t t[4];
    memcpy(t, d, 4);
    memcpy(d, d + 4, 4);
    memcpy(d + 4, t, 4);
}
static void node_class_bad(uint8_t *d, uint64_t size) { (void)size; d[4] = 7; }
static void alpha_too_big(uint8_t *d, uint64_t size)
{
    (void)size;
    double alpha = 101.0;
    memcpy(d + 24, &alpha, 8);
}
static void gates_fitted_two(uint8_t *d, uint64_t size) { (void)size; d[84] = 2; }

static void test_file(void)
{
    gb_skeleton s = random_graph(7);
    gb_segmentation seg, again, back;
    gb_error error;
    segment_with(&s, 20, &seg, NULL);
    segment_with(&s, 20, &again, NULL);
    scratch_create("segment");
    const char *p1 = scratch_path("a.seg"), *p2 = scratch_path("b.seg"),
               *p3 = scratch_path("c.seg");
    CHECK(gb_segmentation_write(p1, &seg, &error) == GB_OK &&
              gb_segmentation_write(p2, &again, &error) == GB_OK,
          "file: written");
    size_t size1 = 0, size2 = 0;
    unsigned char *b1 = scratch_read(p1, &size1), *b2 = scratch_read(p2, &size2);
    CHECK(b1 && b2 && size1 == size2 && !memcmp(b1, b2, size1),
          "file: the same skeleton gives the same bytes");
    CHECK(gb_segmentation_read(p1, &back, &error) == GB_OK, "file: read back");
    CHECK(segmentations_equal(&seg, &back), "file: read back equal to what was written");
    gb_segmentation_free(&back);

    /* the container catches any changed byte; truncation too */
    int refused = 1;
    for (size_t i = 0; i < size1; i += 7) {
        b1[i] ^= 0x10;
        refused &= gb_segmentation_parse(b1, size1, "x.seg", &back, &error) != GB_OK;
        b1[i] ^= 0x10;
    }
    CHECK(refused, "corrupt: every changed byte (every 7th tried) is refused");
    CHECK(gb_segmentation_parse(b1, size1 - 1, "x.seg", &back, &error) != GB_OK,
          "corrupt: a truncated file is refused");
    CHECK(gb_segmentation_parse(b1, size1, "x.seg", &back, &error) == GB_OK,
          "corrupt: the intact bytes still parse");
    gb_segmentation_free(&back);

    /* files whose checksums match but whose content is wrong */
    struct {
        const char *section;
        void (*edit)(uint8_t *, uint64_t);
        const char *what;
    } edits[] = {
        {"clusters", cluster_out_of_range, "corrupt: a cluster id out of range"},
        {"node_map", map_out_of_range, "corrupt: a node map entry out of range"},
        {"nodes", node_radius_nan, "corrupt: a NaN maxball"},
        {"nodes", node_class_bad, "corrupt: an unknown node class"},
        {"gates", gate_normal_long, "corrupt: a gate normal that is not unit"},
        {"gates", gate_other_edge, "corrupt: a gate on another edge"},
        {"edges", edge_reversed, "corrupt: an edge (b, a)"},
        {"header", alpha_too_big, "corrupt: alpha 101"},
        {"header", gates_fitted_two, "corrupt: gates fitted 2"},
    };
    for (size_t i = 0; i < sizeof edits / sizeof edits[0]; ++i) {
        gb_result result = parse_rewritten(b1, size1, GB_SEGMENTATION_VERSION, edits[i].section,
                                           edits[i].edit, p3, &error);
        CHECK(result == GB_ERROR_INVALID || result == GB_ERROR_FORMAT, edits[i].what);
        if (result)
            printf("#   %s\n", error.message);
    }

    /* version 1, whose gates the runtime refitted at load: bake it again */
    gb_result result = parse_rewritten(b1, size1, 1, "", NULL, p3, &error);
    CHECK(result == GB_ERROR_FORMAT && strstr(error.message, "format version 1") &&
              strstr(error.message, "bake it again"),
          "version 1: refused, 'bake it again'");
    if (result)
        printf("#   %s\n", error.message);

    /* a failed write leaves nothing */
    seg.cluster[0] = seg.cluster_count;
    CHECK(gb_segmentation_write(p3, &seg, &error) == GB_ERROR_INVALID,
          "write: an invalid segmentation is refused");
    seg.cluster[0] = again.cluster[0];

    free(b1);
    free(b2);
    scratch_remove();
    gb_segmentation_free(&seg);
    gb_segmentation_free(&again);
    gb_skeleton_free(&s);
}

/* ---- fitted gates in the file ---- */

/* Three clusters along x in a 4 x 2 x 1 frame of voxels of 0.5 from
 * (-1, 0, 0): nodes 0 and 1 joined by an edge (its gate, the paper's disk),
 * node 2 alone; gates[1] is an opening gate between clusters 1 and 2. */
static gb_segmentation three_clusters(gb_visibility_gate gates[3])
{
    static gb_segmented_node nodes[3] = {{0, GB_NODE_TOPOLOGY, {-0.75f, 0.5f, 0.25f}, 0.25f},
                                         {1, GB_NODE_TOPOLOGY, {-0.25f, 0.5f, 0.25f}, 0.5f},
                                         {2, GB_NODE_TOPOLOGY, {0.75f, 0.5f, 0.25f}, 0.25f}};
    static uint32_t edges[2] = {0, 1}, cluster[3] = {0, 1, 2}, node_map[3] = {0, 1, 2};
    gates[0] = (gb_visibility_gate){{-0.5f, 0.5f, 0.25f}, {1, 0, 0}, 0.25f, {0, 1}, 0};
    gates[1] = (gb_visibility_gate){{0.5f, 0.5f, 0.25f}, {1, 0, 0}, 0.5f, {1, 2},
                                    GB_SEGMENTATION_NO_EDGE};
    gates[2] = gates[1];
    return (gb_segmentation){.skeleton_node_count = 3, .node_count = 3, .edge_count = 1,
                             .cluster_count = 3, .gate_count = 1, .nodes = nodes,
                             .edges = edges, .cluster = cluster, .node_map = node_map,
                             .gates = gates, .alpha = 20, .scene_hash = 42, .voxel_size = 0.5,
                             .world_origin = {-1, 0, 0}, .grid_size = {4, 2, 1},
                             .resolution = 4};
}

static int valid(const gb_segmentation *seg, const char *what)
{
    gb_error error;
    gb_result result = gb_segmentation_validate(seg, "three", &error);
    if (result)
        printf("#   %s: %s\n", what, error.message);
    return result == GB_OK;
}

/* What gb_segmentation_validate takes with gates_fitted and what it still
 * refuses; the fitted file written and read back. */
static void test_fitted_gates(void)
{
    gb_visibility_gate gates[3];
    gb_segmentation seg = three_clusters(gates);
    CHECK(valid(&seg, "paper"), "fitted gates: the paper's gate, not fitted: valid");
    seg.gate_count = 2;
    CHECK(!valid(&seg, "opening, not fitted"), "fitted gates: no opening gate unless fitted");
    seg.gates_fitted = 1;
    CHECK(valid(&seg, "opening"), "fitted gates: the paper's disk and an opening gate: valid");
    gates[0] = (gb_visibility_gate){{-0.5f, 0.75f, 0.25f}, {0.6f, 0.8f, 0}, 0.6f, {0, 1}, 0};
    CHECK(valid(&seg, "fitted disk"), "fitted gates: a disk fitted off the edge: valid");
    seg.gates_fitted = 0;
    seg.gate_count = 1;
    CHECK(!valid(&seg, "fitted disk, not fitted"),
          "fitted gates: a disk off the edge in a file not fitted: refused");
    seg.gates_fitted = 1;
    seg.gate_count = 2;
    gates[0].radius = 0.2f;
    CHECK(!valid(&seg, "small"), "fitted gates: a radius below the paper's min(maxball): refused");
    gates[0].radius = 0.6f;
    gates[0].centre[0] = 2.0f;
    CHECK(!valid(&seg, "outside"), "fitted gates: a centre outside the voxel frame: refused");
    gates[0].centre[0] = -0.5f;
    gates[1].clusters[0] = 2;
    gates[1].clusters[1] = 1;
    CHECK(!valid(&seg, "reversed"), "fitted gates: an opening gate (2, 1): refused");
    gates[1].clusters[0] = 0;
    CHECK(!valid(&seg, "edge's pair"),
          "fitted gates: an opening gate where an edge gate is: refused");
    gates[1] = gates[2];
    gates[1].edge = 0;
    CHECK(!valid(&seg, "on an edge"),
          "fitted gates: a gate on an edge after the edge gates: refused");
    gates[1] = gates[2];
    seg.gate_count = 3;
    CHECK(!valid(&seg, "twice"), "fitted gates: the same opening gate twice: refused");
    seg.gate_count = 2;

    scratch_create("fitted");
    const char *path = scratch_path("fitted.seg");
    gb_segmentation back;
    gb_error error;
    CHECK(gb_segmentation_write(path, &seg, &error) == GB_OK &&
              gb_segmentation_read(path, &back, &error) == GB_OK,
          "fitted gates: written and read back");
    CHECK(segmentations_equal(&seg, &back) && back.gates_fitted == 1,
          "fitted gates: read back as written, gates fitted");
    gb_segmentation_free(&back);
    scratch_remove();
}

/* ---- gates fitted to the openings (gate_openings.h) ---- */

/* Two rooms along x in a 20 x 10 x 10 grid of unit voxels, split by a wall
 * at x = 10 (surface voxels) with a 6 x 6 opening (y, z in 2..8); the
 * segmented skeleton's gate there has the paper's radius, min maxball 0.5.
 * The opening's faces lie at x = 10, their centres y, z in 2.5 .. 7.5: the
 * disk's centre (10, 5, 5), normal +x (cluster 0 to 1), radius sqrt(2 <r^2>)
 * = sqrt(2 (35/12 + 35/12)) = sqrt(35/3). */
static void test_gate_fitted_to_opening(void)
{
    enum { NX = 20, NY = 10, NZ = 10 };
    gb_visibility_gate gate = {{10, 5, 5}, {1, 0, 0}, 0.5f, {0, 1}, 0};
    gb_segmentation s = {.cluster_count = 2, .gate_count = 1, .gates = &gate,
                         .voxel_size = 1.0, .grid_size = {NX, NY, NZ}};
    int32_t *clusters = malloc(NX * NY * NZ * sizeof *clusters);
    uint8_t *surface = calloc(NX * NY * NZ, 1);
    for (int i = 0; i < NX * NY * NZ; ++i) {
        int x = i % NX, y = (i / NX) % NY, z = i / (NX * NY);
        int opening = y >= 2 && y < 8 && z >= 2 && z < 8;
        surface[i] = x == 10 && !opening;
        clusters[i] = x < 10 ? 0 : 1;    /* wall voxels too, as thin's grid gives them */
    }
    gb_error error;
    uint32_t fitted = 0;
    CHECK(gb_gate_openings_fit(&s, clusters, surface, &fitted, &error) == GB_OK && fitted == 1,
          "openings: gate fitted");
    printf("# opening: centre %.2f %.2f %.2f normal %.2f %.2f %.2f radius %.4f\n", gate.centre[0],
           gate.centre[1], gate.centre[2], gate.normal[0], gate.normal[1], gate.normal[2],
           gate.radius);
    CHECK(fabsf(gate.centre[0] - 10) < 1e-5f && fabsf(gate.centre[1] - 5) < 1e-5f &&
              fabsf(gate.centre[2] - 5) < 1e-5f && gate.normal[0] == 1.0f,
          "openings: disk at the opening's centre, facing from cluster 0 to 1");
    CHECK_NEAR(gate.radius, sqrt(35.0 / 3.0), 1e-5,
               "openings: radius sqrt(35/3), the 6 x 6 opening's (the wall's voxels are not in it)");

    /* a third room behind x = 15 that no skeleton edge joins to room 1: its
     * faces fill the whole 10 x 10 section, radius sqrt(2 (99/12 + 99/12)) */
    for (int i = 0; i < NX * NY * NZ; ++i)
        if (i % NX >= 15)
            clusters[i] = 2;
    s.cluster_count = 3;
    s.gates = malloc(sizeof *s.gates);
    s.gates[0] = gate;
    uint32_t added = 0;
    CHECK(gb_gate_openings_add(&s, clusters, surface, &added, &error) == GB_OK &&
              added == 1 && s.gate_count == 2 && s.gates[1].clusters[0] == 1 &&
              s.gates[1].clusters[1] == 2 && s.gates[1].edge == GB_SEGMENTATION_NO_EDGE,
          "openings: clusters 1 and 2 touch without a gate: one is added");
    CHECK(gb_gate_openings_fit(&s, clusters, surface, &fitted, &error) == GB_OK && fitted == 2 &&
              fabsf(s.gates[1].centre[0] - 15) < 1e-5f && s.gates[1].normal[0] == 1.0f &&
              fabsf(s.gates[1].radius - sqrtf(33.0f)) < 1e-4f,
          "openings: ... fitted to the whole x = 15 section, radius sqrt(33)");
    CHECK(gb_gate_openings_add(&s, clusters, surface, &added, &error) == GB_OK && added == 0,
          "openings: added once");
    free(s.gates);
    free(clusters);
    free(surface);
}

/* The faces between empty voxels of clusters a < b of a bake: their count,
 * the sum of their centres and of their normals (oriented from a to b). */
typedef struct face_sums {
    uint32_t a, b;
    double count, centre[3], normal[3];
} face_sums;

static face_sums *faces_of(face_sums *sums, uint32_t *count, uint32_t a, uint32_t b)
{
    for (uint32_t i = 0; i < *count; ++i)
        if (sums[i].a == a && sums[i].b == b)
            return &sums[i];
    sums[*count] = (face_sums){a, b, 0, {0, 0, 0}, {0, 0, 0}};
    return &sums[(*count)++];
}

/* Every face between two clusters, by pair, counted voxel by voxel. */
static uint32_t count_faces(const gb_voxel_grid *g, const int32_t *clusters, face_sums *sums)
{
    uint32_t count = 0;
    for (int32_t k = 0; k < g->size[2]; ++k)
        for (int32_t j = 0; j < g->size[1]; ++j)
            for (int32_t i = 0; i < g->size[0]; ++i)
                for (int axis = 0; axis < 3; ++axis) {
                    int32_t v[3] = {i, j, k}, w[3] = {i, j, k};
                    if (++w[axis] >= g->size[axis])
                        continue;
                    size_t p = gb_voxel_index(g, v[0], v[1], v[2]);
                    size_t q = gb_voxel_index(g, w[0], w[1], w[2]);
                    int32_t cp = clusters[p], cq = clusters[q];
                    if (cp < 0 || cq < 0 || cp == cq || g->surface[p] || g->surface[q])
                        continue;
                    face_sums *f = faces_of(sums, &count, (uint32_t)(cp < cq ? cp : cq),
                                            (uint32_t)(cp < cq ? cq : cp));
                    f->count += 1.0;
                    f->normal[axis] += cp < cq ? 1.0 : -1.0;
                    for (int a = 0; a < 3; ++a)
                        f->centre[a] += g->world_origin[a] +
                                        (v[a] + 0.5 + (a == axis ? 0.5 : 0.0)) * g->voxel_size;
                }
    return count;
}

/* The gates joining clusters a and b; *last: the last of them. */
static int gates_joining(const gb_segmentation *seg, uint32_t a, uint32_t b, uint32_t *last)
{
    int count = 0;
    for (uint32_t g = 0; g < seg->gate_count; ++g) {
        const uint32_t *c = seg->gates[g].clusters;
        if ((c[0] == a && c[1] == b) || (c[0] == b && c[1] == a)) {
            *last = g;
            ++count;
        }
    }
    return count;
}

/* A pair's one gate: at the centroid of its faces, along their mean normal
 * (oriented from the gate's first cluster). */
static int gate_on_faces(const gb_visibility_gate *gate, const face_sums *f, double voxel)
{
    double sign = gate->clusters[0] == f->a ? 1.0 : -1.0, length = 0.0, off = 0.0, along = 0.0;
    for (int a = 0; a < 3; ++a)
        length += f->normal[a] * f->normal[a];
    length = sqrt(length);
    for (int a = 0; a < 3; ++a) {
        double c = f->centre[a] / f->count - gate->centre[a];
        off += c * c;
        along += length > 0.0 ? sign * f->normal[a] / length * gate->normal[a] : 1.0 / 3.0;
    }
    return sqrt(off) <= 1e-4 * voxel && along >= 1.0 - 1e-5;
}

/* voxelize, thin, segment and gb_segment_fit_gates on the Cornell box at 32,
 * written and read back: the gates are fitted, and against the faces
 * between the clusters' empty voxels counted here, every touching pair of
 * clusters has a gate, and a pair with one gate has it at its faces'
 * centroid along their mean normal. */
static void test_fitted_bake(void)
{
    gb_scene scene = {0};
    build_cornell_box(&scene, 16, 16);
    gb_voxelize_options voxelize = {.resolution = 32};
    gb_voxel_grid grid = {0};
    gb_skeleton skeleton = {0};
    gb_segmentation seg = {0}, back = {0};
    gb_segment_stats stats;
    int32_t *nearest = NULL;
    gb_error error;
    scratch_create("fitted-bake");
    const char *path = scratch_path("cornell.seg");
    gb_result result = gb_voxelize_scene(&scene, &voxelize, &grid, &error);
    if (result == GB_OK)
        result = gb_thin(&grid, NULL, &skeleton, &nearest, NULL, &error);
    if (result == GB_OK)
        result = gb_segment(&skeleton, NULL, &seg, &stats, &error);
    if (result == GB_OK)
        result = gb_segment_fit_gates(&seg, &grid, nearest, &stats, &error);
    if (result == GB_OK)
        result = gb_segmentation_write(path, &seg, &error);
    if (result == GB_OK)
        result = gb_segmentation_read(path, &back, &error);
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    CHECK(result == GB_OK && back.gates_fitted == 1 && segmentations_equal(&seg, &back),
          "fitted bake: voxelize, thin, segment, fit, written and read back, gates fitted");
    if (result == GB_OK) {
        int32_t *clusters = gb_segmentation_voxel_clusters(&back, nearest);
        face_sums *sums = malloc(((size_t)back.cluster_count * back.cluster_count + 1) *
                                 sizeof *sums);
        uint32_t pairs = count_faces(&grid, clusters, sums), single = 0, joined = 0, on = 0;
        for (uint32_t i = 0; i < pairs; ++i) {
            uint32_t last = 0;
            int n = gates_joining(&back, sums[i].a, sums[i].b, &last);
            joined += n > 0;
            single += n == 1;
            on += n == 1 && gate_on_faces(&back.gates[last], &sums[i], back.voxel_size);
        }
        printf("# fitted bake: %u clusters, %u gates (%u opening gates, %u fitted), %u touching "
               "pairs, %u with one gate\n", back.cluster_count, back.gate_count,
               stats.opening_gates, stats.fitted_gates, pairs, single);
        CHECK(pairs > 0 && stats.opening_gates > 0 && joined == pairs,
              "fitted bake: every pair of touching clusters has a gate");
        CHECK(single > 0 && on == single,
              "fitted bake: a pair's one gate sits at its faces' centroid, along their normal");
        free(sums);
        free(clusters);
    }
    CHECK(gb_segment_fit_gates(&back, &grid, nearest, NULL, &error) == GB_ERROR_ARGUMENT,
          "fitted bake: fitting twice is refused");
    scratch_remove();
    gb_segmentation_free(&back);
    free(nearest);
    gb_segmentation_free(&seg);
    gb_skeleton_free(&skeleton);
    gb_voxel_grid_free(&grid);
    gb_scene_free(&scene);
}

/* ---- the lookup ---- */

/* Two segmented nodes in clusters 0 and 1 over a 4 x 2 x 1 grid of voxels of
 * 0.5 from (-1, 0, 0); a third skeleton node maps to the second. */
static void make_two_clusters(gb_segmentation *seg, gb_voxel_grid *frame, int32_t nearest[8])
{
    static gb_segmented_node nodes[2] = {{0, GB_NODE_TOPOLOGY, {-0.5f, 0.5f, 0.25f}, 1},
                                         {1, GB_NODE_TOPOLOGY, {0.5f, 0.5f, 0.25f}, 1}};
    static uint32_t edges[2] = {0, 1}, cluster[2] = {0, 1}, node_map[3] = {0, 1, 1};
    static gb_visibility_gate gate = {{0, 0.5f, 0.25f}, {1, 0, 0}, 1, {0, 1}, 0};
    memset(seg, 0, sizeof *seg);
    seg->skeleton_node_count = 3;
    seg->node_count = 2;
    seg->edge_count = 1;
    seg->cluster_count = 2;
    seg->gate_count = 1;
    seg->nodes = nodes;
    seg->edges = edges;
    seg->cluster = cluster;
    seg->node_map = node_map;
    seg->gates = &gate;
    seg->alpha = 20;
    seg->scene_hash = 42;
    seg->voxel_size = 0.5;
    seg->world_origin[0] = -1.0;
    seg->grid_size[0] = 4;
    seg->grid_size[1] = 2;
    seg->grid_size[2] = 1;
    memset(frame, 0, sizeof *frame);
    frame->voxel_size = 0.5;
    frame->world_origin[0] = -1.0;
    memcpy(frame->size, seg->grid_size, sizeof frame->size);
    frame->scene_hash = 42;
    const int32_t values[8] = {0, 0, 1, 2, -1, 0, 2, 2};
    memcpy(nearest, values, sizeof values);
}

static void test_lookup(void)
{
    gb_segmentation seg;
    gb_voxel_grid frame;
    int32_t nearest[8];
    gb_error error;
    make_two_clusters(&seg, &frame, nearest);
    CHECK(gb_segmentation_validate(&seg, "two", &error) == GB_OK, "lookup: a valid segmentation");
    CHECK(gb_segmentation_check_grid(&seg, &frame, nearest, "grid", &error) == GB_OK,
          "lookup: the grid matches");
    const double points[][3] = {{-0.9, 0.1, 0.1}, {0.1, 0.1, 0.1}, {0.9, 0.4, 0.4},
                                {-0.9, 0.6, 0.1}, {0.6, 0.9, 0.4}, {1.0, 0.1, 0.1},
                                {-1.01, 0.1, 0.1}, {0.1, 0.1, 0.5}};
    const int32_t expected[] = {0, 1, 1, -1, 1, -1, -1, -1};
    int all = 1;
    for (int i = 0; i < 8; ++i)
        all &= gb_segmentation_cluster_at(&seg, nearest, points[i]) == expected[i];
    CHECK(all, "lookup: point -> voxel -> nearest node -> segmented node -> cluster");
    int32_t *per_voxel = gb_segmentation_voxel_clusters(&seg, nearest);
    const int32_t voxel_expected[8] = {0, 0, 1, 1, -1, 0, 1, 1};
    all = per_voxel != NULL;
    for (int v = 0; all && v < 8; ++v) {
        double centre[3] = {-1.0 + 0.5 * (v % 4 + 0.5), 0.5 * (v / 4 + 0.5), 0.25};
        all &= per_voxel[v] == voxel_expected[v] &&
               per_voxel[v] == gb_segmentation_cluster_at(&seg, nearest, centre);
    }
    CHECK(all, "lookup: the cluster of every voxel, as the lookup at its centre gives it");
    free(per_voxel);

    frame.scene_hash = 43;
    CHECK(gb_segmentation_check_grid(&seg, &frame, nearest, "grid", &error) == GB_ERROR_STALE,
          "lookup: a grid of another scene is refused");
    frame.scene_hash = 42;
    frame.size[0] = 5;
    CHECK(gb_segmentation_check_grid(&seg, &frame, nearest, "grid", &error) == GB_ERROR_STALE,
          "lookup: a grid of another frame is refused");
    frame.size[0] = 4;
    nearest[3] = 3;
    CHECK(gb_segmentation_check_grid(&seg, &frame, nearest, "grid", &error) == GB_ERROR_INVALID,
          "lookup: a grid naming a missing node is refused");
}

/* ---- evaluation in a box ---- */

/* The room [0,2] x [0,1] x [0,1], two clusters split at x = 1 with a gate
 * covering the whole section; with wall, the section is closed by a
 * two-sided wall. */
static void evaluate_box(int wall, gb_segment_evaluation *out)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    const float lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1};
    add_box(&scene, lo, hi, 1, grey);
    if (wall) {
        const float quad[4][3] = {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}};
        add_quad(&scene, quad, grey);
    }
    scene_done(&scene);
    static gb_segmented_node nodes[2] = {{0, GB_NODE_TOPOLOGY, {0.5f, 0.5f, 0.5f}, 1},
                                         {1, GB_NODE_TOPOLOGY, {1.5f, 0.5f, 0.5f}, 1}};
    static uint32_t edges[2] = {0, 1}, cluster[2] = {0, 1}, node_map[2] = {0, 1};
    static gb_visibility_gate gate = {{1, 0.5f, 0.5f}, {1, 0, 0}, 1, {0, 1}, 0};
    gb_segmentation seg = {2, 2, 1, 2, 1, nodes, edges, cluster, node_map, &gate, 20,
                           scene.hash, 0.25, {-0.25, -0.25, -0.25}, {10, 6, 6}, 8, 0};
    int32_t nearest[10 * 6 * 6];
    for (int v = 0; v < 360; ++v)
        nearest[v] = (v % 10) < 5 ? 0 : 1; /* voxel centres x < 1: node 0 */
    gb_segment_evaluate_options options = {.pairs = 4000, .seed = 3};
    gb_error error;
    gb_result result = gb_segment_evaluate(&scene, &seg, nearest, &options, out, &error);
    if (result)
        printf("# gb_segment_evaluate: %s\n", error.message);
    CHECK(result == GB_OK, wall ? "evaluate (wall): runs" : "evaluate (box): runs");
    gb_scene_free(&scene);
}

static void test_evaluate(void)
{
    gb_segment_evaluation e;
    evaluate_box(0, &e);
    CHECK_EQ_INT(e.pairs, 4000, "evaluate (box): every pair evaluated");
    CHECK_EQ_INT(e.visible, 4000, "evaluate (box): a convex room sees itself");
    CHECK_NEAR(gb_visibility_precision(&e.same_cluster), 1.0, 0.0,
               "evaluate (box): same cluster, precision 1");
    CHECK_NEAR(gb_visibility_recall(&e.same_cluster), 0.5, 0.05,
               "evaluate (box): same cluster, recall about 1/2");
    CHECK_NEAR(gb_visibility_recall(&e.one_gate), 1.0, 0.0,
               "evaluate (box): through the gate, recall 1");
    CHECK_NEAR(gb_visibility_precision(&e.one_gate), 1.0, 0.0,
               "evaluate (box): through the gate, precision 1");
    gb_segment_evaluation again;
    evaluate_box(0, &again);
    CHECK(!memcmp(&e.same_cluster, &again.same_cluster, sizeof e.same_cluster) &&
              e.grazing == again.grazing,
          "evaluate: the same seed gives the same counts");

    evaluate_box(1, &e);
    CHECK_NEAR(gb_visibility_precision(&e.same_cluster), 1.0, 0.0,
               "evaluate (wall): same cluster, precision 1");
    CHECK_NEAR(gb_visibility_recall(&e.same_cluster), 1.0, 0.0,
               "evaluate (wall): same cluster, recall 1 (points on the wall on their side)");
    CHECK(gb_visibility_precision(&e.one_gate) < 0.8,
          "evaluate (wall): the gate through the wall predicts wrongly");
    CHECK_EQ_INT(e.unlocated, 0, "evaluate: every point found a cluster");
}

/* ---- a convex room, end to end ---- */

/* The clusters of the empty voxels strictly inside [lo, hi] (one voxel in
 * from the walls), through thin's grid and the segmentation; how many
 * distinct ones, and how many such voxels have none. */
static int room_clusters(const gb_voxel_grid *g, const int32_t *nearest,
                         const gb_segmentation *seg, const float lo[3], const float hi[3],
                         int *unlocated)
{
    uint8_t *seen = calloc(seg->cluster_count + 1, 1);
    int distinct = 0;
    *unlocated = 0;
    for (int32_t k = 0; k < g->size[2]; ++k)
        for (int32_t j = 0; j < g->size[1]; ++j)
            for (int32_t i = 0; i < g->size[0]; ++i) {
                int32_t v[3] = {i, j, k}, inside = 1;
                for (int a = 0; a < 3; ++a) {
                    double c = g->world_origin[a] + (v[a] + 0.5) * g->voxel_size;
                    inside &= c > lo[a] + g->voxel_size && c < hi[a] - g->voxel_size;
                }
                size_t index = gb_voxel_index(g, i, j, k);
                if (!inside || g->surface[index])
                    continue;
                int32_t node = nearest[index];
                if (node < 0) {
                    ++*unlocated;
                    continue;
                }
                uint32_t c = seg->cluster[seg->node_map[node]];
                distinct += !seen[c];
                seen[c] = 1;
            }
    free(seen);
    return distinct;
}

/* A closed box room 4 x 3 x 5 voxelized at 48, thinned, segmented: its
 * inside is one visibility cluster (the other clusters are the empty shell
 * voxelize pads the scene with, outside the walls). */
static void test_convex_room(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    uint32_t grey = add_grey(&scene, 0.5f, 0.0f);
    const float lo[3] = {0, 0, 0}, hi[3] = {4, 3, 5};
    add_box(&scene, lo, hi, 1, grey);
    scene_done(&scene);
    gb_voxelize_options voxelize = {.resolution = 48};
    gb_voxel_grid grid = {0};
    gb_skeleton skeleton = {0};
    gb_segmentation seg = {0};
    int32_t *nearest = NULL;
    gb_error error;
    gb_result result = gb_voxelize_scene(&scene, &voxelize, &grid, &error);
    if (result == GB_OK)
        result = gb_thin(&grid, NULL, &skeleton, &nearest, NULL, &error);
    if (result == GB_OK)
        result = gb_segment(&skeleton, NULL, &seg, NULL, &error);
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    CHECK(result == GB_OK, "convex room: voxelize, thin, segment");
    if (result == GB_OK) {
        int unlocated, distinct = room_clusters(&grid, nearest, &seg, lo, hi, &unlocated);
        printf("# convex room: %u skeleton nodes, %u clusters in all, %d inside, %d voxels "
               "inside without a node\n", skeleton.node_count, seg.cluster_count, distinct,
               unlocated);
        CHECK(distinct == 1 && unlocated == 0, "convex room: its inside is one cluster");
    }
    free(nearest);
    gb_segmentation_free(&seg);
    gb_skeleton_free(&skeleton);
    gb_voxel_grid_free(&grid);
    gb_scene_free(&scene);
}

int main(void)
{
    (void)add_point_light; /* a scene_builder.h helper these tests do not use */
    test_measures();
    test_bent_line();
    test_shrinking_balls();
    test_t_junction();
    test_alpha_extremes();
    test_big_cluster();
    test_ball_rule();
    test_gates();
    test_invariants();
    test_ring();
    test_loop_line(3.0f, 1);
    test_loop_line(20.0f, 0);
    test_coincident_nodes();
    test_isolated_nodes();
    test_equal_radii();
    test_file();
    test_fitted_gates();
    test_gate_fitted_to_opening();
    test_fitted_bake();
    test_lookup();
    test_evaluate();
    test_convex_room();
    return tap_done();
}
