/* adjacency.h — the neighbours of every node of an undirected graph given as
 * a sorted edge list (the skeleton's, the segmented skeleton's), in
 * compressed rows: the neighbours of n are neighbours[offsets[n] ..
 * offsets[n+1]), in increasing order, and edge_of[k] is the index of the
 * edge that slot k walks along.
 *
 * The caller owns the gb_adjacency and frees it with gb_adjacency_free (also
 * on a zeroed one).
 */
#ifndef GB_SEGMENT_ADJACENCY_H
#define GB_SEGMENT_ADJACENCY_H

#include <stdint.h>

#include "result.h"

typedef struct gb_adjacency {
    uint32_t node_count;
    uint32_t *offsets;          /* node_count + 1 */
    uint32_t *neighbours;       /* 2 * edge_count */
    uint32_t *edge_of;          /* 2 * edge_count */
} gb_adjacency;

/* edges: edge_count pairs (a, b), a < b < node_count, sorted by (a, b), no
 * duplicate (as gb_skeleton_validate checks); then each row is increasing. */
gb_result gb_adjacency_build(uint32_t node_count, const uint32_t *edges, uint32_t edge_count,
                             gb_adjacency *adjacency, gb_error *error);
void gb_adjacency_free(gb_adjacency *adjacency);

/* The number of neighbours of n. */
static inline uint32_t gb_degree(const gb_adjacency *adjacency, uint32_t n)
{
    return adjacency->offsets[n + 1] - adjacency->offsets[n];
}

#endif
