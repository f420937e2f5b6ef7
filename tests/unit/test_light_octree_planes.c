/* test_light_octree_planes.c — surface interpolation in
 * gb_light_octree_irradiance (common/light_octree_shading.h): a leaf's
 * light weighs less the further the shaded point lies from the leaf's
 * plane (beyond the nearest leaf's), to MIN_SURFACE at SURFACE_REACH cell
 * edges, on hand-made octrees of depth 2 (4^3 cells of edge 1 over
 * the cube [0, 4]^3, every leaf lit by one VDL from straight above along
 * the leaf normal):
 *
 *  1. Two surfaces across a leaf boundary (issue 49's case of McGuire's
 *     light under the hidden ceiling): a floor at y = 1.9, 0.1 under the
 *     boundary between layers 1 and 2, whose leaves (layer 1) have
 *     irradiance 1, and another floor at y = 2.2 in layer 2 with
 *     irradiance 10. Trilinear alone gives 0.6 x 1 + 0.4 x 10 = 4.6 on the
 *     lower floor; the plane rule gives 1 within the other surface's
 *     MIN_SURFACE share, (0.6 + 0.4e-3 x 10) / (0.6 + 0.4e-3) = 1.006; an
 *     octree clustered for trilinear interpolation gives 4.6.
 *  2. Another orientation on the same plane: a wall's leaves in layer 2
 *     whose plane holds the lower floor's point, told apart by the normal
 *     term alone: 0.6 / (0.6 + 0.4e-3) where trilinear gives 0.6.
 *  3. One tilted plane through many leaves (y = 0.5 x + 1.2), irradiance
 *     linear in the leaf's centre: at points of the plane every leaf's
 *     plane holds the point (within the 16-bit rounding of normal and
 *     offset), so the result is plain trilinear interpolation, computed
 *     here by brute force over the leaves.
 *  4. A point no leaf holds: floors at y = 1.6 (layer 1, irradiance 1) and
 *     2.6 (layer 2, irradiance 10), a point between them at y = 2, 0.4 and
 *     0.6 cell edges from their planes (a window's reveal between the
 *     wall's leaves): plain trilinear, 0.5 x 1 + 0.5 x 10 = 5.5, where the
 *     surface factors alone (0.2 for the farther floor) would give 2.5.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "light_octree_shading.h"
#include "photon_map.h"
#include "tap.h"

#define DEPTH 2u
#define GRID (1u << DEPTH)
#define CELLS (GRID * GRID * GRID)

/* What a leaf holds: lit or not, its unit normal, the offset of its plane
 * from its centre along the normal (cell edges) and its irradiance. */
typedef struct leaf_spec {
    int lit;
    float normal[3];
    double offset;
    float irradiance;
} leaf_spec;

typedef struct hand_octree {
    gb_light_octree_node nodes[1 + 8];
    gb_light_octree_leaf leaves[CELLS];
    gb_light_octree_vdl vdls[CELLS];
    gb_light_octree octree;
} hand_octree;

/* Every cell a leaf (preorder: the root, then its 8 children in order,
 * each the parent of 8 leaves), leaf (x, y, z) as spec says, a lit one's
 * VDL from along its normal; checked as the reader checks it (what:
 * the test's name). The caller frees it. */
static hand_octree *hand_octree_make(leaf_spec (*spec)(const uint32_t cell[3]), const char *what)
{
    hand_octree *o = calloc(1, sizeof *o);
    uint32_t leaf = 0, next = 0;
    for (uint32_t c = 0; c < 8; ++c) {
        o->nodes[0].child[c] = 1 + c;
        for (uint32_t d = 0; d < 8; ++d) {
            uint32_t cell[3] = {2 * (c & 1) + (d & 1), 2 * (c >> 1 & 1) + (d >> 1 & 1),
                                2 * (c >> 2) + (d >> 2)};
            leaf_spec s = spec(cell);
            gb_light_octree_leaf *l = &o->leaves[leaf];
            l->normal = gb_photon_pack_direction(s.normal);
            l->plane = (int16_t)lrint(s.offset * GB_LIGHT_OCTREE_PLANE_ONE);
            l->cell = gb_light_octree_pack_cell(cell);
            l->first_vdl = next;
            l->vdl_count = s.lit ? 1 : 0;
            if (s.lit) {
                gb_light_octree_vdl *v = &o->vdls[next++];
                v->irradiance[0] = v->irradiance[1] = v->irradiance[2] = s.irradiance;
                v->direction = l->normal;
            }
            o->nodes[1 + c].child[d] = leaf++;
        }
    }
    o->octree.header = (gb_light_octree_header){
        .depth = DEPTH, .node_count = 9, .leaf_count = CELLS, .vdl_count = next,
        .origin = {0.0f, 0.0f, 0.0f}, .size = (float)GRID, .photon_count = 1,
        .emitted_count = 1, .knn = 1, .radius = 1.0f, .vdls_max = 1, .tolerance = 0.2f,
        .flattening = 0.5f, .interpolation = GB_LIGHT_OCTREE_SURFACE};
    o->octree.nodes = o->nodes;
    o->octree.leaves = o->leaves;
    o->octree.vdls = o->vdls;
    gb_error error;
    char text[96];
    snprintf(text, sizeof text, "%s: the hand-made octree passes the reader's checks", what);
    CHECK(gb_light_octree_check(&o->octree, what, &error) == GB_OK, text);
    return o;
}

