/* test_thin.c — unit tests of tools/thin: the skeleton has the topology of
 * the empty space (components and independent cycles, computed here without
 * thin's code), is a graph with no 2-D patch, is centred in corridors, and
 * the nearest-node grid only maps voxels to nodes reachable through empty
 * space; same input, same bytes. */
#include "../../tools/thin/cavities.h"
#include "../../tools/thin/collapse.h"
#include "../../tools/thin/cubical_complex.h"
#include "../../tools/thin/nearest_node.h"
#include "../../tools/thin/persistence.h"
#include "../../tools/thin/thin.h"
#include "tap.h"
#include "tap_printf.h"
#include "thin_volumes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- the skeleton graph ---- */

static uint32_t graph_root(uint32_t *parent, uint32_t n)
{
    while (parent[n] != n)
        n = parent[n] = parent[parent[n]];
    return n;
}

static long graph_components(const gb_skeleton *s)
{
    uint32_t *parent = malloc((s->node_count + 1) * sizeof *parent);
    for (uint32_t n = 0; n < s->node_count; ++n)
        parent[n] = n;
    long components = s->node_count;
    for (uint32_t e = 0; e < s->edge_count; ++e) {
        uint32_t a = graph_root(parent, s->edges[2 * e]);
        uint32_t b = graph_root(parent, s->edges[2 * e + 1]);
        if (a != b) {
            parent[a] = b;
            --components;
        }
    }
    free(parent);
    return components;
}

/* Corner coordinates of a node (positions are exact lattice corners). */
static void node_corner(const gb_skeleton *s, const gb_voxel_grid *g, uint32_t n, int corner[3])
{
    for (int a = 0; a < 3; ++a)
        corner[a] = (int)lround((s->nodes[n].position[a] - g->world_origin[a]) / g->voxel_size);
}

/* The corners of edge e's two nodes. */
static void edge_corners(const gb_skeleton *s, const gb_voxel_grid *g, uint32_t e, int a[3],
                         int b[3])
{
    node_corner(s, g, s->edges[2 * e], a);
    node_corner(s, g, s->edges[2 * e + 1], b);
}

static int on_lattice(const gb_skeleton *s, const gb_voxel_grid *g)
{
    for (uint32_t n = 0; n < s->node_count; ++n) {
        int c[3];
        node_corner(s, g, n, c);
        for (int a = 0; a < 3; ++a)
            if (fabs(g->world_origin[a] + c[a] * g->voxel_size - s->nodes[n].position[a]) > 1e-4)
                return 0;
        int touches_empty = 0;
        for (int d = 0; d < 8; ++d)
            touches_empty |= volume_empty(g, c[0] - 1 + (d & 1), c[1] - 1 + ((d >> 1) & 1),
                                          c[2] - 1 + ((d >> 2) & 1));
        if (!touches_empty)
            return 0;
    }
    return 1;
}

/* Whether some edge's corners a (its first node's) and b pass test. */
static int some_edge(const gb_skeleton *s, const gb_voxel_grid *g,
                     int (*test)(const int a[3], const int b[3], const int *p), const int *p)
{
    for (uint32_t e = 0; e < s->edge_count; ++e) {
        int a[3], b[3];
        edge_corners(s, g, e, a, b);
        if (test(a, b, p))
            return 1;
    }
    return 0;
}

static int not_unit(const int a[3], const int b[3], const int *unused)
{
    (void)unused;
    return abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]) != 1;
}

/* From corner p = {x, y, z, axis} one step up along axis. */
static int steps_from(const int a[3], const int b[3], const int *p)
{
    return a[0] == p[0] && a[1] == p[1] && a[2] == p[2] && b[p[3]] == p[p[3]] + 1;
}

/* Edges join nodes one lattice step apart. */
static int edges_are_unit(const gb_skeleton *s, const gb_voxel_grid *g)
{
    return !some_edge(s, g, not_unit, NULL);
}

/* Is there an edge between the nodes at corners p and p + unit step? */
static int has_edge_at(const gb_skeleton *s, const gb_voxel_grid *g, const int p[3], int axis)
{
    const int from[4] = {p[0], p[1], p[2], axis};
    return some_edge(s, g, steps_from, from);
}

/* No unit square of the lattice has its 4 edges in the graph while it is a
 * face of an empty voxel (a 2-D patch that should have collapsed). */
static int no_filled_square(const gb_skeleton *s, const gb_voxel_grid *g)
{
    for (uint32_t e = 0; e < s->edge_count; ++e) {
        int p[3], q[3];
        edge_corners(s, g, e, p, q);
        int u = q[0] != p[0] ? 0 : q[1] != p[1] ? 1 : 2;
        for (int v = 0; v < 3; ++v) {
            if (v == u)
                continue;
            int pv[3] = {p[0], p[1], p[2]}, pu[3] = {p[0], p[1], p[2]};
            pv[v] += 1;
            pu[u] += 1;
            if (!has_edge_at(s, g, pv, u) || !has_edge_at(s, g, p, v) || !has_edge_at(s, g, pu, v))
                continue;
            int w = 3 - u - v, c[3] = {p[0], p[1], p[2]};
            int below = volume_empty(g, c[0] - (w == 0), c[1] - (w == 1), c[2] - (w == 2));
            int above = volume_empty(g, c[0], c[1], c[2]);
            if (below || above)
                return 0;
        }
    }
    return 1;
}

/* ---- running thin ---- */

typedef struct outcome {
    gb_skeleton skeleton;
    int32_t *nearest;
    gb_thin_stats stats;
    gb_result result;
} outcome;

