/* voxel_grids.h — voxel grids made in memory for the unit tests of the
 * voxel file and of voxelize:
 *
 *   voxel_grid_make(&grid, 9, 5, 4);        // zeroed but its size; aborts
 *   voxel_grid_fill(&grid, surface);        // surface(i, j, k): 1 or 0
 *   ...
 *   gb_voxel_grid_free(&grid);              // the caller's
 *
 * A grid that cannot be allocated is the test's own failure: it aborts.
 */
#ifndef GB_VOXEL_GRIDS_H
#define GB_VOXEL_GRIDS_H

#include <stdlib.h>
#include <string.h>

#include "voxel_grid.h"

static inline void voxel_grid_make(gb_voxel_grid *grid, int nx, int ny, int nz)
{
    memset(grid, 0, sizeof *grid);
    int32_t size[3] = {nx, ny, nz};
    gb_error error;
    if (gb_voxel_grid_allocate(grid, size, &error) != GB_OK)
        abort();
}

/* Every voxel's surface flag, surface(i, j, k). */
static inline void voxel_grid_fill(gb_voxel_grid *grid, int (*surface)(int i, int j, int k))
{
    for (int k = 0; k < grid->size[2]; ++k)
        for (int j = 0; j < grid->size[1]; ++j)
            for (int i = 0; i < grid->size[0]; ++i) {
                size_t index = gb_voxel_index(grid, i, j, k);
                grid->surface[index] = (uint8_t)(surface(i, j, k) != 0);
            }
}

#endif
