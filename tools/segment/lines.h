/* lines.h — the lines of noel-biri-2014 §IV.B.1: maximal paths of the
 * skeleton whose interior nodes are unclassified (degree two) and whose two
 * extrema L1 and Lk are classified nodes; and the recursive split of lines
 * that curvature_nodes.h and coverage_nodes.h share.
 *
 * A line is stored as its whole path, extrema included: L1, n1 .. nm, Lk.
 * A line may have no interior node (an edge between two classified nodes),
 * and its two extrema may be the same node (a loop: a cycle through one
 * classified node, or a ring through its anchor).
 *
 * Split (the paper's recursion, made iterative): in a piece (L1 .. Lk) of a
 * line, the interior node of largest measure, if that measure is > 1, is
 * classified; the pieces (L1 .. n) and (n .. Lk) are then examined the same
 * way until no interior node has a measure above 1. Ties between interior
 * nodes go to the smaller node index, so the result does not depend on the
 * direction a line was walked.
 *
 * The caller owns the gb_lines and frees it with gb_lines_free.
 */
#ifndef GB_SEGMENT_LINES_H
#define GB_SEGMENT_LINES_H

#include <math.h>
#include <stdint.h>

#include "adjacency.h"
#include "result.h"
#include "skeleton.h"

typedef struct gb_lines {
    uint32_t count;
    uint32_t *offsets;          /* count + 1: line i is nodes[offsets[i] .. offsets[i+1]) */
    uint32_t *nodes;            /* the paths, extrema included */
    uint32_t longest;           /* nodes in the longest path */
} gb_lines;

/* Every edge of the skeleton lies on exactly one line. Lines come in the
 * order of their first extremum, then of its neighbour along the line.
 * Precondition: every unclassified node (node_class 0) has degree two and
 * lies on a path between classified nodes (topology_nodes.h anchors rings);
 * otherwise GB_ERROR_INVALID. */
gb_result gb_lines_extract(const gb_adjacency *adjacency, const uint8_t *node_class,
                           gb_lines *lines, gb_error *error);
void gb_lines_free(gb_lines *lines);

/* How far an interior node is from what the piece (first .. last) would be
 * replaced with; above 1 classifies it. */
typedef double (*gb_line_measure)(const gb_skeleton *skeleton, uint32_t node, uint32_t first,
                                  uint32_t last);

/* Splits every line as above, giving the classified nodes new_class.
 * *classified counts them. */
gb_result gb_lines_split(const gb_skeleton *skeleton, const gb_lines *lines,
                         gb_line_measure measure, uint8_t new_class, uint8_t *node_class,
                         uint32_t *classified, gb_error *error);

/* length / maxball, the ratio both measures use: 0 when length is 0 (a node
 * on the line, or coincident with the extremum), infinite when only the
 * radius is 0. */
static inline double gb_line_ratio(double length, double maxball)
{
    if (!(length > 0.0))
        return 0.0;
    return maxball > 0.0 ? length / maxball : INFINITY;
}

/* Euclidean distance between two skeleton nodes, in double. */
static inline double gb_node_distance(const gb_skeleton *s, uint32_t a, uint32_t b)
{
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        double d = (double)s->nodes[a].position[i] - (double)s->nodes[b].position[i];
        d2 += d * d;
    }
    return sqrt(d2);
}

#endif
