/* test_empty_topology.c — the empty space's components and Euler
 * characteristic (tools/voxelize/empty_topology.h) on hand-made grids whose
 * topology is known: a block (a ball: 1, 1), a hollow box (inside and the
 * shell around it: 2, 1 + 2) and the same with a door, a ring (1, 0), two
 * voxels touching at a corner (2, 2). */
#include "tap.h"
#include "tap_printf.h"
#include "../../tools/voxelize/empty_topology.h"
#include "../../tools/voxelize/voxelize.h"

#include <stdlib.h>
#include <string.h>

static int make_grid(gb_voxel_grid *grid, int n, uint8_t fill)
{
    memset(grid, 0, sizeof *grid);
    grid->size[0] = grid->size[1] = grid->size[2] = n;
    grid->voxel_size = 1.0;
    grid->surface = malloc((size_t)n * n * n);
    if (grid->surface)
        memset(grid->surface, fill, (size_t)n * n * n);
    return grid->surface != NULL;
}

static void set(gb_voxel_grid *grid, int i, int j, int k, uint8_t value)
{
    grid->surface[gb_voxel_index(grid, i, j, k)] = value;
}

/* value on the border of the box lo..hi (included): the voxels with a
 * coordinate at lo or hi along an axis where the box is more than one voxel
 * thick (a flat box's border is its rim). */
static void set_border(gb_voxel_grid *grid, const int lo[3], const int hi[3], uint8_t value)
{
    for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i) {
                const int c[3] = {i, j, k};
                int border = 0;
                for (int a = 0; a < 3; ++a)
                    border |= lo[a] < hi[a] && (c[a] == lo[a] || c[a] == hi[a]);
                if (border)
                    set(grid, i, j, k, value);
            }
}

static void expect(const gb_voxel_grid *grid, uint64_t components, int64_t euler,
                   const char *name)
{
    gb_empty_topology t;
    gb_error error;
    if (!CHECKF(gb_empty_topology_count(grid, &t, &error) == GB_OK, "%s: counted", name))
        return;
    CHECK_EQ_INTF(t.components, components, "%s: %llu components", name,
                  (unsigned long long)components);
    CHECK_EQ_INTF(t.euler, euler, "%s: Euler characteristic %lld", name, (long long)euler);
}

static void test_shapes(void)
{
    gb_voxel_grid g;
    if (!make_grid(&g, 6, 0))
        return;
    expect(&g, 1, 1, "all empty");
    free(g.surface);

    /* The shell of [2, 6]^3 in a 9^3 grid: a 3^3 ball inside, and outside
     * the grid's border region around it (a thick sphere: 2). */
    if (!make_grid(&g, 9, 0))
        return;
    set_border(&g, (const int[3]){2, 2, 2}, (const int[3]){6, 6, 6}, 1);
    expect(&g, 2, 3, "hollow box");
    /* A one-voxel hole through a face joins inside and outside by an arc
     * (one vertex, two edges, no square): one component, 1 + 2 - 1. */
    set(&g, 6, 4, 4, 0);
    expect(&g, 1, 2, "hollow box with a door");
    free(g.surface);

    /* A square ring of empty voxels in solid surface: a circle. */
    if (!make_grid(&g, 6, 1))
        return;
    set_border(&g, (const int[3]){1, 1, 2}, (const int[3]){4, 4, 2}, 0);
    expect(&g, 1, 0, "ring");
    free(g.surface);

    /* Two voxels touching only at a corner: 6-connectivity keeps them apart. */
    if (!make_grid(&g, 4, 1))
        return;
    set(&g, 1, 1, 1, 0);
    set(&g, 2, 2, 2, 0);
    expect(&g, 2, 2, "two voxels at a corner");
    free(g.surface);
}

int main(void)
{
    test_shapes();
    return tap_done();
}
