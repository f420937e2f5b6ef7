/* empty_voxels.h — which voxels of a grid are empty, one bit a voxel: what
 * thin keeps of the voxel grid's surface bytes once its cubical complex is
 * built (an eighth of them), for the node radii and the nearest-node grid,
 * so that gb_thin_and_free can give the surface back while it thins.
 *
 * The caller owns the gb_empty_voxels and frees it with
 * gb_empty_voxels_free.
 */
#ifndef GB_EMPTY_VOXELS_H
#define GB_EMPTY_VOXELS_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"
#include "voxel_grid.h"

typedef struct gb_empty_voxels {
    uint64_t *bits;             /* bit v % 64 of word v / 64: voxel v (dense index) empty */
} gb_empty_voxels;

/* The empty voxels (surface == 0) of grid. */
gb_result gb_empty_voxels_of(const gb_voxel_grid *grid, gb_empty_voxels *empty,
                             gb_error *error);
void gb_empty_voxels_free(gb_empty_voxels *empty);

static inline int gb_voxel_is_empty(const gb_empty_voxels *empty, size_t voxel)
{
    return (int)(empty->bits[voxel / 64] >> (voxel % 64) & 1);
}

#endif
