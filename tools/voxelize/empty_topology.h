/* empty_topology.h — the topology of a grid's empty space, in two numbers
 * that voxelize -r auto compares across resolutions (auto_resolution.h):
 *   components  the 6-connected components of the empty voxels (b0: the
 *               rooms an opening joins or not);
 *   euler       the Euler characteristic of the cubical complex on the
 *               empty voxels' centres: V - E + F - C, with E the pairs of
 *               6-adjacent empty voxels, F the 2 x 2 squares and C the
 *               2 x 2 x 2 blocks of empty voxels. It is b0 - b1 + b2, so
 *               with b0 fixed a change says a loop (two doors between two
 *               rooms) or a cavity opened or closed.
 * The caller owns the grid; only grid->surface is read (0 empty). */
#ifndef GB_EMPTY_TOPOLOGY_H
#define GB_EMPTY_TOPOLOGY_H

#include <stdint.h>

#include "result.h"
#include "voxel_grid.h"

typedef struct gb_empty_topology {
    uint64_t components;
    int64_t euler;
} gb_empty_topology;

/* GB_ERROR_OUT_OF_MEMORY when the search's queue cannot grow. */
gb_result gb_empty_topology_count(const gb_voxel_grid *grid, gb_empty_topology *topology,
                                  gb_error *error);

#endif
