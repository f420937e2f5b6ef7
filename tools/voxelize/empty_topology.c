#include "empty_topology.h"

#include <stdlib.h>
#include <string.h>

#include "index_queue.h"

/* Visits the component of start, marking its voxels in seen. */
static gb_result flood(const gb_voxel_grid *grid, uint8_t *seen, size_t start, gb_index_queue *q,
                       gb_error *error)
{
    const int32_t *n = grid->size;
    const size_t step[3] = {1, (size_t)n[0], (size_t)n[0] * (size_t)n[1]};
    seen[start] = 1;
    if (!gb_index_queue_push(q, start))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "empty space: out of memory");
    while (q->count) {
        size_t v = gb_index_queue_pop(q);
        size_t cell[3] = {v % step[1], v / step[1] % (size_t)n[1], v / step[2]};
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                if (side ? cell[axis] + 1 >= (size_t)n[axis] : cell[axis] == 0)
                    continue;
                size_t w = side ? v + step[axis] : v - step[axis];
                if (grid->surface[w] || seen[w])
                    continue;
                seen[w] = 1;
                if (!gb_index_queue_push(q, w))
                    return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "empty space: out of memory");
            }
    }
    return GB_OK;
}

static gb_result count_components(const gb_voxel_grid *grid, uint64_t *components,
                                  gb_error *error)
{
    size_t count = (size_t)grid->size[0] * (size_t)grid->size[1] * (size_t)grid->size[2];
    uint8_t *seen = calloc(count, 1);
    if (!seen)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "empty space: out of memory");
    gb_index_queue q = {0};
    gb_result result = GB_OK;
    *components = 0;
    for (size_t v = 0; v < count && result == GB_OK; ++v)
        if (!grid->surface[v] && !seen[v]) {
            ++*components;
            result = flood(grid, seen, v, &q, error);
        }
    gb_index_queue_free(&q);
    free(seen);
    return result;
}

static int empty(const gb_voxel_grid *grid, int32_t i, int32_t j, int32_t k)
{
    return !grid->surface[gb_voxel_index(grid, i, j, k)];
}

/* V - E + F - C: each empty voxel adds itself and the edges, squares and
 * block that it is the lowest corner of. */
static int64_t euler_characteristic(const gb_voxel_grid *grid)
{
    const int32_t *n = grid->size;
    int64_t chi = 0;
    for (int32_t k = 0; k < n[2]; ++k)
        for (int32_t j = 0; j < n[1]; ++j)
            for (int32_t i = 0; i < n[0]; ++i) {
                if (!empty(grid, i, j, k))
                    continue;
                int x = i + 1 < n[0] && empty(grid, i + 1, j, k);
                int y = j + 1 < n[1] && empty(grid, i, j + 1, k);
                int z = k + 1 < n[2] && empty(grid, i, j, k + 1);
                int xy = x && y && empty(grid, i + 1, j + 1, k);
                int xz = x && z && empty(grid, i + 1, j, k + 1);
                int yz = y && z && empty(grid, i, j + 1, k + 1);
                int xyz = xy && xz && yz && empty(grid, i + 1, j + 1, k + 1);
                chi += 1 - (x + y + z) + (xy + xz + yz) - xyz;
            }
    return chi;
}

gb_result gb_empty_topology_count(const gb_voxel_grid *grid, gb_empty_topology *topology,
                                  gb_error *error)
{
    memset(topology, 0, sizeof *topology);
    gb_result result = count_components(grid, &topology->components, error);
    if (result == GB_OK)
        topology->euler = euler_characteristic(grid);
    return result;
}