static outcome run_thin(const gb_voxel_grid *g, const gb_thin_options *options)
{
    outcome o;
    memset(&o, 0, sizeof o);
    gb_error error = {{0}};
    o.result = gb_thin(g, options, &o.skeleton, &o.nearest, &o.stats, &error);
    if (o.result)
        printf("# gb_thin: %s\n", error.message);
    return o;
}

static void free_outcome(outcome *o)
{
    gb_skeleton_free(&o->skeleton);
    free(o->nearest);
}

/* Every empty voxel maps to a node at a corner of a voxel of its own
 * component; non-empty voxels map to -1 unless next to empty space. */
static int nearest_is_consistent(const gb_voxel_grid *g, const outcome *o)
{
    for (int k = 0; k < g->size[2]; ++k)
        for (int j = 0; j < g->size[1]; ++j)
            for (int i = 0; i < g->size[0]; ++i) {
                int32_t node = o->nearest[gb_voxel_index(g, i, j, k)];
                int next_to_empty = 0;
                for (int d = 0; d < 27; ++d)
                    next_to_empty |=
                        volume_empty(g, i + d % 3 - 1, j + d / 3 % 3 - 1, k + d / 9 - 1);
                if (!next_to_empty && node != -1)
                    return 0;
                if (next_to_empty && (node < 0 || (uint32_t)node >= o->skeleton.node_count))
                    return 0;
            }
    return 1;
}

static void check_topology(const char *name, gb_voxel_grid *g, long expected_b0,
                           long expected_b1, long expected_b2)
{
    volume_topology t = volume_topology_of(g);
    CHECK_EQ_INTF(t.b0, expected_b0, "%s: empty space has b0 = %ld (flood fill)", name,
                  expected_b0);
    CHECK_EQ_INTF(t.b1, expected_b1, "%s: empty space has b1 = %ld (Euler characteristic)",
                  name, expected_b1);
    CHECK_EQ_INTF(t.b2, expected_b2, "%s: empty space has b2 = %ld (complement)", name,
                  expected_b2);

    gb_cubical_complex complex;
    gb_error error;
    gb_result built = gb_cubical_complex_build(&complex, g, &error);
    CHECK_EQ_INTF(built ? -999 : gb_euler_characteristic(gb_cubical_complex_count(&complex)),
                  t.euler, "%s: thin's complex has the Euler characteristic", name);
    gb_cubical_complex_free(&complex);

    outcome o = run_thin(g, NULL);
    CHECK_EQ_INTF(o.result, GB_OK, "%s: thin succeeds", name);
    const gb_skeleton *s = &o.skeleton;
    long components = graph_components(s);
    long cycles = (long)s->edge_count - (long)s->node_count + components;
    CHECK_EQ_INTF(components, t.b0, "%s: skeleton has the empty space's components", name);
    CHECK_EQ_INTF(cycles, t.b1, "%s: skeleton has its independent cycles (E - V + C)", name);
    CHECK_EQ_INTF(o.stats.cavities_opened, t.b2, "%s: one square opened per cavity", name);
    CHECK_EQ_INTF(o.stats.squares_left, 0, "%s: thin: no square left", name);
    CHECKF(no_filled_square(s, g), "%s: no unit square of edges over an empty voxel face",
           name);
    CHECKF(on_lattice(s, g), "%s: nodes on lattice corners of empty voxels", name);
    CHECKF(edges_are_unit(s, g), "%s: edges are unit lattice steps", name);
    CHECKF(o.nearest && nearest_is_consistent(g, &o),
           "%s: every voxel next to empty space has a node, others -1", name);
    printf("# %s: %u nodes, %u edges, %u iterations\n", name, s->node_count, s->edge_count,
           o.stats.iterations);
    free_outcome(&o);
    gb_voxel_grid_free(g);
}

/* ---- the volumes of the issue ---- */

/* A volume: a solid grid of `size`, carved by `carve` (when not NULL),
 * then its boxes (volume_boxes); the Betti numbers of its empty space. */
typedef struct topology_case {
    const char *name;
    int size[3];
    long b0, b1, b2;
    void (*carve)(gb_voxel_grid *g);
    int boxes[7][7];            /* room for the VOLUME_END after six */
} topology_case;

/* A corridor along the diagonal of the xy plane: the 3 x 3 blocks around
 * (i, i), z 1..4; the boxes after it close the grid's walls again. */
static void carve_diagonal(gb_voxel_grid *g)
{
    for (int i = 1; i < 19; ++i)
        volume_box(g, i - 1, i - 1, 1, i + 1, i + 1, 4, 0);
}

/* Empty voxels (i, i, i), each touching the next at a corner only. */
static void carve_corners(gb_voxel_grid *g)
{
    for (int i = 1; i < 7; ++i)
        volume_box(g, i, i, i, i, i, i, 0);
}

