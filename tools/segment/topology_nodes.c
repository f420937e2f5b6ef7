/* topology_nodes.c — topology nodes (degree != 2) and one anchor per ring. */
#include "topology_nodes.h"

#include <stdlib.h>

#include "segmentation.h"

/* Larger maxball first, then the smaller index. */
static int better_anchor(const gb_skeleton *s, uint32_t candidate, uint32_t anchor)
{
    float rc = s->nodes[candidate].radius, ra = s->nodes[anchor].radius;
    return rc > ra || (rc == ra && candidate < anchor);
}

/* Visits the component of degree-2 node start (marking seen); returns its
 * anchor when it is a ring, or UINT32_MAX when it reaches another degree. */
static uint32_t ring_anchor(const gb_skeleton *s, const gb_adjacency *g, uint32_t start,
                            uint8_t *seen, uint32_t *stack)
{
    uint32_t top = 0, anchor = start;
    int ring = 1;
    stack[top++] = start;
    seen[start] = 1;
    while (top) {
        uint32_t n = stack[--top];
        if (better_anchor(s, n, anchor))
            anchor = n;
        for (uint32_t k = g->offsets[n]; k < g->offsets[n + 1]; ++k) {
            uint32_t m = g->neighbours[k];
            if (gb_degree(g, m) != 2)
                ring = 0;
            else if (!seen[m]) {
                seen[m] = 1;
                stack[top++] = m;
            }
        }
    }
    return ring ? anchor : UINT32_MAX;
}

gb_result gb_topology_nodes(const gb_skeleton *skeleton, const gb_adjacency *g,
                            uint8_t *node_class, uint32_t *rings, gb_error *error)
{
    uint32_t count = skeleton->node_count;
    *rings = 0;
    uint8_t *seen = calloc(count ? count : 1, 1);
    uint32_t *stack = malloc(count ? count * sizeof *stack : 1);
    if (!seen || !stack) {
        free(seen);
        free(stack);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u nodes", count);
    }
    for (uint32_t n = 0; n < count; ++n)
        if (gb_degree(g, n) != 2)
            node_class[n] = GB_NODE_TOPOLOGY;
    for (uint32_t n = 0; n < count; ++n) {
        if (node_class[n] || seen[n])
            continue;
        uint32_t anchor = ring_anchor(skeleton, g, n, seen, stack);
        if (anchor != UINT32_MAX) {
            node_class[anchor] = GB_NODE_TOPOLOGY;
            ++*rings;
        }
    }
    free(seen);
    free(stack);
    return GB_OK;
}
