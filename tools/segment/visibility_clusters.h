/* visibility_clusters.h — visibility clusters (noel-biri-2014 §IV.B.2): sets
 * of segmented nodes whose maximal balls make a quasi-convex region, grown
 * greedily:
 *
 *   sort the nodes by maxball, largest first;
 *   for each node n in that order not yet clustered: a new cluster C, push n;
 *     while the stack is not empty: pop m, add it to C, then push
 *       - each neighbour of m that is not a curvature node and whose maxball
 *         differs by no more than alpha % from the largest maxball in C:
 *         |maxball(x) - max_C| <= alpha / 100 * max_C;
 *       - each node inside the maximal ball of m (|x - m| <= maxball(m))
 *         reachable from m through nodes inside that ball (a breadth-first
 *         traversal from m), whatever its class.
 *
 * Decided here: nodes already in another cluster are neither pushed nor
 * traversed, so every cluster is connected in the segmented skeleton, as the
 * paper states; a node is put in C when it is pushed, so it is pushed once;
 * equal maxballs are ordered by the smaller index, neighbours in increasing
 * index, so clusters are numbered in the order they are created and the
 * result is deterministic. alpha = 0 joins neighbours of exactly the
 * cluster's largest maxball only (balls still merge); alpha = 100 joins
 * every neighbour that is not a curvature node.
 */
#ifndef GB_SEGMENT_VISIBILITY_CLUSTERS_H
#define GB_SEGMENT_VISIBILITY_CLUSTERS_H

#include <stdint.h>

#include "result.h"
#include "segmentation.h"

/* Reads out's nodes and edges; fills out->cluster and out->cluster_count.
 * alpha: percent, in [0, 100]. */
gb_result gb_visibility_clusters(gb_segmentation *out, double alpha, gb_error *error);

#endif