static const topology_case topology_cases[] = {
    {"box room", {14, 12, 10}, 1, 0, 0, NULL, {{1, 1, 1, 12, 10, 8, VOLUME_EMPTY}}},
    {"ring corridor", {16, 16, 6}, 1, 1, 0, NULL,
     {{1, 1, 1, 14, 14, 4, VOLUME_EMPTY}, {5, 5, 1, 10, 10, 4, VOLUME_SOLID}}},
    {"two rooms and a door", {24, 12, 9}, 1, 0, 0, NULL,
     {{1, 1, 1, 22, 10, 7, VOLUME_EMPTY}, {11, 0, 0, 12, 11, 8, VOLUME_SOLID},
      {11, 5, 1, 12, 6, 4, VOLUME_EMPTY}}},
    {"room with a floor-to-ceiling pillar", {14, 14, 7}, 1, 1, 0, NULL,
     {{1, 1, 1, 12, 12, 5, VOLUME_EMPTY}, {6, 6, 1, 7, 7, 5, VOLUME_SOLID}}},
    {"room with two pillars", {16, 16, 7}, 1, 2, 0, NULL,
     {{1, 1, 1, 14, 14, 5, VOLUME_EMPTY}, {4, 4, 1, 5, 5, 5, VOLUME_SOLID},
      {10, 9, 1, 11, 11, 5, VOLUME_SOLID}}},
    {"1-voxel corridor", {14, 3, 3}, 1, 0, 0, NULL, {{1, 1, 1, 12, 1, 1, VOLUME_EMPTY}}},
    {"1-voxel ring corridor", {9, 9, 3}, 1, 1, 0, NULL,
     {{1, 1, 1, 7, 1, 1, VOLUME_EMPTY}, {1, 7, 1, 7, 7, 1, VOLUME_EMPTY},
      {1, 1, 1, 1, 7, 1, VOLUME_EMPTY}, {7, 1, 1, 7, 7, 1, VOLUME_EMPTY}}},
    {"diagonal corridor", {20, 20, 6}, 1, 0, 0, carve_diagonal,
     {{0, 0, 0, 19, 19, 0, VOLUME_SOLID}, {0, 0, 5, 19, 19, 5, VOLUME_SOLID},
      {0, 0, 0, 0, 19, 5, VOLUME_SOLID}, {0, 0, 0, 19, 0, 5, VOLUME_SOLID},
      {19, 0, 0, 19, 19, 5, VOLUME_SOLID}, {0, 19, 0, 19, 19, 5, VOLUME_SOLID}}},
    {"voxels touching only at corners", {8, 8, 8}, 1, 0, 0, carve_corners, {{0}}},
    {"empty space filling the grid", {10, 9, 8}, 1, 0, 0, NULL, {{0, 0, 0, 9, 8, 7, VOLUME_EMPTY}}},
    {"corridors leaving the grid", {12, 7, 7}, 1, 0, 0, NULL,
     {{0, 2, 2, 11, 4, 4, VOLUME_EMPTY}, {4, 0, 2, 6, 6, 4, VOLUME_EMPTY}}},
    {"no empty voxel", {6, 5, 4}, 0, 0, 0, NULL, {{0}}},
    {"single empty voxel", {3, 3, 3}, 1, 0, 0, NULL, {{1, 1, 1, 1, 1, 1, VOLUME_EMPTY}}},
    {"a grid of one empty voxel", {1, 1, 1}, 1, 0, 0, NULL, {{0, 0, 0, 0, 0, 0, VOLUME_EMPTY}}},
    {"a grid one voxel thick, cut in two", {1, 9, 1}, 2, 0, 0, NULL,
     {{0, 0, 0, 0, 8, 0, VOLUME_EMPTY}, {0, 4, 0, 0, 4, 0, VOLUME_SOLID}}},
    {"object floating in a room", {16, 16, 16}, 1, 0, 1, NULL,
     {{1, 1, 1, 14, 14, 14, VOLUME_EMPTY}, {6, 5, 7, 9, 9, 9, VOLUME_SOLID}}},
    {"two floating objects, one hollow", {18, 16, 16}, 2, 0, 2, NULL,
     {{1, 1, 1, 16, 14, 14, VOLUME_EMPTY}, {4, 5, 5, 7, 9, 9, VOLUME_SOLID},
      {11, 5, 5, 14, 9, 9, VOLUME_SOLID}, {12, 6, 6, 13, 8, 8, VOLUME_EMPTY}}},
    {"floating object with a hole through it", {16, 16, 16}, 1, 1, 1, NULL,
     {{1, 1, 1, 14, 14, 14, VOLUME_EMPTY}, {5, 5, 5, 10, 10, 10, VOLUME_SOLID},
      {7, 5, 7, 8, 10, 8, VOLUME_EMPTY}}},
    {"two separate rooms", {20, 8, 8}, 2, 0, 0, NULL,
     {{1, 1, 1, 7, 6, 6, VOLUME_EMPTY}, {12, 1, 1, 18, 6, 6, VOLUME_EMPTY}}},
    {"an object floating in a hollow floating object", {22, 22, 22}, 2, 0, 2, NULL,
     {{1, 1, 1, 20, 20, 20, VOLUME_EMPTY}, {4, 4, 4, 17, 17, 17, VOLUME_SOLID},
      {6, 6, 6, 15, 15, 15, VOLUME_EMPTY}, {9, 9, 9, 12, 12, 12, VOLUME_SOLID}}},
};

static void test_topology_cases(void)
{
    for (size_t c = 0; c < sizeof topology_cases / sizeof *topology_cases; ++c) {
        const topology_case *t = &topology_cases[c];
        gb_voxel_grid g = volume_solid(t->size[0], t->size[1], t->size[2]);
        if (t->carve)
            t->carve(&g);
        volume_boxes(&g, t->boxes);
        check_topology(t->name, &g, t->b0, t->b1, t->b2);
    }
}

/* ---- geometry ---- */

/* A straight corridor along x of cross-section w x h: nodes away from its
 * ends lie on its axis, with the radius of the largest ball across it. */
