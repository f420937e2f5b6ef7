/* segmented_skeleton.c — classified nodes, the edges of the lines between
 * them, and every skeleton node's nearest extremum. */
#include "segmented_skeleton.h"

#include <stdlib.h>
#include <string.h>

static void copy_frame(const gb_skeleton *s, gb_segmentation *out)
{
    out->skeleton_node_count = s->node_count;
    out->scene_hash = s->scene_hash;
    out->voxel_size = s->voxel_size;
    memcpy(out->world_origin, s->world_origin, sizeof out->world_origin);
    memcpy(out->grid_size, s->grid_size, sizeof out->grid_size);
    out->resolution = s->resolution;
}

/* Segmented nodes in skeleton order; node_map of each to itself, the others
 * UINT32_MAX for now. */
static gb_result collect_nodes(const gb_skeleton *s, const uint8_t *node_class,
                               gb_segmentation *out, gb_error *error)
{
    uint32_t count = 0;
    for (uint32_t n = 0; n < s->node_count; ++n)
        count += node_class[n] != 0;
    out->nodes = malloc(count ? count * sizeof *out->nodes : 1);
    out->node_map = malloc(s->node_count ? s->node_count * sizeof *out->node_map : 1);
    if (!out->nodes || !out->node_map)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u nodes", count);
    for (uint32_t n = 0; n < s->node_count; ++n) {
        out->node_map[n] = UINT32_MAX;
        if (!node_class[n])
            continue;
        gb_segmented_node *node = &out->nodes[out->node_count];
        node->skeleton_node = n;
        node->node_class = node_class[n];
        memcpy(node->position, s->nodes[n].position, sizeof node->position);
        node->radius = s->nodes[n].radius;
        out->node_map[n] = out->node_count++;
    }
    return GB_OK;
}

/* Interior nodes of a line go to the nearer extremum (ties: smaller index). */
static void map_line(const gb_skeleton *s, const uint32_t *path, uint32_t length,
                     uint32_t *node_map)
{
    uint32_t first = path[0], last = path[length - 1];
    for (uint32_t i = 1; i + 1 < length; ++i) {
        double to_first = gb_node_distance(s, path[i], first);
        double to_last = gb_node_distance(s, path[i], last);
        uint32_t nearest = to_first < to_last ? first
                           : to_last < to_first ? last
                           : first < last ? first : last;
        node_map[path[i]] = node_map[nearest];
    }
}

static int compare_pairs(const void *a, const void *b)
{
    const uint32_t *p = a, *q = b;
    if (p[0] != q[0])
        return p[0] < q[0] ? -1 : 1;
    return p[1] < q[1] ? -1 : p[1] > q[1];
}

/* One edge per line between distinct extrema, sorted, duplicates removed. */
static gb_result collect_edges(const gb_lines *lines, gb_segmentation *out, gb_error *error)
{
    out->edges = malloc(lines->count ? 2 * (size_t)lines->count * sizeof *out->edges : 1);
    if (!out->edges)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u edges",
                       lines->count);
    uint32_t count = 0;
    for (uint32_t i = 0; i < lines->count; ++i) {
        uint32_t a = out->node_map[lines->nodes[lines->offsets[i]]];
        uint32_t b = out->node_map[lines->nodes[lines->offsets[i + 1] - 1]];
        if (a == b)
            continue;
        out->edges[2 * count] = a < b ? a : b;
        out->edges[2 * count + 1] = a < b ? b : a;
        ++count;
    }
    qsort(out->edges, count, 2 * sizeof *out->edges, compare_pairs);
    out->edge_count = 0;
    for (uint32_t e = 0; e < count; ++e) {
        uint32_t *edge = out->edges + 2 * e, *kept = out->edges + 2 * out->edge_count;
        if (out->edge_count && kept[-2] == edge[0] && kept[-1] == edge[1])
            continue;
        kept[0] = edge[0];
        kept[1] = edge[1];
        ++out->edge_count;
    }
    return GB_OK;
}

gb_result gb_segmented_skeleton(const gb_skeleton *skeleton, const uint8_t *node_class,
                                const gb_lines *lines, gb_segmentation *out, gb_error *error)
{
    copy_frame(skeleton, out);
    gb_result result = collect_nodes(skeleton, node_class, out, error);
    if (result)
        return result;
    for (uint32_t i = 0; i < lines->count; ++i)
        map_line(skeleton, lines->nodes + lines->offsets[i],
                 lines->offsets[i + 1] - lines->offsets[i], out->node_map);
    for (uint32_t n = 0; n < skeleton->node_count; ++n)
        if (out->node_map[n] == UINT32_MAX)
            return gb_fail(error, GB_ERROR_INVALID, "skeleton node %u is on no line", n);
    return collect_edges(lines, out, error);
}
