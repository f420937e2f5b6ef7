/* lines.c — lines between classified nodes and their recursive split. */
#include "lines.h"

#include <stdlib.h>
#include <string.h>

/* The slot that leaves cur (a node of degree two) by its other edge than
 * edge_in. */
static uint32_t next_slot(const gb_adjacency *g, uint32_t cur, uint32_t edge_in)
{
    uint32_t k = g->offsets[cur];
    return g->edge_of[k] == edge_in ? k + 1 : k;
}

/* Walks from classified node start along slot k to the next classified node,
 * appending the path (start excluded) to lines->nodes. */
static gb_result walk_line(const gb_adjacency *g, const uint8_t *node_class, uint32_t k,
                           uint8_t *edge_used, gb_lines *lines, uint32_t *length,
                           gb_error *error)
{
    uint32_t steps = 0;
    for (;;) {
        uint32_t edge = g->edge_of[k], cur = g->neighbours[k];
        edge_used[edge] = 1;
        lines->nodes[*length] = cur;
        ++*length;
        if (node_class[cur])
            return GB_OK;
        if (gb_degree(g, cur) != 2 || ++steps > g->node_count)
            return gb_fail(error, GB_ERROR_INVALID,
                           "node %u is unclassified but not on a line between classified nodes",
                           cur);
        k = next_slot(g, cur, edge);
    }
}

static uint32_t edge_count_of(const gb_adjacency *g)
{
    return g->offsets[g->node_count] / 2;
}

gb_result gb_lines_extract(const gb_adjacency *g, const uint8_t *node_class, gb_lines *lines,
                           gb_error *error)
{
    memset(lines, 0, sizeof *lines);
    uint32_t edges = edge_count_of(g);
    /* every line has at least one edge: at most `edges` lines and 2 * edges nodes */
    lines->offsets = malloc(((size_t)edges + 1) * sizeof *lines->offsets);
    lines->nodes = malloc(2 * (size_t)edges * sizeof *lines->nodes + 1);
    uint8_t *edge_used = calloc(edges ? edges : 1, 1);
    gb_result result = GB_OK;
    if (!lines->offsets || !lines->nodes || !edge_used)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u edges", edges);
    uint32_t length = 0;
    for (uint32_t n = 0; n < g->node_count && !result; ++n) {
        if (!node_class[n])
            continue;
        for (uint32_t k = g->offsets[n]; k < g->offsets[n + 1] && !result; ++k) {
            if (edge_used[g->edge_of[k]])
                continue;
            lines->offsets[lines->count] = length;
            lines->nodes[length++] = n;
            result = walk_line(g, node_class, k, edge_used, lines, &length, error);
            uint32_t path = length - lines->offsets[lines->count++];
            if (path > lines->longest)
                lines->longest = path;
        }
    }
    for (uint32_t e = 0; e < edges && !result; ++e)
        if (!edge_used[e])
            result = gb_fail(error, GB_ERROR_INVALID,
                             "edge %u is on no line between classified nodes", e);
    if (lines->offsets)
        lines->offsets[lines->count] = length;
    free(edge_used);
    if (result)
        gb_lines_free(lines);
    return result;
}

void gb_lines_free(gb_lines *lines)
{
    if (!lines)
        return;
    free(lines->offsets);
    free(lines->nodes);
    memset(lines, 0, sizeof *lines);
}

/* The index in path (first, last) of the interior node of largest measure,
 * or 0 when none is above 1. */
static uint32_t split_point(const gb_skeleton *s, const uint32_t *path, uint32_t first,
                            uint32_t last, gb_line_measure measure)
{
    uint32_t best = 0;
    double best_measure = 1.0;
    for (uint32_t i = first + 1; i < last; ++i) {
        double m = measure(s, path[i], path[first], path[last]);
        if (m > best_measure || (best && m == best_measure && path[i] < path[best])) {
            best = i;
            best_measure = m;
        }
    }
    return best;
}

/* Splits one path; stack holds pairs of indices, 2 * path length entries. */
static uint32_t split_line(const gb_skeleton *s, const uint32_t *path, uint32_t length,
                           gb_line_measure measure, uint8_t new_class, uint8_t *node_class,
                           uint32_t *stack)
{
    uint32_t top = 0, classified = 0;
    stack[top++] = 0;
    stack[top++] = length - 1;
    while (top) {
        uint32_t last = stack[--top], first = stack[--top];
        uint32_t split = split_point(s, path, first, last, measure);
        if (!split)
            continue;
        node_class[path[split]] = new_class;
        ++classified;
        stack[top++] = split;
        stack[top++] = last;
        stack[top++] = first;
        stack[top++] = split;
    }
    return classified;
}

gb_result gb_lines_split(const gb_skeleton *skeleton, const gb_lines *lines,
                         gb_line_measure measure, uint8_t new_class, uint8_t *node_class,
                         uint32_t *classified, gb_error *error)
{
    *classified = 0;
    uint32_t *stack = malloc(2 * ((size_t)lines->longest + 1) * sizeof *stack);
    if (!stack)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for a line of %u nodes",
                       lines->longest);
    for (uint32_t i = 0; i < lines->count; ++i) {
        uint32_t start = lines->offsets[i], length = lines->offsets[i + 1] - start;
        *classified += split_line(skeleton, lines->nodes + start, length, measure, new_class,
                                  node_class, stack);
    }
    free(stack);
    return GB_OK;
}