static void check_centred(int w, int h)
{
    int length = 30;
    gb_voxel_grid g = volume_solid(length + 2, w + 2, h + 2);
    volume_box(&g, 1, 1, 1, length, w, h, 0);
    float largest = 0.0f;
    for (int k = 1; k <= h; ++k)
        for (int j = 1; j <= w; ++j) {
            float d = volume_brute_distance(&g, length / 2, j, k);
            largest = d > largest ? d : largest;
        }
    outcome o = run_thin(&g, NULL);
    int middle_nodes = 0, off_axis = 0, radius_off = 0;
    double centre_y = g.world_origin[1] + g.voxel_size * (1 + w / 2.0);
    double centre_z = g.world_origin[2] + g.voxel_size * (1 + h / 2.0);
    for (uint32_t n = 0; n < o.skeleton.node_count; ++n) {
        const gb_skeleton_node *node = &o.skeleton.nodes[n];
        double x = (node->position[0] - g.world_origin[0]) / g.voxel_size;
        if (x < 8 || x > length - 6)
            continue;
        ++middle_nodes;
        if (fabs(node->position[1] - centre_y) > 0.5 * g.voxel_size + 1e-6 ||
            fabs(node->position[2] - centre_z) > 0.5 * g.voxel_size + 1e-6)
            ++off_axis;
        if (node->radius < largest - g.voxel_size - 1e-6 || node->radius > largest + 1e-6)
            ++radius_off;
    }
    char what[160];
    snprintf(what, sizeof what, "corridor %dx%d: the skeleton runs along its middle", w, h);
    CHECK(middle_nodes >= length - 14, what);
    snprintf(what, sizeof what, "corridor %dx%d: nodes within half a voxel of the axis", w, h);
    CHECK_EQ_INT(off_axis, 0, what);
    snprintf(what, sizeof what,
             "corridor %dx%d: node radius within one voxel of the largest distance across", w, h);
    CHECK_EQ_INT(radius_off, 0, what);
    snprintf(what, sizeof what, "corridor %dx%d: a single line (no spur)", w, h);
    CHECK_EQ_INT(o.skeleton.edge_count + 1, o.skeleton.node_count, what);
    free_outcome(&o);
    gb_voxel_grid_free(&g);
}

/* Two rooms, a wall at x = 12..13 with a door: every voxel of a room maps to
 * a node on its side of the wall or in the doorway, never to one across the
 * wall, although the nodes across are nearer in a straight line. */
static void test_grid_through_door(void)
{
    static const int rooms[][7] = {
        {1, 1, 1, 26, 20, 7, VOLUME_EMPTY}, {12, 0, 0, 13, 23, 8, VOLUME_SOLID},
        {12, 1, 1, 13, 3, 7, VOLUME_EMPTY} /* the door, at one end of the wall */, {0}};
    gb_voxel_grid g = volume_made(28, 24, 9, rooms);
    outcome o = run_thin(&g, NULL);
    CHECK_EQ_INT(o.result, GB_OK, "two rooms: thin succeeds");
    int wrong_side = 0, changed_far_from_door = 0;
    for (int k = 1; k <= 7; ++k)
        for (int j = 1; j <= 20; ++j)
            for (int i = 1; i <= 26; ++i) {
                if (!volume_empty(&g, i, j, k) || (i >= 12 && i <= 13))
                    continue;
                int32_t node = o.nearest[gb_voxel_index(&g, i, j, k)];
                double x = (o.skeleton.nodes[node].position[0] - g.world_origin[0]) / g.voxel_size;
                int room = i < 12 ? 0 : 1;
                int node_room = x <= 12.0 ? 0 : x >= 14.0 ? 1 : -1; /* -1: doorway */
                if (node_room >= 0 && node_room != room) {
                    ++wrong_side;
                    if (j > 8)
                        ++changed_far_from_door;
                }
            }
    CHECK_EQ_INT(wrong_side, 0, "two rooms: no voxel maps to a node across the wall");
    CHECK_EQ_INT(changed_far_from_door, 0, "two rooms: mapping crosses rooms only near the door");
    /* the wall voxels far from the door face both rooms: each side's node */
    int32_t west = o.nearest[gb_voxel_index(&g, 11, 15, 4)];
    int32_t wall = o.nearest[gb_voxel_index(&g, 12, 15, 4)];
    double wall_node_x = (o.skeleton.nodes[wall].position[0] - g.world_origin[0]) / g.voxel_size;
    CHECK(wall >= 0 && wall_node_x <= 12.0,
          "two rooms: a wall voxel takes the node of its empty neighbour");
    CHECK(west >= 0, "two rooms: voxels next to the wall have a node");
    CHECK_EQ_INT(o.nearest[gb_voxel_index(&g, 5, 23, 4)], -1,
                 "two rooms: a voxel away from empty space gets -1");
    free_outcome(&o);
    gb_voxel_grid_free(&g);
}

/* The nearest node is the geodesic one: in a U-shaped corridor the node at
 * the end of the other branch is nearer in a straight line but not by path. */
static void test_grid_is_geodesic(void)
{
    static const int branches[][7] = {
        {1, 1, 1, 22, 3, 3, VOLUME_EMPTY}, {1, 9, 1, 22, 11, 3, VOLUME_EMPTY},
        {20, 1, 1, 22, 11, 3, VOLUME_EMPTY}, {0}};
    gb_voxel_grid g = volume_made(24, 13, 5, branches);
    outcome o = run_thin(&g, NULL);
    int crossing = 0;
    for (int i = 1; i <= 17; ++i)
        for (int j = 1; j <= 3; ++j) {
            int32_t node = o.nearest[gb_voxel_index(&g, i, j, 2)];
            double y = (o.skeleton.nodes[node].position[1] - g.world_origin[1]) / g.voxel_size;
            crossing += y > 6.0;
        }
    CHECK_EQ_INT(crossing, 0, "U corridor: voxels of one branch never map to the other branch");
    free_outcome(&o);
    gb_voxel_grid_free(&g);
}

