/* test_voxelize.c — voxelize (tools/voxelize): the exact triangle/box test
 * against an independent brute force, walls that must not leak, degenerate,
 * offset and tiny scenes,
 * determinism over thread counts. */
#include "tap.h"
#include "triangle_box_overlap.h"
#include "../../tools/voxelize/voxelize.h"
#include "voxel_grids.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ------------------------------------------------------------- helpers */

static uint64_t random_state = 0x853c49e6748fea9bull;

static uint32_t random_u32(void)
{
    random_state ^= random_state << 13;
    random_state ^= random_state >> 7;
    random_state ^= random_state << 17;
    return (uint32_t)(random_state >> 11);
}

static int random_int(int low, int high) /* inclusive */
{
    return low + (int)(random_u32() % (uint32_t)(high - low + 1));
}

static size_t voxel_count(const gb_voxel_grid *grid)
{
    return (size_t)grid->size[0] * grid->size[1] * grid->size[2];
}

static size_t count_surface(const gb_voxel_grid *grid)
{
    size_t count = 0;
    for (size_t index = 0; index < voxel_count(grid); ++index)
        count += grid->surface[index];
    return count;
}

/* A grid of size voxels of edge 1 with its corner at the world origin. */
static void make_unit_grid(gb_voxel_grid *grid, int nx, int ny, int nz)
{
    voxel_grid_make(grid, nx, ny, nz);
    grid->voxel_size = 1;
}

/* Voxelizes triangles into a unit grid whose voxel coordinates are world
 * coordinates. */
static gb_result mark_in_unit_grid(gb_voxel_grid *grid, const float *positions,
                                   uint32_t vertex_count, const uint32_t *indices,
                                   uint32_t triangle_count, int thread_count)
{
    static const double zero[3] = {0, 0, 0};
    gb_voxelize_options options = {0};
    options.thread_count = thread_count;
    gb_error error;
    return gb_voxelize_surface(grid, zero, zero, positions, vertex_count, indices,
                               triangle_count, &options, &error);
}

