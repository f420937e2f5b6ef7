/* coverage_nodes.c — nodes outside the maximal balls of their line's extrema. */
#include "coverage_nodes.h"

#include <math.h>

#include "segmentation.h"

double gb_coverage(const gb_skeleton *s, uint32_t node, uint32_t first, uint32_t last)
{
    double to_first = gb_line_ratio(gb_node_distance(s, node, first), s->nodes[first].radius);
    double to_last = gb_line_ratio(gb_node_distance(s, node, last), s->nodes[last].radius);
    return fmin(to_first, to_last);
}

gb_result gb_coverage_nodes(const gb_skeleton *skeleton, const gb_lines *lines,
                            uint8_t *node_class, uint32_t *count, gb_error *error)
{
    return gb_lines_split(skeleton, lines, gb_coverage, GB_NODE_COVERAGE, node_class, count,
                          error);
}