/* ---- 1. two surfaces across a leaf boundary ------------------------------- */

#define LOWER_FLOOR 1.9
#define UPPER_FLOOR 2.2

static leaf_spec two_floors(const uint32_t cell[3])
{
    leaf_spec s = {cell[1] == 1 || cell[1] == 2, {0.0f, 1.0f, 0.0f}, 0.0, 1.0f};
    double floor = cell[1] == 1 ? LOWER_FLOOR : UPPER_FLOOR;
    s.offset = floor - (cell[1] + 0.5);
    s.irradiance = cell[1] == 1 ? 1.0f : 10.0f;
    return s;
}

static void test_two_surfaces(void)
{
    hand_octree *o = hand_octree_make(two_floors, "two floors");
    const float up[3] = {0.0f, 1.0f, 0.0f};
    const float lower[3] = {1.5f, (float)LOWER_FLOOR, 2.3f}, upper[3] = {2.2f, (float)UPPER_FLOOR, 1.5f};
    float e[3], f[3];
    gb_light_octree_irradiance(&o->octree, lower, up, up, e);
    gb_light_octree_irradiance(&o->octree, upper, up, up, f);
    double expected_lower = (0.6 + 0.4e-3 * 10.0) / (0.6 + 0.4e-3);
    /* the upper floor: 0.7 of layer 2 (the leaf centre 2.5 is 0.3 above),
     * layer 1's plane 0.3 below it too */
    double expected_upper = (0.7 * 10.0 + 0.3e-3 * 1.0) / (0.7 + 0.3e-3);
    printf("# lower floor %.6g (trilinear alone 4.6, expected %.6g); upper %.6g (trilinear "
           "alone 7.3, expected %.6g)\n", e[1], expected_lower, f[1], expected_upper);
    CHECK(fabs(e[1] - expected_lower) < 1e-3 * expected_lower,
          "the lower floor keeps its own light: the upper floor's leaves weigh MIN_SURFACE");
    CHECK(fabs(f[1] - expected_upper) < 1e-3 * expected_upper,
          "the upper floor keeps its own light: the lower floor's leaves weigh MIN_SURFACE");
    o->octree.header.interpolation = GB_LIGHT_OCTREE_TRILINEAR;
    gb_light_octree_irradiance(&o->octree, lower, up, up, e);
    CHECK(fabs(e[1] - 4.6) < 1e-5 * 4.6,
          "clustered for trilinear interpolation: 0.6 x 1 + 0.4 x 10, the paper's");
    free(o);
}

/* ---- 2. another orientation across a leaf boundary ------------------------ */

/* The lower floor of 1 in layer 1; in layer 2 leaves of a wall facing +x
 * whose plane, x = 1.5, holds the point below: only the normal term,
 * 1 - |n_leaf.ng|, tells them from the floor. Their VDL, along +x, gives
 * a floor point nothing, so trilinear alone reads 0.6 x 1 + 0.4 x 0. */
static leaf_spec floor_and_wall(const uint32_t cell[3])
{
    leaf_spec s = two_floors(cell);
    if (cell[1] == 2) {
        s.normal[0] = 1.0f, s.normal[1] = 0.0f;
        s.offset = 1.5 - (cell[0] + 0.5);
    }
    return s;
}

static void test_other_orientation(void)
{
    hand_octree *o = hand_octree_make(floor_and_wall, "floor and wall");
    const float up[3] = {0.0f, 1.0f, 0.0f}, point[3] = {1.5f, (float)LOWER_FLOOR, 2.3f};
    float e[3];
    gb_light_octree_irradiance(&o->octree, point, up, up, e);
    double expected = 0.6 / (0.6 + 0.4e-3);
    printf("# under the wall's leaves: %.6g (trilinear alone 0.6, expected %.6g)\n", e[1],
           expected);
    CHECK(fabs(e[1] - expected) < 1e-3 * expected,
          "leaves of another orientation on the point's plane weigh MIN_SURFACE");
    free(o);
}

