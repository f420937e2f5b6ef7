/* curvature_nodes.h — curvature nodes (noel-biri-2014 §IV.B.1, Fig. 4):
 *
 *     curv(n) = dist(n, L1Lk) / maxball(n)
 *
 * A node with curv > 1 is so far from the straight line L1Lk that the line
 * misses its maximal ball: replacing the line by an edge would likely cross
 * a wall. Such a node becomes a curvature node and splits its line; the two
 * new lines are examined recursively (lines.h, gb_lines_split).
 *
 * Decided here: dist(n, L1Lk) is the distance to the segment [L1, Lk], the
 * edge that would replace the line. It equals the distance to the infinite
 * line whenever n projects between L1 and Lk, and it catches lines that go
 * out beyond an extremum and come back. When L1 and Lk are the same node or
 * coincide, it is the distance to that point. dist 0 gives curv 0; maxball 0
 * with dist > 0 gives an infinite curv.
 *
 * Loops (a line whose two extrema are the same node, including a ring from
 * its anchor) must not become an edge from a node to itself: before the
 * recursion, every loop's interior node of largest curv (to the point L1,
 * ties to the smaller index) is classified — a curvature node when its curv
 * is above 1, else a topology node, kept only to keep the cycle.
 */
#ifndef GB_SEGMENT_CURVATURE_NODES_H
#define GB_SEGMENT_CURVATURE_NODES_H

#include <stdint.h>

#include "lines.h"
#include "result.h"
#include "skeleton.h"

double gb_curv(const gb_skeleton *skeleton, uint32_t node, uint32_t first, uint32_t last);

/* Classifies one interior node of every loop line as above; returns how many
 * loops were opened (topology or curvature nodes added). */
uint32_t gb_open_loops(const gb_skeleton *skeleton, const gb_lines *lines, uint8_t *node_class);

/* The recursive split by curv > 1 of every line; *count: nodes classified. */
gb_result gb_curvature_nodes(const gb_skeleton *skeleton, const gb_lines *lines,
                             uint8_t *node_class, uint32_t *count, gb_error *error);

#endif
