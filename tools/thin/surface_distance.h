/* surface_distance.h — the exact Euclidean distance from an empty voxel to
 * the nearest surface voxel (centre to centre, world units), for the few
 * voxels thin needs it of: those around its skeleton's nodes, whose largest
 * is the node's maximal-ball radius (skeleton_graph.h). The voxel file
 * stores no distance (formats/FORMATS.md, "Voxel file"), and a whole
 * distance transform would cost a float per voxel for a few thousand reads.
 *
 * A search pruned by bounds, over the empty-voxel bits thin already holds
 * (empty_voxels.h; a surface voxel is a voxel of the grid that is not
 * empty): the grid is cut into blocks of 8^3 voxels and super-blocks of
 * 64^3, each marked when it holds a surface voxel. From the query's block
 * outwards, shell by shell (Chebyshev rings of blocks), a marked block (in a
 * marked super-block) nearer than the best squared distance found so far is
 * scanned, a row of 8 voxels at a time; the search stops at the first shell
 * whose lower bound ((R - 1) * 8 + 1)^2 is not below the best. The best
 * starts just above the bound the previous query gives by the triangle
 * inequality (queries come in groups around a node's corner). Every surface
 * voxel that could be nearer is examined: the answer is the minimum over
 * all of them, on integers (squared voxel counts), then voxel_size *
 * sqrt(n) as a float: the value an exact distance transform gives.
 *
 *   gb_surface_distance index;
 *   gb_surface_distance_build(&index, grid, empty, &error);  // grid: its frame
 *   gb_surface_distances(&index, voxels, count, distances);
 *   gb_surface_distance_free(&index);
 *
 * The caller owns index (and keeps empty alive while it is used).
 */
#ifndef GB_SURFACE_DISTANCE_H
#define GB_SURFACE_DISTANCE_H

#include <stddef.h>
#include <stdint.h>

#include "empty_voxels.h"
#include "result.h"
#include "voxel_grid.h"

typedef struct gb_surface_distance {
    int32_t size[3];            /* the grid's voxels */
    int32_t blocks[3];          /* 8^3 blocks along each axis */
    int32_t supers[3];          /* 64^3 super-blocks along each axis */
    uint8_t *block_marked;      /* 1: the block holds a surface voxel */
    uint8_t *super_marked;      /* 1: the super-block holds a surface voxel */
    double voxel_size;
    const gb_empty_voxels *empty;
} gb_surface_distance;

gb_result gb_surface_distance_build(gb_surface_distance *index, const gb_voxel_grid *grid,
                                    const gb_empty_voxels *empty, gb_error *error);
void gb_surface_distance_free(gb_surface_distance *index);

/* distances[n]: the distance of voxel voxels[n] (a dense index) to the
 * nearest surface voxel, 0 on a surface voxel; in a grid with no surface
 * voxel (never one voxelize writes), to the nearest voxel outside the
 * grid, which thin counts as not empty. */
void gb_surface_distances(const gb_surface_distance *index, const size_t *voxels, size_t count,
                          float *distances);

#endif
