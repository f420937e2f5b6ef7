/* nearest_node.h — for every voxel, the skeleton node nearest to it through
 * the empty space (noel-biri-2014 §IV.A: "a 3D grid that gives for each
 * voxel the index of the nearest node of the skeleton (with respect to the
 * geometry of the empty space)").
 *
 * Geodesic distance: shortest paths of 26-connected steps between empty
 * voxels, each step weighted by its length (1, sqrt 2, sqrt 3 voxels, in
 * thousandths), from every node's corner to the centres of the empty voxels
 * around it (sqrt 3 / 2); ties broken towards the smaller node index, so the
 * result does not depend on the order of work. Paths never enter a non-empty
 * voxel. Computed by raster sweeps to the fixed point, or by multi-source
 * Dijkstra with a bucket queue (Dial) when the sweeps would take too many
 * passes (see nearest_node.c).
 *
 * A non-empty voxel with an empty voxel among its 26 neighbours takes the
 * node of the one whose distance plus step is smallest (same ties), so that
 * a surface point looked up slightly inside a wall still finds its node;
 * other voxels get -1, and so does an empty voxel farther than 16 777
 * voxels along the empty space from every node (a state is 6 bytes a cell:
 * 24 bits of distance, 24 of node). At most 16 777 214 nodes.
 */
#ifndef GB_NEAREST_NODE_H
#define GB_NEAREST_NODE_H

#include <stdint.h>

#include "cubical_complex.h"
#include "empty_voxels.h"
#include "progress.h"
#include "result.h"
#include "voxel_grid.h"

enum { GB_NEAREST_SWEEP_PAIRS = 8 };

typedef struct gb_nearest_options {
    int sweep_pairs;            /* raster sweep pairs before Dijkstra takes over
                                   (GB_NEAREST_SWEEP_PAIRS; 0: Dijkstra only) */
    int threads;                /* the sweeps' planes go to up to 8, Dijkstra's
                                   slabs along z to up to 64 */
    gb_progress_callback progress;  /* may be NULL */
    void *progress_user;
} gb_nearest_options;

/* grid gives the frame, empty its empty voxels (grid's surface is not read).
 * node_cells: the cell of each node in the lattice of complex (increasing).
 * On success *nearest is a malloc'ed array with one entry per voxel of grid
 * (x fastest), the caller's to free. The result does not depend on the
 * options (they only choose how it is computed). Only the frame of complex
 * is used (not its faces). */
gb_result gb_nearest_node(const gb_voxel_grid *grid, const gb_empty_voxels *empty,
                          const gb_cubical_complex *complex,
                          const uint32_t *node_cells, uint32_t node_count,
                          const gb_nearest_options *options, int32_t **nearest,
                          gb_error *error);

#endif