/* Voxels reachable from start through 6-connected non-surface voxels. */
static uint8_t *flood_fill(const gb_voxel_grid *grid, int start_i, int start_j, int start_k)
{
    size_t count = voxel_count(grid);
    uint8_t *reached = calloc(count, 1);
    size_t *queue = malloc(count * sizeof *queue);
    size_t head = 0, tail = 0, start = gb_voxel_index(grid, start_i, start_j, start_k);
    if (grid->surface[start])
        goto done;
    reached[start] = 1;
    queue[tail++] = start;
    while (head < tail) {
        size_t index = queue[head++];
        int i = (int)(index % grid->size[0]);
        int j = (int)(index / grid->size[0] % grid->size[1]);
        int k = (int)(index / grid->size[0] / grid->size[1]);
        static const int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                       {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (int s = 0; s < 6; ++s) {
            int a = i + step[s][0], b = j + step[s][1], c = k + step[s][2];
            if (a < 0 || b < 0 || c < 0 || a >= grid->size[0] || b >= grid->size[1]
                || c >= grid->size[2])
                continue;
            size_t next = gb_voxel_index(grid, a, b, c);
            if (!reached[next] && !grid->surface[next]) {
                reached[next] = 1;
                queue[tail++] = next;
            }
        }
    }
done:
    free(queue);
    return reached;
}

/* ------------------------------------------------------------- brute force */

/* Independent overlap test, exact on integer coordinates: the points of the
 * triangle are v0 + u e1 + w e2 with u, w >= 0 and u + w <= 1; those inside
 * the closed box lower..upper form a bounded convex polygon of the (u, w)
 * plane cut by 9 half-planes. It is non-empty iff one of its vertices exists:
 * a crossing of two constraint lines that satisfies all nine. Coordinates are
 * integers (a lattice of the caller's choosing); everything is exact in
 * int64 with the caller's small magnitudes. */
static int brute_force_overlap(const int64_t v[3][3], const int64_t lower[3],
                               const int64_t upper[3])
{
    int64_t a[9][2], b[9];
    int m = 0;
    for (int d = 0; d < 3; ++d) {
        int64_t e1 = v[1][d] - v[0][d], e2 = v[2][d] - v[0][d];
        a[m][0] = e1, a[m][1] = e2, b[m++] = upper[d] - v[0][d];
        a[m][0] = -e1, a[m][1] = -e2, b[m++] = v[0][d] - lower[d];
    }
    a[m][0] = -1, a[m][1] = 0, b[m++] = 0;
    a[m][0] = 0, a[m][1] = -1, b[m++] = 0;
    a[m][0] = 1, a[m][1] = 1, b[m++] = 1;
    for (int p = 0; p < 9; ++p)
        for (int q = p + 1; q < 9; ++q) {
            int64_t det = a[p][0] * a[q][1] - a[p][1] * a[q][0];
            if (det == 0)
                continue;
            int64_t u = b[p] * a[q][1] - b[q] * a[p][1];
            int64_t w = a[p][0] * b[q] - a[q][0] * b[p];
            if (det < 0)
                det = -det, u = -u, w = -w;
            int inside = 1;
            for (int r = 0; r < 9 && inside; ++r)
                inside = a[r][0] * u + a[r][1] * w <= b[r] * det;
            if (inside)
                return 1;
        }
    return 0;
}

/* ------------------------------------------------------------- the exact test */

static void test_overlap_cases(void)
{
    const double half[3] = {0.5, 0.5, 0.5}, centre[3] = {0.5, 0.5, 0.5};
    double inside[3][3] = {{0.2, 0.2, 0.5}, {0.8, 0.2, 0.5}, {0.5, 0.8, 0.5}};
    CHECK(gb_triangle_box_overlap(inside, centre, half), "triangle inside the box");
    double far[3][3] = {{3, 3, 3}, {4, 3, 3}, {3, 4, 3}};
    CHECK(!gb_triangle_box_overlap(far, centre, half), "triangle far away");
    double on_face[3][3] = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1}};
    CHECK(gb_triangle_box_overlap(on_face, centre, half), "wall lying in the top face touches");
    double above[3][3] = {{-1, -1, 1.0000001}, {3, -1, 1.0000001}, {-1, 3, 1.0000001}};
    CHECK(!gb_triangle_box_overlap(above, centre, half), "wall 1e-7 above the box does not");
    double corner[3][3] = {{1, 1, 1}, {2, 1, 1}, {1, 2, 2}};
    CHECK(gb_triangle_box_overlap(corner, centre, half), "vertex on the box corner touches");
    /* The plane x + y + z = 3 + 1e-9 passes 1e-9 beyond the corner (1,1,1),
     * with the triangle's bounds overlapping the box: only the normal axis
     * separates. */
    double beyond[3][3] = {{3 + 1e-9, -1, 1}, {-1, 3 + 1e-9, 1}, {-1, -1, 5 + 1e-9}};
    CHECK(!gb_triangle_box_overlap(beyond, centre, half), "plane just beyond the corner: apart");
    double through[3][3] = {{3, -1, 1}, {-1, 3, 1}, {-1, -1, 5}};
    CHECK(gb_triangle_box_overlap(through, centre, half), "plane through the corner: touches");
    /* Edge x + y = 2.0000001 at z = 0.5: only an edge cross product separates. */
    double edge_beyond[3][3] = {{2.0000001, 0, 0.5}, {0, 2.0000001, 0.5}, {5, 5, 0.5}};
    CHECK(!gb_triangle_box_overlap(edge_beyond, centre, half), "edge just beyond: apart");
    double segment[3][3] = {{-1, 0.5, 0.5}, {2, 0.5, 0.5}, {0.5, 0.5, 0.5}};
    CHECK(gb_triangle_box_overlap(segment, centre, half), "degenerate segment through the box");
    double segment_out[3][3] = {{-1, 1.5, 0.5}, {2, 1.5, 0.5}, {0.5, 1.5, 0.5}};
    CHECK(!gb_triangle_box_overlap(segment_out, centre, half), "degenerate segment beside it");
    double diagonal[3][3] = {{-1, 1.01, 0.5}, {1.01, -1, 0.5}, {1.01, -1, 0.5}};
    CHECK(gb_triangle_box_overlap(diagonal, centre, half), "diagonal segment across a corner");
    double diagonal_out[3][3] = {{-1, 3.01, 0.5}, {3.01, -1, 0.5}, {3.01, -1, 0.5}};
    CHECK(!gb_triangle_box_overlap(diagonal_out, centre, half),
          "diagonal segment past the corner (bounds overlap)");
    double point[3][3] = {{1, 0.3, 0}, {1, 0.3, 0}, {1, 0.3, 0}};
    CHECK(gb_triangle_box_overlap(point, centre, half), "point on an edge of the box");
    double point_out[3][3] = {{1, 0.3, -1e-12}, {1, 0.3, -1e-12}, {1, 0.3, -1e-12}};
    CHECK(!gb_triangle_box_overlap(point_out, centre, half), "point 1e-12 outside");
}

/* Random triangles on the 1/64 voxel lattice (exact in floats and doubles),
 * of several kinds that make exact ties frequent. */
enum { LATTICE = 64, TRIAL_GRID = 10 };

