/* topology_nodes.h — the first classification of noel-biri-2014 §IV.B.1:
 * "each node of degree different than two is classified as a topology node"
 * (isolated nodes, ends and junctions).
 *
 * Open case decided here: a ring, a connected component whose nodes all have
 * degree two, has no topology node, so no line could start on it. Its node of
 * largest maxball (ties: the smallest index) becomes its topology node, its
 * anchor; the ring is then one line from the anchor back to itself, which
 * lines.h opens like any line whose two extremities are the same node.
 */
#ifndef GB_SEGMENT_TOPOLOGY_NODES_H
#define GB_SEGMENT_TOPOLOGY_NODES_H

#include <stdint.h>

#include "adjacency.h"
#include "result.h"
#include "skeleton.h"

/* node_class: one per skeleton node, all GB_NODE_UNCLASSIFIED on entry;
 * topology nodes and ring anchors get GB_NODE_TOPOLOGY. *rings: how many
 * rings were anchored. */
gb_result gb_topology_nodes(const gb_skeleton *skeleton, const gb_adjacency *adjacency,
                            uint8_t *node_class, uint32_t *rings, gb_error *error);

#endif
