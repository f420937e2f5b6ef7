/* visibility_gates.h — visibility gates (noel-biri-2014 §IV.C): for each
 * edge (n1, n2) of the segmented skeleton whose nodes are in different
 * visibility clusters, a disk "at the middle of the edge (n1, n2), orthogonal
 * to it, with radius min(maxball(n1), maxball(n2))".
 *
 * Gates come in the order of their edges; the normal points from the edge's
 * first (smaller) node to its second, and clusters[0] is the first node's
 * cluster. A zero-length edge never needs a gate: coincident neighbours lie
 * in each other's maximal ball, so the clustering puts them together
 * (visibility_clusters.h); finding one anyway is an internal error.
 */
#ifndef GB_SEGMENT_VISIBILITY_GATES_H
#define GB_SEGMENT_VISIBILITY_GATES_H

#include "result.h"
#include "segmentation.h"

/* Reads out's nodes, edges and clusters; fills out->gates and gate_count. */
gb_result gb_visibility_gates(gb_segmentation *out, gb_error *error);

#endif