/* ---- 3. one tilted plane -------------------------------------------------- */

/* y = SLOPE x + HEIGHT */
#define SLOPE 0.5
#define HEIGHT 1.2

static void plane_normal(float n[3])
{
    double length = sqrt(SLOPE * SLOPE + 1.0);
    n[0] = (float)(-SLOPE / length), n[1] = (float)(1.0 / length), n[2] = 0.0f;
}

/* The signed distance (cell edges) of the cell centre below the plane
 * along its normal: the offset of the plane from the centre. */
static double plane_offset(const uint32_t cell[3])
{
    double x = cell[0] + 0.5, y = cell[1] + 0.5;
    return (y - (SLOPE * x + HEIGHT)) * -1.0 / sqrt(SLOPE * SLOPE + 1.0);
}

static leaf_spec tilted_plane(const uint32_t cell[3])
{
    leaf_spec s = {0, {0}, 0.0, 0.0f};
    plane_normal(s.normal);
    s.offset = plane_offset(cell);
    s.lit = fabs(s.offset) < 0.9;
    s.irradiance = (float)(1.0 + 0.3 * cell[0] + 0.2 * cell[2]);
    return s;
}

/* Plain trilinear over the lit leaves, by brute force in double: each
 * leaf's tent weight max(Π (1 - |d|), 10^-6) for centres within one edge. */
static double trilinear(const hand_octree *o, const double x[3])
{
    double total = 0.0, weight = 0.0;
    for (uint32_t i = 0; i < CELLS; ++i) {
        const gb_light_octree_leaf *l = &o->leaves[i];
        uint32_t cell[3];
        gb_light_octree_leaf_cell(l, cell);
        double w = 1.0;
        int near = l->vdl_count > 0;
        for (int k = 0; k < 3; ++k) {
            double d = x[k] - (cell[k] + 0.5);
            near &= fabs(d) < 1.0;
            w *= 1.0 - fabs(d);
        }
        if (!near)
            continue;
        w = fmax(w, 1e-6);
        total += w * o->vdls[l->first_vdl].irradiance[0];
        weight += w;
    }
    return weight > 0.0 ? total / weight : 0.0;
}

static void test_tilted_plane(void)
{
    hand_octree *o = hand_octree_make(tilted_plane, "tilted plane");
    float n[3];
    plane_normal(n);
    double worst = 0.0;
    int points = 0;
    for (int a = 0; a < 20; ++a)
        for (int b = 0; b < 20; ++b) {
            double x[3] = {0.6 + 2.8 * a / 19.0, 0.0, 0.6 + 2.8 * b / 19.0};
            x[1] = SLOPE * x[0] + HEIGHT;
            if (x[1] < 0.6 || x[1] > 3.4)
                continue;
            float p[3] = {(float)x[0], (float)x[1], (float)x[2]}, e[3];
            gb_light_octree_irradiance(&o->octree, p, n, n, e);
            double expected = trilinear(o, x);
            worst = fmax(worst, fabs(e[0] - expected) / expected);
            ++points;
        }
    printf("# %d points of the plane: worst relative difference from trilinear %.2g\n", points,
           worst);
    CHECK(points > 100 && worst < 1e-3,
          "points of a tilted plane: every leaf's plane holds them, plain trilinear");
    free(o);
}

/* ---- 4. a point no leaf holds -------------------------------------------- */

static leaf_spec far_floors(const uint32_t cell[3])
{
    leaf_spec s = two_floors(cell);
    s.offset = (cell[1] == 1 ? 1.6 : 2.6) - (cell[1] + 0.5);
    return s;
}

static void test_no_leaf_holds(void)
{
    hand_octree *o = hand_octree_make(far_floors, "floors a cell apart");
    const float up[3] = {0.0f, 1.0f, 0.0f}, point[3] = {1.5f, 2.0f, 2.5f};
    float e[3];
    gb_light_octree_irradiance(&o->octree, point, up, up, e);
    printf("# between floors 0.4 and 0.6 away: %.6g (trilinear 5.5; the surface factors "
           "alone 2.5)\n", e[1]);
    CHECK(fabs(e[1] - 5.5) < 1e-5 * 5.5,
          "a point no leaf's plane holds, within a reach: plain trilinear");
    free(o);
}

int main(void)
{
    test_two_surfaces();
    test_other_orientation();
    test_tilted_plane();
    test_no_leaf_holds();
    return tap_done();
}
