/* coverage_nodes.h — coverage nodes (noel-biri-2014 §IV.B.1, Fig. 5): after
 * the curvature split, a node of a line that lies in none of the maximal
 * balls centred at the line's two extrema becomes a coverage node and splits
 * the line; recursively (lines.h, gb_lines_split), until every remaining
 * interior node is covered. This keeps lines of small balls from becoming a
 * single edge poorly covered by the balls at its ends.
 *
 * The measure: coverage(n) = min over the extrema E of |n - E| / maxball(E);
 * n is uncovered when it is above 1 (balls are closed), and the most
 * uncovered node splits first (ties: the smaller index). A node coincident
 * with an extremum is always covered; an extremum of maxball 0 covers only
 * the points at its centre.
 */
#ifndef GB_SEGMENT_COVERAGE_NODES_H
#define GB_SEGMENT_COVERAGE_NODES_H

#include <stdint.h>

#include "lines.h"
#include "result.h"
#include "skeleton.h"

double gb_coverage(const gb_skeleton *skeleton, uint32_t node, uint32_t first, uint32_t last);

/* The recursive split by coverage > 1 of every line; *count: nodes classified. */
gb_result gb_coverage_nodes(const gb_skeleton *skeleton, const gb_lines *lines,
                            uint8_t *node_class, uint32_t *count, gb_error *error);

#endif