/* ---- the maps of persistence, against their definitions ---- */

/* Chessboard distance of voxel (i,j,k) to the nearest non-empty voxel
 * (outside the grid counts as non-empty), by brute force. */
static int brute_distance(const gb_voxel_grid *g, int i, int j, int k)
{
    if (!volume_empty(g, i, j, k))
        return 0;
    for (int r = 1;; ++r)
        for (int c = k - r; c <= k + r; ++c)
            for (int b = j - r; b <= j + r; ++b)
                for (int a = i - r; a <= i + r; ++a)
                    if (!volume_empty(g, a, b, c))
                        return r;
}

/* Both maps of g against brute force, every voxel (their openings taken on
 * 3 threads). */
static void check_maps(gb_voxel_grid g, const char *what)
{
    gb_cubical_complex complex;
    gb_persistence maps;
    gb_error error;
    CHECK(!gb_cubical_complex_build(&complex, &g, &error) &&
              !gb_persistence_init(&maps, &complex, 1.0, 0.0, 3, NULL, NULL, &error),
          "maps: computed");
    int nx = g.size[0], ny = g.size[1], nz = g.size[2];
    int *d = malloc(sizeof *d * (size_t)nx * ny * nz);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                d[gb_voxel_index(&g, i, j, k)] = brute_distance(&g, i, j, k);
    int distance_wrong = 0, opening_wrong = 0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                size_t cell = gb_voxel_cell(&complex, i, j, k);
                distance_wrong += gb_persistence_distance(&maps, cell) !=
                                  d[gb_voxel_index(&g, i, j, k)];
                int opening = 0; /* max distance(y) over y with |x - y| < distance(y) */
                for (int c = 0; c < nz; ++c)
                    for (int b = 0; b < ny; ++b)
                        for (int a = 0; a < nx; ++a) {
                            int dy = d[gb_voxel_index(&g, a, b, c)];
                            int far = abs(a - i) > abs(b - j) ? abs(a - i) : abs(b - j);
                            far = abs(c - k) > far ? abs(c - k) : far;
                            if (far < dy && dy > opening)
                                opening = dy;
                        }
                opening_wrong += gb_persistence_opening(&maps, cell) != opening;
            }
    char label[96];
    snprintf(label, sizeof label, "maps (%s): chessboard distance as defined, every voxel", what);
    CHECK_EQ_INT(distance_wrong, 0, label);
    snprintf(label, sizeof label, "maps (%s): opening as defined, every voxel", what);
    CHECK_EQ_INT(opening_wrong, 0, label);
    free(d);
    gb_persistence_free(&maps);
    gb_cubical_complex_free(&complex);
    gb_voxel_grid_free(&g);
}

static void test_maps(void)
{
    gb_voxel_grid g = volume_solid(17, 13, 9);
    volume_boxes(&g, (const int[][7]){{1, 1, 1, 15, 11, 7, VOLUME_EMPTY},
                                      {5, 4, 1, 6, 5, 7, VOLUME_SOLID},
                                      {11, 1, 3, 15, 3, 4, VOLUME_SOLID},
                                      /* an opening onto the grid border */
                                      {0, 6, 3, 0, 8, 5, VOLUME_EMPTY},
                                      {0}});
    check_maps(g, "boxes");
    /* rooms of every size: random solid boxes and single voxels in an empty
     * volume (a fixed linear congruential sequence) */
    gb_voxel_grid r = volume_solid(23, 19, 14);
    volume_box(&r, 1, 1, 1, 21, 17, 12, 0);
    uint32_t state = 12345;
    for (int n = 0; n < 40; ++n) {
        int c[6];
        for (int k = 0; k < 6; ++k) {
            state = state * 1664525u + 1013904223u;
            c[k] = (int)((state >> 8) % (uint32_t)r.size[k % 3]);
        }
        int big = n % 4 == 0; /* a box; else a voxel */
        volume_box(&r, c[0], c[1], c[2], big ? c[0] + c[3] % 5 : c[0],
                   big ? c[1] + c[4] % 5 : c[1], big ? c[2] + c[5] % 4 : c[2], 1);
    }
    check_maps(r, "random");
}

/* The sweeps and Dijkstra (on 1 to 5 slabs) give the same grid, also on a
 * serpentine whose far end needs more sweeps than allowed. */
static void check_nearest_ways(const char *name, const gb_voxel_grid *g, int sweep_pairs)
{
    gb_cubical_complex complex;
    gb_empty_voxels empty = {0};
    gb_error error;
    outcome o = run_thin(g, NULL);
    gb_cubical_complex_build(&complex, g, &error);
    uint32_t *cells = malloc((o.skeleton.node_count + 1) * sizeof *cells);
    for (uint32_t n = 0; n < o.skeleton.node_count; ++n) {
        int c[3];
        node_corner(&o.skeleton, g, n, c);
        cells[n] = (uint32_t)gb_cell_index(&complex, c[0] + 1, c[1] + 1, c[2] + 1);
    }
    size_t voxels = (size_t)g->size[0] * g->size[1] * g->size[2];
    /* Dijkstra alone on one slab: the sweeps' own answer is not the reference */
    gb_nearest_options alone = {0, 1, NULL, NULL};
    int32_t *dijkstra = NULL;
    int same = !gb_empty_voxels_of(g, &empty, &error) &&
               !gb_nearest_node(g, &empty, &complex, cells, o.skeleton.node_count, &alone,
                                &dijkstra, &error) &&
               !memcmp(dijkstra, o.nearest, voxels * sizeof *dijkstra);
    gb_empty_voxels_free(&empty);
    int swept = 1;
    const int pair_counts[2] = {sweep_pairs, GB_NEAREST_SWEEP_PAIRS};
    for (int threads = 1; threads <= 5; ++threads)
        for (int p = 0; p < 2; ++p) {
            int pairs = pair_counts[p];
            gb_nearest_options options = {pairs, threads, NULL, NULL};
            int32_t *nearest = NULL;
            int equal = dijkstra && !gb_empty_voxels_of(g, &empty, &error) &&
                        !gb_nearest_node(g, &empty, &complex, cells, o.skeleton.node_count,
                                         &options, &nearest, &error) &&
                        !memcmp(nearest, dijkstra, voxels * sizeof *nearest);
            (p == 0 ? &same : &swept)[0] &= equal;
            free(nearest);
            gb_empty_voxels_free(&empty);
        }
    char what[160];
    snprintf(what, sizeof what,
             "%s: Dijkstra on 1..5 slabs (after %d sweep pairs) and thin give one-slab Dijkstra's grid",
             name, sweep_pairs);
    CHECK(same, what);
    snprintf(what, sizeof what,
             "%s: up to %d sweep pairs on 1..5 threads give one-slab Dijkstra's grid", name,
             GB_NEAREST_SWEEP_PAIRS);
    CHECK(swept, what);
    free(dijkstra);
    free(cells);
    gb_cubical_complex_free(&complex);
    free_outcome(&o);
}

