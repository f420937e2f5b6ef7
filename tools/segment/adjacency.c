/* adjacency.c — compressed rows of neighbours from a sorted edge list. */
#include "adjacency.h"

#include <stdlib.h>
#include <string.h>

static void count_degrees(const uint32_t *edges, uint32_t edge_count, uint32_t *offsets)
{
    for (uint32_t e = 0; e < edge_count; ++e) {
        ++offsets[edges[2 * e] + 1];
        ++offsets[edges[2 * e + 1] + 1];
    }
}

/* Edges in (a, b) order put every smaller neighbour of a node before every
 * larger one, each group increasing: the rows come out sorted. */
static void fill_rows(const uint32_t *edges, uint32_t edge_count, gb_adjacency *g,
                      uint32_t *cursor)
{
    for (uint32_t e = 0; e < edge_count; ++e) {
        uint32_t a = edges[2 * e], b = edges[2 * e + 1];
        g->neighbours[cursor[a]] = b;
        g->edge_of[cursor[a]++] = e;
        g->neighbours[cursor[b]] = a;
        g->edge_of[cursor[b]++] = e;
    }
}

gb_result gb_adjacency_build(uint32_t node_count, const uint32_t *edges, uint32_t edge_count,
                             gb_adjacency *g, gb_error *error)
{
    memset(g, 0, sizeof *g);
    g->node_count = node_count;
    size_t slots = 2 * (size_t)edge_count;
    g->offsets = calloc((size_t)node_count + 1, sizeof *g->offsets);
    g->neighbours = malloc(slots ? slots * sizeof *g->neighbours : 1);
    g->edge_of = malloc(slots ? slots * sizeof *g->edge_of : 1);
    uint32_t *cursor = malloc(((size_t)node_count + 1) * sizeof *cursor);
    if (!g->offsets || !g->neighbours || !g->edge_of || !cursor) {
        free(cursor);
        gb_adjacency_free(g);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u nodes", node_count);
    }
    count_degrees(edges, edge_count, g->offsets);
    for (uint32_t n = 0; n < node_count; ++n)
        g->offsets[n + 1] += g->offsets[n];
    memcpy(cursor, g->offsets, ((size_t)node_count + 1) * sizeof *cursor);
    fill_rows(edges, edge_count, g, cursor);
    free(cursor);
    return GB_OK;
}

void gb_adjacency_free(gb_adjacency *g)
{
    if (!g)
        return;
    free(g->offsets);
    free(g->neighbours);
    free(g->edge_of);
    memset(g, 0, sizeof *g);
}
