/* distance.h — exact Euclidean distance transform of a voxel grid: for each
 * empty voxel, the distance from its centre to the centre of the nearest
 * surface voxel, in world units (grid->voxel_size per voxel); 0 on surface
 * voxels. Separable squared transform (Saito & Toriwaki 1994), each 1-D pass
 * by the lower envelope of parabolas (Felzenszwalb & Huttenlocher, "Distance
 * Transforms of Sampled Functions", 2012, algorithm 1). Squared distances in
 * voxel units are integers kept exactly in floats (below 2^24: sides up to
 * 2300 voxels), so the result is exact up to the final square root.
 *
 * Lines are split over options->thread_count threads; the result does not
 * depend on the thread count.
 */
#ifndef GB_VOXELIZE_DISTANCE_H
#define GB_VOXELIZE_DISTANCE_H

#include "result.h"
#include "voxel_grid.h"
#include "voxelize.h"

/* Fills grid->distance from grid->surface. Fails with GB_ERROR_INVALID when
 * the grid has no surface voxel, GB_ERROR_ARGUMENT when a side is too long
 * for exact squared distances. options may be NULL. */
gb_result gb_distance_transform(gb_voxel_grid *grid, const gb_voxelize_options *options,
                                gb_error *error);

#endif