static void test_nearest_ways(void)
{
    gb_voxel_grid g = volume_made(30, 24, 14,
                                  (const int[][7]){{1, 1, 1, 28, 22, 12, VOLUME_EMPTY},
                                                   {8, 6, 1, 9, 7, 12, VOLUME_SOLID},
                                                   {12, 3, 4, 16, 8, 6, VOLUME_SOLID},
                                                   {0}});
    check_nearest_ways("cluttered room", &g, 0);
    gb_voxel_grid_free(&g);

    /* a serpentine of 2-voxel corridors in y, walls every 3 voxels in x */
    g = volume_solid(33, 20, 4);
    volume_box(&g, 1, 1, 1, 31, 18, 2, 0);
    for (int x = 3, gap_at_top = 1; x < 31; x += 3, gap_at_top = !gap_at_top)
        volume_box(&g, x, gap_at_top ? 1 : 3, 0, x, gap_at_top ? 16 : 18, 3, 1);
    check_nearest_ways("serpentine", &g, 0);
    check_nearest_ways("serpentine", &g, 1);
    gb_voxel_grid_free(&g);
}

/* ---- determinism and options ---- */

static int same_outcome(const outcome *a, const outcome *b, size_t voxels)
{
    return a->skeleton.node_count == b->skeleton.node_count &&
           a->skeleton.edge_count == b->skeleton.edge_count &&
           !memcmp(a->skeleton.nodes, b->skeleton.nodes,
                   a->skeleton.node_count * sizeof *a->skeleton.nodes) &&
           !memcmp(a->skeleton.edges, b->skeleton.edges,
                   a->skeleton.edge_count * 2 * sizeof *a->skeleton.edges) &&
           !memcmp(a->nearest, b->nearest, voxels * sizeof *a->nearest);
}

static gb_voxel_grid cluttered_room(void)
{
    return volume_made(30, 24, 14,
                       (const int[][7]){{1, 1, 1, 28, 22, 12, VOLUME_EMPTY},
                                        {8, 6, 1, 9, 7, 12, VOLUME_SOLID},
                                        {18, 12, 1, 20, 14, 12, VOLUME_SOLID},
                                        {12, 3, 4, 16, 8, 6, VOLUME_SOLID},
                                        {3, 15, 1, 10, 16, 8, VOLUME_SOLID},
                                        {22, 2, 7, 26, 6, 9, VOLUME_SOLID},
                                        {0}});
}

static void test_determinism(void)
{
    gb_voxel_grid g = cluttered_room();
    outcome a = run_thin(&g, NULL), b = run_thin(&g, NULL);
    size_t voxels = (size_t)g.size[0] * g.size[1] * g.size[2];
    CHECK(same_outcome(&a, &b, voxels), "determinism: two runs give the same skeleton and grid");
    int threads[] = {1, 3, 4, 7, 64};
    for (int t = 0; t < 5; ++t) {
        gb_thin_options options = {0};
        options.threads = threads[t];
        outcome c = run_thin(&g, &options);
        char what[96];
        snprintf(what, sizeof what, "determinism: %d threads give the same bytes as 2",
                 threads[t]);
        CHECK(same_outcome(&a, &c, voxels), what);
        free_outcome(&c);
    }
    free_outcome(&a);
    free_outcome(&b);
    gb_voxel_grid_free(&g);
}

/* The collapse alone (with its cavity rounds, as thin runs it) on threads,
 * every iteration shared however few cells it lists, or only those listing
 * 1 000 cells or more (the others on one thread): the complex left, the
 * pairs removed and the iterations that removed them are those of one
 * thread. */
typedef struct collapsed {
    uint8_t *faces;
    size_t cell_count;
    uint64_t pairs_removed;
    uint32_t iterations, shared_iterations;
} collapsed;