static void random_lattice_triangle(int kind, int64_t v[3][3])
{
    int step = kind == 1 ? LATTICE / 2 : kind == 2 ? LATTICE : 1;
    int extent = kind == 0 ? 3 : 8;
    int64_t base[3];
    for (int d = 0; d < 3; ++d)
        base[d] = random_int(LATTICE / 2, (TRIAL_GRID - extent) * LATTICE - LATTICE / 2);
    for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
            v[c][d] = base[d] / step * step + random_int(0, extent * LATTICE / step) * step;
    switch (kind) {
    case 3: /* axis-aligned wall on a voxel face */
        for (int c = 0; c < 3; ++c)
            v[c][2] = v[0][2] / LATTICE * LATTICE;
        break;
    case 4: /* sliver: two vertices one lattice step apart */
        for (int d = 0; d < 3; ++d)
            v[2][d] = v[1][d] + (d == 0);
        break;
    case 5: /* collinear: v2 is the midpoint of an even edge */
        for (int d = 0; d < 3; ++d) {
            v[1][d] = v[0][d] + (v[1][d] - v[0][d]) / 2 * 2;
            v[2][d] = (v[0][d] + v[1][d]) / 2;
        }
        break;
    case 6: /* a point */
        for (int d = 0; d < 3; ++d)
            v[1][d] = v[2][d] = v[0][d];
        break;
    case 7: /* wall on the 45 degree plane x - y = integer */
        for (int c = 0; c < 3; ++c)
            v[c][1] = v[c][0] - (v[0][0] - v[0][1]) / LATTICE * LATTICE;
        break;
    }
}

static int brute_force_voxel(const int64_t v[3][3], int i, int j, int k)
{
    int64_t lower[3] = {(int64_t)i * LATTICE, (int64_t)j * LATTICE, (int64_t)k * LATTICE};
    int64_t upper[3] = {lower[0] + LATTICE, lower[1] + LATTICE, lower[2] + LATTICE};
    return brute_force_overlap(v, lower, upper);
}

static void test_random_triangles_against_brute_force(void)
{
    enum { TRIALS = 3200, KINDS = 8 };
    gb_voxel_grid grid;
    make_unit_grid(&grid, TRIAL_GRID, TRIAL_GRID, TRIAL_GRID);
    long mismatches = 0, surface_voxels = 0, first_bad = -1;
    for (int trial = 0; trial < TRIALS; ++trial) {
        int64_t v[3][3];
        random_lattice_triangle(trial % KINDS, v);
        float positions[9];
        for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d)
                positions[3 * c + d] = (float)v[c][d] / LATTICE;
        uint32_t indices[3] = {0, 1, 2};
        memset(grid.surface, 0, voxel_count(&grid));
        mark_in_unit_grid(&grid, positions, 3, indices, 1, 1 + trial % 2);
        for (int k = 0; k < TRIAL_GRID; ++k)
            for (int j = 0; j < TRIAL_GRID; ++j)
                for (int i = 0; i < TRIAL_GRID; ++i) {
                    int expected = brute_force_voxel(v, i, j, k);
                    int got = grid.surface[gb_voxel_index(&grid, i, j, k)];
                    surface_voxels += got;
                    if (got != expected && first_bad < 0)
                        first_bad = trial;
                    mismatches += got != expected;
                }
    }
    CHECK_EQ_INT(mismatches, 0, "3200 random lattice triangles (8 kinds): voxelization equals "
                                "an exact brute force voxel for voxel");
    if (first_bad >= 0)
        printf("#   first mismatch in trial %ld\n", first_bad);
    CHECK(surface_voxels > 20000, "... on a fair number of surface voxels");
    gb_voxel_grid_free(&grid);
}

static void test_general_boxes_against_brute_force(void)
{
    long mismatches = 0, overlaps = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        int64_t v[3][3], lower[3], upper[3];
        random_lattice_triangle(trial % 8, v);
        double vertex[3][3], centre[3], half[3];
        for (int d = 0; d < 3; ++d) {
            lower[d] = v[trial % 3][d] + random_int(-2 * LATTICE, LATTICE / 2);
            upper[d] = lower[d] + 2 * random_int(0, 2 * LATTICE);
            centre[d] = (double)(lower[d] + upper[d]) / 2 / LATTICE;
            half[d] = (double)(upper[d] - lower[d]) / 2 / LATTICE;
        }
        for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d)
                vertex[c][d] = (double)v[c][d] / LATTICE;
        int expected = brute_force_overlap(v, lower, upper);
        overlaps += expected;
        mismatches += gb_triangle_box_overlap(vertex, centre, half) != expected;
    }
    CHECK_EQ_INT(mismatches, 0, "20000 random triangles against boxes of any shape, flat "
                                "boxes too: same answer as the brute force");
    CHECK(overlaps > 2000, "... with many overlaps among them");
}

/* ------------------------------------------------------------- walls */

/* A sheet through point with normal, cut into cells x cells quads (jittered
 * inside the plane), wide enough to cross a grid of side 24. */
