/* skeleton_graph.h — the thinned complex read as a graph: its points are the
 * nodes, its edges the edges (noel-biri-2014 §IV.A: "a graph embedded in 3D
 * space").
 *
 * A node sits at its point, a corner of the voxel grid: world_origin +
 * voxel_size * (x, y, z) for corner (x, y, z); its radius is the largest
 * exact distance to the surface of the empty voxels around that corner
 * (surface_distance.h). Nodes are
 * numbered in the order of their cells (x fastest, then y, then z), edges are
 * sorted by their first then second node: the graph depends only on the
 * complex.
 */
#ifndef GB_SKELETON_GRAPH_H
#define GB_SKELETON_GRAPH_H

#include <stdint.h>

#include "cubical_complex.h"
#include "empty_voxels.h"
#include "result.h"
#include "skeleton.h"
#include "voxel_grid.h"

/* Fills node_count, edge_count, nodes and edges of skeleton (the other
 * fields are left as they are) and returns in *node_cells (malloc'ed,
 * node_count entries, increasing) the cell of each node. Squares left in
 * the complex (none after a complete thinning) contribute their edges. */
/* grid gives the frame, empty its empty voxels. */
gb_result gb_skeleton_graph_build(const gb_cubical_complex *complex, const gb_voxel_grid *grid,
                                  const gb_empty_voxels *empty, gb_skeleton *skeleton,
                                  uint32_t **node_cells, gb_error *error);

#endif