static collapsed collapse_on(const gb_voxel_grid *g, int threads, size_t parallel_cells)
{
    collapsed out = {0};
    gb_cubical_complex complex = {0};
    gb_persistence persistence = {0};
    gb_collapse collapse = {0};
    gb_error error;
    uint64_t squares_left = 0;
    uint32_t opened = 1;
    if (gb_cubical_complex_build(&complex, g, &error) ||
        gb_persistence_init(&persistence, &complex, 1.0, 0.0, threads, NULL, NULL, &error) ||
        gb_collapse_init(&collapse, &complex, &persistence, threads, &error)) {
        printf("Bail out! collapse_on: %s\n", error.message);
        exit(1);
    }
    collapse.parallel_cells = parallel_cells;
    while (opened)
        if (gb_collapse_run(&collapse, NULL, NULL, &error) ||
            gb_open_cavities(&complex, &collapse, &squares_left, &opened, &error)) {
            printf("Bail out! collapse_on: %s\n", error.message);
            exit(1);
        }
    out.faces = complex.faces;
    out.cell_count = complex.cell_count;
    complex.faces = NULL;
    out.pairs_removed = collapse.pairs_removed;
    out.iterations = collapse.iteration;
    out.shared_iterations = collapse.shared_iterations;
    gb_collapse_free(&collapse);
    gb_persistence_free(&persistence);
    gb_cubical_complex_free(&complex);
    return out;
}

static void test_collapse_threads(void)
{
    /* tall enough for several chunks of 8 planes or more; boxes across the
     * chunks' bounds, and one floating (a cavity to open) */
    gb_voxel_grid g = volume_made(26, 22, 90,
                                  (const int[][7]){{1, 1, 1, 24, 20, 88, VOLUME_EMPTY},
                                                   {8, 6, 1, 9, 7, 88, VOLUME_SOLID},
                                                   {12, 3, 14, 16, 8, 30, VOLUME_SOLID},
                                                   {3, 12, 28, 10, 16, 45, VOLUME_SOLID},
                                                   {15, 12, 40, 19, 15, 44, VOLUME_SOLID},
                                                   {4, 2, 60, 22, 5, 62, VOLUME_SOLID},
                                                   {2, 2, 70, 23, 19, 71, VOLUME_SOLID},
                                                   {0}});
    collapsed one = collapse_on(&g, 1, 1);
    CHECK(one.shared_iterations == 0, "collapse on 1 thread shares no iteration");
    int threads[] = {2, 4, 3, 2};
    size_t parallel_cells[] = {1, 1, 1, 1000};
    for (int t = 0; t < 4; ++t) {
        collapsed many = collapse_on(&g, threads[t], parallel_cells[t]);
        int all = parallel_cells[t] == 1;
        CHECKF(all ? many.shared_iterations >= many.iterations
                   : many.shared_iterations > 0 && many.shared_iterations < many.iterations,
               "collapse on %d threads from %zu cells shares %s iterations (%u of %u)",
               threads[t], parallel_cells[t], all ? "all" : "some", many.shared_iterations,
               many.iterations);
        CHECKF(!memcmp(one.faces, many.faces, one.cell_count) &&
                   one.pairs_removed == many.pairs_removed && one.iterations == many.iterations,
               "collapse on %d threads from %zu cells leaves the complex of 1 (%llu pairs, "
               "%u iterations)",
               threads[t], parallel_cells[t], (unsigned long long)many.pairs_removed,
               many.iterations);
        free(many.faces);
    }
    free(one.faces);
    gb_voxel_grid_free(&g);
}

/* ---- node radii: exact distances, against a brute force ---- */

/* Every node's radius is the largest exact distance to a wall voxel of the
 * empty voxels around its corner, each found by trying every voxel of the
 * grid (volume_brute_distance): equal to the float, not within a tolerance. */
static void test_radii_brute_force(void)
{
    gb_voxel_grid g = cluttered_room();
    outcome o = run_thin(&g, NULL);
    CHECK_EQ_INT(o.result, GB_OK, "radii: thinned");
    int wrong = 0, positive = 0;
    for (uint32_t n = 0; n < o.skeleton.node_count; ++n) {
        int corner[3];
        for (int a = 0; a < 3; ++a)
            corner[a] = (int)lround((o.skeleton.nodes[n].position[a] - g.world_origin[a]) /
                                    g.voxel_size) + 1;
        float radius = 0.0f;
        for (int d = 0; d < 8; ++d) {
            int i = corner[0] - 1 - (d & 1), j = corner[1] - 1 - (d >> 1 & 1),
                k = corner[2] - 1 - (d >> 2 & 1);
            if (volume_empty(&g, i, j, k)) {
                float r = volume_brute_distance(&g, i, j, k);
                radius = r > radius ? r : radius;
            }
        }
        wrong += o.skeleton.nodes[n].radius != radius;
        positive += radius > 0.0f;
    }
    CHECKF(o.skeleton.node_count > 10 && positive == (int)o.skeleton.node_count,
           "radii: %u nodes, each with empty voxels around it", o.skeleton.node_count);
    CHECK_EQ_INT(wrong, 0, "radii: every node's radius is the brute-force distance, exactly");
    free_outcome(&o);
    gb_voxel_grid_free(&g);
}

/* gb_thin_and_free gives the same skeleton and grid as gb_thin, and the
 * surface back; the empty voxels' bits are the surface's zeros. */
static void test_thin_and_free(void)
{
    gb_voxel_grid g = cluttered_room();
    size_t voxels = (size_t)g.size[0] * g.size[1] * g.size[2];
    gb_empty_voxels empty = {0};
    gb_error error;
    int same_bits = gb_empty_voxels_of(&g, &empty, &error) == GB_OK;
    for (size_t v = 0; same_bits && v < voxels; ++v)
        same_bits = gb_voxel_is_empty(&empty, v) == !g.surface[v];
    CHECK(same_bits, "thin and free: the empty voxels' bits are the surface's zeros");
    gb_empty_voxels_free(&empty);
    outcome kept = run_thin(&g, NULL);
    outcome freed = {0};
    freed.result = gb_thin_and_free(&g, NULL, &freed.skeleton, &freed.nearest, &freed.stats,
                                    &error);
    CHECK(freed.result == GB_OK && same_outcome(&kept, &freed, voxels) && g.surface == NULL,
          "thin and free: gb_thin's skeleton and grid, the surface given back");
    free_outcome(&kept);
    free_outcome(&freed);
    gb_voxel_grid_free(&g);
}

