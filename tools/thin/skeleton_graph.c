/* skeleton_graph.c — nodes and edges of the thinned complex (see
 * skeleton_graph.h). */
#include "skeleton_graph.h"

#include <stdlib.h>
#include <string.h>

#include "bisection.h"
#include "surface_distance.h"

static gb_result collect_node_cells(const gb_cubical_complex *complex, uint32_t **cells,
                                    uint32_t *count, uint32_t *edge_count, gb_error *error)
{
    size_t nodes = 0, edges = 0;
    for (size_t cell = 0; cell < complex->cell_count; ++cell) {
        uint8_t f = complex->faces[cell];
        nodes += (f & GB_FACE_POINT) != 0;
        edges += (size_t)gb_face_count(f & GB_FACE_EDGES);
    }
    if (nodes > UINT32_MAX || edges > UINT32_MAX)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "skeleton: more than 2^32 nodes or edges");
    *cells = malloc(nodes ? nodes * sizeof **cells : 1);
    if (!*cells)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "skeleton: out of memory for %zu nodes",
                       nodes);
    size_t n = 0;
    for (size_t cell = 0; cell < complex->cell_count; ++cell)
        if (complex->faces[cell] & GB_FACE_POINT)
            (*cells)[n++] = (uint32_t)cell;
    *count = (uint32_t)nodes;
    *edge_count = (uint32_t)edges;
    return GB_OK;
}

typedef struct cell_query {
    const uint32_t *cells;
    size_t cell;
} cell_query;

static int at_or_below_cell(const void *user, size_t i)
{
    const cell_query *query = user;
    return query->cells[i] <= query->cell;
}

/* Index of cell in the increasing array cells (it is there). */
static uint32_t node_of_cell(const uint32_t *cells, uint32_t count, size_t cell)
{
    cell_query query = {cells, cell};
    return (uint32_t)gb_bisection_last(count, at_or_below_cell, &query);
}

/* The empty voxels around a corner (cell coordinates), as dense indices
 * into voxels (8 at most); returns how many. */
static int corner_voxels(const gb_voxel_grid *grid, const gb_empty_voxels *empty,
                         const int32_t corner[3], size_t voxels[8])
{
    int count = 0;
    for (int d = 0; d < 8; ++d) {
        int32_t i = corner[0] - 1 - (d & 1), j = corner[1] - 1 - ((d >> 1) & 1),
                k = corner[2] - 1 - ((d >> 2) & 1);
        if (i < 0 || j < 0 || k < 0 || i >= grid->size[0] || j >= grid->size[1] ||
            k >= grid->size[2])
            continue;
        size_t v = gb_voxel_index(grid, i, j, k);
        if (gb_voxel_is_empty(empty, v))
            voxels[count++] = v;
    }
    return count;
}

/* Every node's radius: the largest distance to the surface of the empty
 * voxels around its corner (surface_distance.h). */
static gb_result set_radii(const gb_cubical_complex *complex, const gb_voxel_grid *grid,
                           const gb_empty_voxels *empty, const uint32_t *cells,
                           gb_skeleton *skeleton, gb_error *error)
{
    gb_surface_distance index;
    gb_result built = gb_surface_distance_build(&index, grid, empty, error);
    if (built)
        return built;
    size_t most = 8 * (size_t)skeleton->node_count + 1;
    size_t *voxels = malloc(most * sizeof *voxels);
    float *distances = malloc(most * sizeof *distances);
    uint8_t *counts = malloc(skeleton->node_count + 1);
    gb_result result = GB_OK;
    if (!voxels || !distances || !counts)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "skeleton: out of memory for radii");
    size_t total = 0;
    for (uint32_t n = 0; !result && n < skeleton->node_count; ++n) {
        int32_t corner[3];
        gb_cell_coordinates(complex, cells[n], corner);
        counts[n] = (uint8_t)corner_voxels(grid, empty, corner, voxels + total);
        total += counts[n];
    }
    if (!result)
        gb_surface_distances(&index, voxels, total, distances);
    for (uint32_t n = 0, at = 0; !result && n < skeleton->node_count; ++n) {
        float radius = 0.0f;
        for (int v = 0; v < counts[n]; ++v, ++at)
            if (distances[at] > radius)
                radius = distances[at];
        skeleton->nodes[n].radius = radius;
    }
    free(voxels);
    free(distances);
    free(counts);
    gb_surface_distance_free(&index);
    return result;
}

static void place_nodes(const gb_cubical_complex *complex, const gb_voxel_grid *grid,
                        const uint32_t *cells, gb_skeleton *skeleton)
{
    for (uint32_t n = 0; n < skeleton->node_count; ++n) {
        int32_t corner[3];
        gb_cell_coordinates(complex, cells[n], corner);
        for (int a = 0; a < 3; ++a)
            skeleton->nodes[n].position[a] =
                (float)(grid->world_origin[a] + grid->voxel_size * (double)(corner[a] - 1));
    }
}

static void join_edges(const gb_cubical_complex *complex, const uint32_t *cells,
                       gb_skeleton *skeleton)
{
    size_t e = 0;
    for (uint32_t n = 0; n < skeleton->node_count; ++n) {
        uint8_t f = complex->faces[cells[n]];
        for (int axis = 0; axis < 3; ++axis) {
            if (!(f & gb_edge_bit(axis)))
                continue;
            skeleton->edges[2 * e] = n;
            skeleton->edges[2 * e + 1] =
                node_of_cell(cells, skeleton->node_count, cells[n] + complex->step[axis]);
            ++e;
        }
    }
}

gb_result gb_skeleton_graph_build(const gb_cubical_complex *complex, const gb_voxel_grid *grid,
                                  const gb_empty_voxels *empty, gb_skeleton *skeleton,
                                  uint32_t **node_cells, gb_error *error)
{
    uint32_t *cells = NULL, node_count = 0, edge_count = 0;
    gb_result result = collect_node_cells(complex, &cells, &node_count, &edge_count, error);
    if (result)
        return result;
    skeleton->nodes = malloc(node_count ? node_count * sizeof *skeleton->nodes : 1);
    skeleton->edges = malloc(edge_count ? 2 * (size_t)edge_count * sizeof *skeleton->edges : 1);
    if (!skeleton->nodes || !skeleton->edges) {
        free(cells);
        free(skeleton->nodes);
        free(skeleton->edges);
        skeleton->nodes = NULL;
        skeleton->edges = NULL;
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "skeleton: out of memory");
    }
    skeleton->node_count = node_count;
    skeleton->edge_count = edge_count;
    place_nodes(complex, grid, cells, skeleton);
    join_edges(complex, cells, skeleton);
    result = set_radii(complex, grid, empty, cells, skeleton, error);
    if (result) {
        free(cells);
        return result;
    }
    *node_cells = cells;
    return GB_OK;
}
