/* segmented_skeleton.h — the segmented skeleton of noel-biri-2014 §IV.B.1:
 * "we get a new segmented skeleton by removing all unclassified nodes", each
 * remaining line becoming an edge between its two extrema, and "each node of
 * the original skeleton can be associated with a node of the segmented
 * skeleton by taking the nearest extrema on the line containing that node".
 *
 * Decided here: segmented nodes are the classified nodes in increasing
 * skeleton index; "nearest" is the Euclidean distance to the extremum
 * (ties: the extremum of smaller index); segmented edges are the distinct
 * pairs of extrema of the lines, sorted — two lines between the same two
 * nodes (a cycle shorter than its balls) give one edge, and no edge joins a
 * node to itself (loops were opened, curvature_nodes.h).
 */
#ifndef GB_SEGMENT_SEGMENTED_SKELETON_H
#define GB_SEGMENT_SEGMENTED_SKELETON_H

#include <stdint.h>

#include "lines.h"
#include "result.h"
#include "segmentation.h"
#include "skeleton.h"

/* Fills nodes, edges, node_map, their counts and the voxel frame and scene
 * hash of out (clusters and gates are left for the next steps). lines: the
 * lines between the classified nodes of node_class. */
gb_result gb_segmented_skeleton(const gb_skeleton *skeleton, const uint8_t *node_class,
                                const gb_lines *lines, gb_segmentation *out, gb_error *error);

#endif