static int count_progress(void *user, double fraction)
{
    double *last = user;
    if (fraction < last[0] - 1e-9 || fraction > 1.0 + 1e-9)
        last[1] = 1.0;
    last[0] = fraction;
    last[2] += 1.0;
    return 0;
}

static int cancel_progress(void *user, double fraction)
{
    (void)user;
    return fraction > 0.3;
}

static void test_options(void)
{
    gb_voxel_grid g = cluttered_room();
    gb_thin_options strict = {0}, loose = {0};
    strict.persistence = -1.0;  /* keep every isthmus at once */
    loose.persistence = 4.0;
    loose.min_lifespan = 3.0;
    outcome s = run_thin(&g, &strict), d = run_thin(&g, NULL), l = run_thin(&g, &loose);
    CHECK(s.skeleton.node_count >= d.skeleton.node_count &&
          d.skeleton.node_count >= l.skeleton.node_count,
          "options: a larger persistence keeps fewer nodes");
    CHECK(graph_components(&l.skeleton) == graph_components(&s.skeleton) &&
          (long)l.skeleton.edge_count - l.skeleton.node_count ==
              (long)s.skeleton.edge_count - s.skeleton.node_count,
          "options: topology does not depend on persistence");
    CHECK_NEAR(d.skeleton.persistence, 1.0, 0.0, "options: default persistence recorded");
    CHECK_NEAR(l.skeleton.min_lifespan, 3.0, 0.0, "options: min lifespan recorded");
    CHECK_EQ_INT(d.skeleton.scene_hash, g.scene_hash, "options: scene hash recorded");
    CHECK_NEAR(d.skeleton.voxel_size, g.voxel_size, 0.0, "options: voxel size recorded");
    free_outcome(&s);
    free_outcome(&d);
    free_outcome(&l);

    double seen[3] = {0.0, 0.0, 0.0};
    gb_thin_options watched = {0};
    watched.progress = count_progress;
    watched.progress_user = seen;
    outcome w = run_thin(&g, &watched);
    CHECK(seen[2] > 2 && seen[1] == 0.0, "progress: called, increasing, within [0, 1]");
    free_outcome(&w);

    gb_thin_options cancelled = {0};
    cancelled.progress = cancel_progress;
    gb_error error;
    gb_skeleton skeleton;
    int32_t *nearest = NULL;
    CHECK_EQ_INT(gb_thin(&g, &cancelled, &skeleton, &nearest, NULL, &error),
                 GB_ERROR_INTERRUPTED, "progress: a nonzero return cancels, as interrupted");
    CHECK(skeleton.nodes == NULL && nearest == NULL, "progress: a cancelled run leaves nothing");
    gb_voxel_grid_free(&g);
}

/* The grid as thin's main writes it: an OpenVDB int32 grid that reads back
 * the same, -1 voxels included. */
static void test_grid_file(void)
{
    gb_voxel_grid g = cluttered_room();
    outcome o = run_thin(&g, NULL);
    char path[] = "/tmp/gibake-test-thin-XXXXXX";
    int fd = mkstemp(path);
    if (fd >= 0)
        close(fd);
    gb_error error;
    CHECK_EQ_INT(gb_voxel_grid_write_int32(path, &g, "nearest_node", o.nearest, &error), GB_OK,
                 "grid file: written");
    gb_voxel_grid frame;
    memset(&frame, 0, sizeof frame);
    int32_t *values = NULL;
    CHECK_EQ_INT(gb_voxel_grid_read_int32(path, "nearest_node", &frame, &values, &error), GB_OK,
                 "grid file: read back");
    size_t voxels = (size_t)g.size[0] * g.size[1] * g.size[2];
    CHECK(values && frame.size[0] == g.size[0] && frame.size[1] == g.size[1] &&
              frame.size[2] == g.size[2] && !memcmp(values, o.nearest, voxels * sizeof *values),
          "grid file: same frame and values");
    CHECK_EQ_INT(frame.scene_hash, g.scene_hash, "grid file: scene hash kept");
    free(values);
    gb_voxel_grid_free(&frame);
    unlink(path);
    free_outcome(&o);
    gb_voxel_grid_free(&g);
}

static void test_bad_input(void)
{
    gb_voxel_grid g = {0};
    gb_skeleton skeleton;
    gb_error error;
    CHECK_EQ_INT(gb_thin(&g, NULL, &skeleton, NULL, NULL, &error), GB_ERROR_ARGUMENT,
                 "bad input: an empty grid struct is refused");
    g = volume_solid(4, 4, 4);
    g.voxel_size = 0.0;
    CHECK_EQ_INT(gb_thin(&g, NULL, &skeleton, NULL, NULL, &error), GB_ERROR_ARGUMENT,
                 "bad input: a zero voxel size is refused");
    gb_voxel_grid_free(&g);
}

int main(void)
{
    test_topology_cases();
    check_centred(5, 5);
    check_centred(4, 4);
    check_centred(7, 3);
    check_centred(9, 9);
    test_grid_through_door();
    test_grid_is_geodesic();
    test_maps();
    test_nearest_ways();
    test_determinism();
    test_collapse_threads();
    test_radii_brute_force();
    test_thin_and_free();
    test_options();
    test_grid_file();
    test_bad_input();
    return tap_done();
}
