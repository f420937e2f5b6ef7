/* empty_voxels.c — see empty_voxels.h. */
#include "empty_voxels.h"

#include <stdlib.h>

gb_result gb_empty_voxels_of(const gb_voxel_grid *grid, gb_empty_voxels *empty,
                             gb_error *error)
{
    size_t count = (size_t)grid->size[0] * grid->size[1] * grid->size[2];
    empty->bits = calloc(count / 64 + 1, sizeof *empty->bits);
    if (!empty->bits)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %zu voxels", count);
    for (size_t v = 0; v < count; ++v)
        if (!grid->surface[v])
            empty->bits[v / 64] |= (uint64_t)1 << (v % 64);
    return GB_OK;
}

void gb_empty_voxels_free(gb_empty_voxels *empty)
{
    free(empty->bits);
    empty->bits = NULL;
}
