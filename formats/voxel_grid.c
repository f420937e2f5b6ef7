/* voxel_grid.c — allocation of the dense in-memory voxel grid (the OpenVDB
 * file functions are in voxel_grid_openvdb.cpp). */
#include "voxel_grid.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Number of voxels of size, or 0 when a side is not positive or the count
 * (times the bytes per voxel) would not fit in a size_t. */
static size_t voxel_count_of(const int32_t size[3])
{
    size_t count = 1;
    for (int axis = 0; axis < 3; ++axis) {
        if (size[axis] <= 0)
            return 0;
        if (count > SIZE_MAX / 8 / (size_t)size[axis])
            return 0;
        count *= (size_t)size[axis];
    }
    return count;
}

gb_result gb_voxel_grid_allocate(gb_voxel_grid *grid, const int32_t size[3], gb_error *error)
{
    size_t count = voxel_count_of(size);
    if (count == 0)
        return gb_fail(error, GB_ERROR_ARGUMENT, "voxel grid: bad size %d x %d x %d",
                       (int)size[0], (int)size[1], (int)size[2]);
    uint8_t *surface = calloc(count, sizeof *surface);
    float *distance = calloc(count, sizeof *distance);
    if (!surface || !distance) {
        free(surface);
        free(distance);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                       "voxel grid: out of memory for %d x %d x %d voxels",
                       (int)size[0], (int)size[1], (int)size[2]);
    }
    for (int axis = 0; axis < 3; ++axis)
        grid->size[axis] = size[axis];
    grid->surface = surface;
    grid->distance = distance;
    return GB_OK;
}

void gb_voxel_grid_free(gb_voxel_grid *grid)
{
    if (!grid)
        return;
    free(grid->surface);
    free(grid->distance);
    memset(grid, 0, sizeof *grid);
}