static void make_sheet(const double point[3], const double normal[3], int cells,
                       float *positions, uint32_t *indices)
{
    double n[3], t1[3], t2[3];
    double length = sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    for (int d = 0; d < 3; ++d)
        n[d] = normal[d] / length;
    double helper[3] = {fabs(n[0]) < 0.6 ? 1 : 0, fabs(n[0]) < 0.6 ? 0 : 1, 0};
    t1[0] = n[1] * helper[2] - n[2] * helper[1];
    t1[1] = n[2] * helper[0] - n[0] * helper[2];
    t1[2] = n[0] * helper[1] - n[1] * helper[0];
    length = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    for (int d = 0; d < 3; ++d)
        t1[d] /= length;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
    int side = cells + 1;
    for (int b = 0; b < side; ++b)
        for (int a = 0; a < side; ++a) {
            int border = a == 0 || b == 0 || a == cells || b == cells;
            double s = -60 + 120.0 * a / cells, t = -60 + 120.0 * b / cells;
            if (!border) {
                s += (random_u32() % 1000) * 0.0007;
                t += (random_u32() % 1000) * 0.0007;
            }
            for (int d = 0; d < 3; ++d)
                positions[3 * (b * side + a) + d] = (float)(point[d] + s * t1[d] + t * t2[d]);
        }
    for (int b = 0; b < cells; ++b)
        for (int a = 0; a < cells; ++a) {
            uint32_t v00 = b * side + a, v10 = v00 + 1, v01 = v00 + side, v11 = v01 + 1;
            uint32_t *q = indices + 6 * (b * cells + a);
            q[0] = v00, q[1] = v10, q[2] = v11, q[3] = v00, q[4] = v11, q[5] = v01;
        }
}

static double signed_distance(const double point[3], const double normal[3], int i, int j,
                              int k)
{
    double length = sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    double centre[3] = {i + 0.5, j + 0.5, k + 0.5};
    double s = 0;
    for (int d = 0; d < 3; ++d)
        s += (centre[d] - point[d]) * normal[d] / length;
    return s;
}

/* Voxelizes the sheet into a 24^3 grid and floods from a voxel well below it:
 * returns the number of voxels reached well above it (a leak), and stores the
 * number of surface voxels. */
static long sheet_leak(const double point[3], const double normal[3], int cells,
                       size_t *surface_count)
{
    enum { SIDE = 24 };
    int side = cells + 1;
    float *positions = malloc(sizeof(float) * 3 * side * side);
    uint32_t *indices = malloc(sizeof(uint32_t) * 6 * cells * cells);
    make_sheet(point, normal, cells, positions, indices);
    gb_voxel_grid grid;
    make_unit_grid(&grid, SIDE, SIDE, SIDE);
    mark_in_unit_grid(&grid, positions, (uint32_t)(side * side), indices,
                      (uint32_t)(2 * cells * cells), 2);
    *surface_count = count_surface(&grid);
    int start[3] = {-1, -1, -1};
    for (int k = 0; k < SIDE && start[0] < 0; ++k)
        for (int j = 0; j < SIDE && start[0] < 0; ++j)
            for (int i = 0; i < SIDE && start[0] < 0; ++i)
                if (signed_distance(point, normal, i, j, k) < -3)
                    start[0] = i, start[1] = j, start[2] = k;
    uint8_t *reached = flood_fill(&grid, start[0], start[1], start[2]);
    long leaked = 0, below = 0;
    for (int k = 0; k < SIDE; ++k)
        for (int j = 0; j < SIDE; ++j)
            for (int i = 0; i < SIDE; ++i) {
                double s = signed_distance(point, normal, i, j, k);
                size_t index = gb_voxel_index(&grid, i, j, k);
                leaked += s > 1 && reached[index];
                below += s < -1 && reached[index];
            }
    if (below == 0)
        leaked = -1; /* the flood did not even start */
    free(reached);
    free(positions);
    free(indices);
    gb_voxel_grid_free(&grid);
    return leaked;
}

static void test_thin_walls(void)
{
    size_t surface;
    double on_face[3] = {12.3, 11.7, 12}, vertical[3] = {0, 0, 1};
    CHECK_EQ_INT(sheet_leak(on_face, vertical, 1, &surface), 0,
                 "wall on a voxel face (z = 12): no 6-connected leak");
    CHECK_EQ_INT(surface, 2 * 24 * 24, "... and it marks the two layers it touches");
    double mid[3] = {12.3, 11.7, 12.5};
    CHECK_EQ_INT(sheet_leak(mid, vertical, 1, &surface), 0, "wall inside a layer: no leak");
    CHECK_EQ_INT(surface, 24 * 24, "... and it marks exactly that layer");
    CHECK_EQ_INT(sheet_leak(mid, vertical, 12, &surface), 0,
                 "same wall in 288 jittered triangles: no leak");
    CHECK_EQ_INT(surface, 24 * 24, "... still exactly one layer");

    double centre[3] = {12.1, 11.9, 12.3};
    double diagonal[3] = {1, 0, 1};
    CHECK_EQ_INT(sheet_leak(centre, diagonal, 1, &surface), 0, "45 degree wall: no leak");
    CHECK_EQ_INT(sheet_leak(centre, diagonal, 12, &surface), 0,
                 "45 degree wall in 288 triangles: no leak");
    double on_edges[3] = {12, 12, 12};
    CHECK_EQ_INT(sheet_leak(on_edges, diagonal, 12, &surface), 0,
                 "45 degree wall through voxel edges: no leak");
    double body[3] = {1, 1, 1};
    CHECK_EQ_INT(sheet_leak(on_edges, body, 12, &surface), 0,
                 "wall x + y + z = 36 through voxel corners: no leak");
    double grazing[3] = {0.0175, 0.011, 1};
    CHECK_EQ_INT(sheet_leak(centre, grazing, 12, &surface), 0,
                 "wall at a grazing angle (1 degree off a voxel layer): no leak");
    double grazing_face[3] = {1e-4, 0, 1};
    CHECK_EQ_INT(sheet_leak(on_face, grazing_face, 1, &surface), 0,
                 "wall 1e-4 radian off a voxel face: no leak");
    double oblique[3] = {1, 2.5, -3.7};
    CHECK_EQ_INT(sheet_leak(centre, oblique, 12, &surface), 0, "oblique wall: no leak");
}

/* ------------------------------------------------------------- rooms */

/* The 12 triangles of the closed box lower..upper (outward order not
 * needed). */
static void make_box(const double lower[3], const double upper[3], float positions[24],
                     uint32_t indices[36])
{
    for (int c = 0; c < 8; ++c)
        for (int d = 0; d < 3; ++d)
            positions[3 * c + d] = (float)(c >> d & 1 ? upper[d] : lower[d]);
    static const uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                         {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    for (int f = 0; f < 6; ++f) {
        uint32_t *t = indices + 6 * f;
        t[0] = faces[f][0], t[1] = faces[f][1], t[2] = faces[f][2];
        t[3] = faces[f][0], t[4] = faces[f][2], t[5] = faces[f][3];
    }
}

static void test_room_on_voxel_faces(void)
{
    double lower[3] = {0, 0, 0}, upper[3] = {8, 8, 8};
    float positions[24];
    uint32_t indices[36];
    make_box(lower, upper, positions, indices);
    gb_voxelize_options options = {.resolution = 8};
    gb_voxel_grid grid = {0};
    gb_error error;
    CHECK_EQ_INT(gb_voxelize_triangles(positions, 8, indices, 12, &options, &grid, &error),
                 GB_OK, "voxelize a closed box of side 8 at resolution 8");
    CHECK_EQ_INT(grid.size[0], 12, "8 voxels + 2 x pad 2 along x");
    CHECK_EQ_INT(grid.size[2], 12, "... and along z");
    CHECK_NEAR(grid.voxel_size, 1.0, 0, "voxel size = longest side / resolution");
    CHECK_NEAR(grid.world_origin[1], -2.0, 0, "origin = bounds min - pad voxels");
    CHECK_EQ_INT(grid.resolution, 8, "resolution recorded");
    /* Walls on voxel faces touch the two layers around them: the shell
     * [1,10]^3 minus [3,8]^3. */
    CHECK_EQ_INT(count_surface(&grid), 10 * 10 * 10 - 6 * 6 * 6,
                 "walls on voxel faces mark the two layers around each face");
    uint8_t *reached = flood_fill(&grid, 0, 0, 0);
    CHECK(!reached[gb_voxel_index(&grid, 5, 5, 5)], "the inside is not reached from outside");
    CHECK(reached[gb_voxel_index(&grid, 11, 11, 11)], "the outside is connected");
    free(reached);
    gb_voxel_grid_free(&grid);
}

/* A rotated thin box (walls of zero thickness, rotated about two axes) must
 * keep its inside sealed. */
static void test_rotated_room(void)
{
    float positions[24];
    uint32_t indices[36];
    double lower[3] = {-1, -1, -1}, upper[3] = {1, 1, 1};
    make_box(lower, upper, positions, indices);
    double ca = cos(0.7), sa = sin(0.7), cb = cos(0.31), sb = sin(0.31);
    for (int c = 0; c < 8; ++c) {
        float *p = positions + 3 * c;
        double x = ca * p[0] - sa * p[1], y = sa * p[0] + ca * p[1], z = p[2];
        double y2 = cb * y - sb * z, z2 = sb * y + cb * z;
        p[0] = (float)x, p[1] = (float)y2, p[2] = (float)z2;
    }
    for (int resolution = 5; resolution <= 41; resolution += 4) {
        gb_voxelize_options options = {.resolution = (uint32_t)resolution, .pad = 1};
        gb_voxel_grid grid = {0};
        gb_error error;
        gb_voxelize_triangles(positions, 8, indices, 12, &options, &grid, &error);
        uint8_t *reached = flood_fill(&grid, 0, 0, 0);
        int sealed = !reached[gb_voxel_index(&grid, grid.size[0] / 2, grid.size[1] / 2,
                                             grid.size[2] / 2)];
        char what[96];
        snprintf(what, sizeof what, "rotated thin box at resolution %d: inside sealed",
                 resolution);
        CHECK(sealed, what);
        free(reached);
        gb_voxel_grid_free(&grid);
    }
}

/* ------------------------------------------------------------- odd scenes */

static void test_single_and_degenerate(void)
{
    float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t indices[3] = {0, 1, 2};
    gb_voxelize_options options = {.resolution = 16};
    gb_voxel_grid grid = {0};
    gb_error error;
    CHECK_EQ_INT(gb_voxelize_triangles(triangle, 3, indices, 1, &options, &grid, &error), GB_OK,
                 "a single triangle voxelizes");
    CHECK_EQ_INT(grid.size[0], 20, "16 + 2 pads along x");
    CHECK_EQ_INT(grid.size[2], 5, "flat axis: 1 voxel + 2 pads");
    /* In voxel units the triangle is x, y >= 2, x + y <= 20 at z = 2 (a face:
     * layers 1 and 2); voxel (i, j) touches it iff i >= 1, j >= 1 and
     * max(i, 2) + max(j, 2) <= 20. */
    long expected = 0, got = 0;
    for (int j = 0; j < grid.size[1]; ++j)
        for (int i = 0; i < grid.size[0]; ++i) {
            int touches = i >= 1 && j >= 1 && (i > 2 ? i : 2) + (j > 2 ? j : 2) <= 20;
            expected += 2 * touches;
            got += grid.surface[gb_voxel_index(&grid, i, j, 1)]
                   + grid.surface[gb_voxel_index(&grid, i, j, 2)];
        }
    CHECK_EQ_INT(got, expected, "its voxels: the closed right triangle on two layers");
    CHECK_EQ_INT(count_surface(&grid), expected, "and no others");
    gb_voxel_grid_free(&grid);

    float segment[9] = {0, 0, 0, 4, 4, 0, 2, 2, 0};
    CHECK_EQ_INT(gb_voxelize_triangles(segment, 3, indices, 1, &options, &grid, &error), GB_OK,
                 "a degenerate triangle (a diagonal segment) voxelizes");
    /* In voxel units the segment x = y from 2 to 18 at z = 2 (a face): voxels
     * (a, a) for a in 1..18 and, at each lattice corner it passes, (a, a+1)
     * and (a+1, a) for a in 1..17, on layers 1 and 2. */
    CHECK_EQ_INT(count_surface(&grid), 2 * (18 + 2 * 17), "... as the segment it is");
    gb_voxel_grid_free(&grid);

    float point[9] = {1, 2, 3, 1, 2, 3, 1, 2, 3};
    CHECK_EQ_INT(gb_voxelize_triangles(point, 3, indices, 1, &options, &grid, &error),
                 GB_ERROR_INVALID, "a scene that is a single point is refused");
    CHECK(strstr(error.message, "zero extent") != NULL, "... saying it has zero extent");

    float mixed[18] = {0, 0, 0, 1, 1, 1, 0.5f, 0.5f, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    uint32_t two[6] = {0, 1, 2, 3, 4, 5};
    CHECK_EQ_INT(gb_voxelize_triangles(mixed, 6, two, 2, &options, &grid, &error), GB_OK,
                 "a collinear triangle and a point triangle together voxelize");
    CHECK(count_surface(&grid) >= 16 && grid.surface[gb_voxel_index(&grid, 10, 10, 10)],
          "... along the space diagonal");
    gb_voxel_grid_free(&grid);
}

static void test_errors(void)
{
    float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t indices[3] = {0, 1, 2}, bad[3] = {0, 1, 3};
    gb_voxel_grid grid = {0};
    gb_error error;
    CHECK_EQ_INT(gb_voxelize_triangles(triangle, 3, bad, 1, NULL, &grid, &error),
                 GB_ERROR_INVALID, "index out of range refused");
    CHECK(strstr(error.message, "out of range") != NULL, "... saying so");
    CHECK_EQ_INT(gb_voxelize_triangles(triangle, 3, indices, 0, NULL, &grid, &error),
                 GB_ERROR_INVALID, "no triangle refused");
    float not_finite[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    CHECK_EQ_INT(gb_voxelize_triangles(not_finite, 3, indices, 1, NULL, &grid, &error),
                 GB_ERROR_INVALID, "NaN position refused");
    gb_voxelize_options options = {.resolution = 5000};
    CHECK_EQ_INT(gb_voxelize_triangles(triangle, 3, indices, 1, &options, &grid, &error),
                 GB_ERROR_ARGUMENT, "resolution above the maximum refused");
    options = (gb_voxelize_options){.pad = 65};
    CHECK_EQ_INT(gb_voxelize_triangles(triangle, 3, indices, 1, &options, &grid, &error),
                 GB_ERROR_ARGUMENT, "pad above the maximum refused");
    options = (gb_voxelize_options){.pad = GB_VOXELIZE_NO_PAD, .resolution = 4};
    CHECK_EQ_INT(gb_voxelize_triangles(triangle, 3, indices, 1, &options, &grid, &error),
                 GB_OK, "no pad is allowed");
    CHECK(grid.size[0] == 4 && grid.size[2] == 1 && count_surface(&grid) == 13,
          "... and gives the bare 4 x 4 x 1 grid with the 13 voxels i + j <= 4");
    gb_voxel_grid_free(&grid);
    CHECK(grid.surface == NULL, "nothing left allocated");
}

/* A closed tetrahedron-like soup with generic coordinates. */
static void make_generic_scene(float positions[18], uint32_t indices[24], double scale,
                               double offset)
{
    static const double corner[6][3] = {{0.11, 0.07, 0.03}, {0.93, 0.13, 0.21},
                                        {0.37, 0.89, 0.17}, {0.41, 0.33, 0.97},
                                        {0.52, 0.47, 0.45}, {0.05, 0.61, 0.72}};
    for (int c = 0; c < 6; ++c)
        for (int d = 0; d < 3; ++d)
            positions[3 * c + d] = (float)(corner[c][d] * scale + offset);
    static const uint32_t faces[24] = {0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3,
                                       4, 5, 0, 5, 2, 3, 4, 1, 5, 0, 3, 5};
    memcpy(indices, faces, sizeof faces);
}

static int same_surface(const gb_voxel_grid *a, const gb_voxel_grid *b)
{
    return memcmp(a->size, b->size, sizeof a->size) == 0
           && memcmp(a->surface, b->surface, voxel_count(a)) == 0;
}

static void test_offset_and_tiny_scenes(void)
{
    float positions[18];
    uint32_t indices[24];
    gb_voxelize_options options = {.resolution = 48};
    gb_error error;
    gb_voxel_grid unit = {0}, tiny = {0}, far = {0};
    make_generic_scene(positions, indices, 1.0, 0.0);
    gb_voxelize_triangles(positions, 6, indices, 8, &options, &unit, &error);
    /* 2^-13 = 1.22e-4: a power of two, so the floats scale exactly and the
     * voxels must be the very same. */
    double scale = ldexp(1.0, -13);
    make_generic_scene(positions, indices, scale, 0.0);
    CHECK_EQ_INT(gb_voxelize_triangles(positions, 6, indices, 8, &options, &tiny, &error), GB_OK,
                 "a scene of size 1.2e-4 voxelizes");
    CHECK(same_surface(&unit, &tiny), "... into the same voxels as at size 1");
    CHECK_NEAR(tiny.voxel_size / unit.voxel_size, scale, 0, "... with voxels 2^-13 as large");
    gb_voxel_grid_free(&tiny);
    /* 1e-4 exactly: floats round differently than at size 1, which may move
     * a voxel where the scene grazes one, no more. */
    make_generic_scene(positions, indices, 1e-4, 0.0);
    CHECK_EQ_INT(gb_voxelize_triangles(positions, 6, indices, 8, &options, &tiny, &error), GB_OK,
                 "a scene of size 1e-4 voxelizes");
    long differ = 0;
    for (size_t index = 0; index < voxel_count(&unit) && tiny.size[0] == unit.size[0]; ++index)
        differ += unit.surface[index] != tiny.surface[index];
    CHECK(tiny.size[0] == unit.size[0] && differ <= 4,
          "... into the voxels of size 1 but for a few grazed by rounding");
    gb_voxel_grid_free(&tiny);

    /* Offset by 1e6: floats there are 1/16 apart, so the scene is built on
     * that lattice: side 64 at resolution 64 has walls on voxel faces. */
    float room[24], moved[24];
    uint32_t box[36];
    double lower[3] = {0, 0, 0}, upper[3] = {64, 48, 40};
    make_box(lower, upper, room, box);
    for (int c = 0; c < 24; ++c)
        moved[c] = room[c] + 1e6f;
    gb_voxel_grid_free(&unit);
    options.resolution = 64;
    gb_voxelize_triangles(room, 8, box, 12, &options, &unit, &error);
    CHECK_EQ_INT(gb_voxelize_triangles(moved, 8, box, 12, &options, &far, &error), GB_OK,
                 "a room offset by 1e6 voxelizes");
    CHECK(same_surface(&unit, &far), "... into the same voxels as at the origin");
    CHECK_NEAR(far.world_origin[0], 1e6 - 2, 0, "... and its origin at 1e6 - pad");
    CHECK_EQ_INT(count_surface(&far), 66LL * 50 * 42 - 62LL * 46 * 38,
                 "... its walls on voxel faces each marking two layers");
    gb_voxel_grid_free(&unit);
    gb_voxel_grid_free(&far);
}

/* ------------------------------------------------------------- a scene */

/* A closed box room as a gb_scene built in memory, voxelized, written and
 * read back. */
static void test_scene_round_trip(void)
{
    gb_scene scene = {0};
    double lower[3] = {-1, 0, -1}, upper[3] = {3, 2.5, 1};
    scene.vertex_count = 8;
    scene.triangle_count = 12;
    scene.positions = malloc(24 * sizeof(float));
    scene.indices = malloc(36 * sizeof(uint32_t));
    scene.triangle_material = calloc(12, sizeof(uint32_t));
    scene.material_count = 1;
    scene.materials = calloc(1, sizeof(gb_material));
    scene.materials[0].Kd[0] = scene.materials[0].Kd[1] = scene.materials[0].Kd[2] = 0.5f;
    make_box(lower, upper, scene.positions, scene.indices);
    gb_error error;
    gb_result result = gb_scene_finish(&scene, &error);
    CHECK_EQ_INT(result, GB_OK, "a box room built in memory is a scene");
    gb_voxel_grid grid = {0}, read = {0};
    gb_voxelize_options options = {.resolution = 40};
    result = gb_voxelize_scene(&scene, &options, &grid, &error);
    CHECK_EQ_INT(result, GB_OK, "voxelize the scene");
    CHECK(grid.scene_hash == scene.hash && scene.hash != 0, "the grid carries the scene hash");
    CHECK(grid.size[0] == 44 && grid.size[1] == 29 && grid.size[2] == 24,
          "4 x 2.5 x 2 at resolution 40: 40 x 25 x 20 voxels + pads");
    char path[] = "/tmp/gb_test_voxelize_XXXXXX";
    int fd = mkstemp(path);
    if (fd >= 0)
        close(fd);
    CHECK_EQ_INT(gb_voxel_grid_write(path, &grid, &error), GB_OK, "write it");
    CHECK_EQ_INT(gb_voxel_grid_read(path, &read, &error), GB_OK, "read it back");
    CHECK(read.scene_hash == scene.hash && read.resolution == 40
              && read.voxel_size == grid.voxel_size && same_surface(&grid, &read),
          "the file keeps the hash, the frame and every surface voxel");
    unlink(path);
    gb_voxel_grid_free(&grid);
    gb_voxel_grid_free(&read);
    gb_scene_free(&scene);
}

/* ------------------------------------------------------------- threads, progress */

typedef struct progress_log {
    int calls, backwards, stop_after;
    double last;
} progress_log;

static int log_progress(void *user, double fraction)
{
    progress_log *log = user;
    log->backwards += fraction < log->last || fraction > 1;
    log->last = fraction;
    ++log->calls;
    return log->stop_after && log->calls >= log->stop_after;
}

static void test_threads_and_progress(void)
{
    enum { TRIANGLES = 3000 };
    float *positions = malloc(sizeof(float) * 9 * TRIANGLES);
    uint32_t *indices = malloc(sizeof(uint32_t) * 3 * TRIANGLES);
    for (int t = 0; t < TRIANGLES; ++t) {
        float base[3] = {(random_u32() % 10000) * 1e-4f, (random_u32() % 10000) * 1e-4f,
                         (random_u32() % 10000) * 1e-4f};
        for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d)
                positions[9 * t + 3 * c + d] = base[d] + (random_u32() % 1000) * 1e-4f;
        for (int c = 0; c < 3; ++c)
            indices[3 * t + c] = (uint32_t)(3 * t + c);
    }
    gb_voxel_grid one = {0}, two = {0}, five = {0};
    gb_error error;
    progress_log log = {0};
    gb_voxelize_options options = {.resolution = 70, .thread_count = 1};
    gb_voxelize_triangles(positions, 3 * TRIANGLES, indices, TRIANGLES, &options, &one, &error);
    options.thread_count = 2;
    options.progress = log_progress;
    options.progress_user = &log;
    gb_voxelize_triangles(positions, 3 * TRIANGLES, indices, TRIANGLES, &options, &two, &error);
    options.thread_count = 5;
    options.progress = NULL;
    gb_voxelize_triangles(positions, 3 * TRIANGLES, indices, TRIANGLES, &options, &five, &error);
    CHECK(same_surface(&one, &two) && same_surface(&one, &five),
          "surface is the same on 1, 2 and 5 threads");
    CHECK(log.calls > 2 && log.backwards == 0, "progress is reported and never goes back");
    CHECK(log.last == 1.0, "progress ends at 1");
    for (int stop_after = 1; stop_after < log.calls && stop_after <= 7; stop_after += 3) {
        progress_log stopping = {.stop_after = stop_after};
        gb_voxel_grid cancelled = {0};
        options.progress = log_progress;
        options.progress_user = &stopping;
        gb_result result = gb_voxelize_triangles(positions, 3 * TRIANGLES, indices, TRIANGLES,
                                                 &options, &cancelled, &error);
        char what[80];
        snprintf(what, sizeof what, "progress asking to stop at call %d cancels the work",
                 stop_after);
        CHECK(result == GB_ERROR_INTERRUPTED && strstr(error.message, "interrupted")
                  && cancelled.surface == NULL && stopping.calls == stop_after, what);
    }
    gb_voxel_grid_free(&one);
    gb_voxel_grid_free(&two);
    gb_voxel_grid_free(&five);
    free(positions);
    free(indices);
}

int main(void)
{
    test_overlap_cases();
    test_random_triangles_against_brute_force();
    test_general_boxes_against_brute_force();
    test_thin_walls();
    test_room_on_voxel_faces();
    test_rotated_room();
    test_single_and_degenerate();
    test_errors();
    test_offset_and_tiny_scenes();
    test_scene_round_trip();
    test_threads_and_progress();
    return tap_done();
}
