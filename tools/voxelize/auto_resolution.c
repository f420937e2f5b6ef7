#include "auto_resolution.h"

#include <string.h>

/* The empty space's topology at resolution r. */
static gb_result topology_at(const gb_scene *scene, const gb_voxelize_options *options,
                             uint32_t r, gb_empty_topology *topology, gb_error *error)
{
    gb_voxelize_options check = {0};
    if (options) {
        check.pad = options->pad;
        check.thread_count = options->thread_count;
    }
    check.resolution = r;
    gb_voxel_grid grid = {0};
    gb_result result = gb_voxelize_scene(scene, &check, &grid, error);
    if (result == GB_OK)
        result = gb_empty_topology_count(&grid, topology, error);
    gb_voxel_grid_free(&grid);
    return result;
}

static int same(const gb_empty_topology *a, const gb_empty_topology *b)
{
    return a->components == b->components && a->euler == b->euler;
}

gb_result gb_voxelize_auto_resolution(const gb_scene *scene, const gb_voxelize_options *options,
                                      gb_auto_resolution *choice, gb_error *error)
{
    memset(choice, 0, sizeof *choice);
    uint32_t r = GB_AUTO_RESOLUTION_FIRST;
    for (int step = 0; step < GB_AUTO_RESOLUTION_STEPS; ++step, r *= 2) {
        gb_result result = topology_at(scene, options, r, &choice->topology[step], error);
        if (result != GB_OK)
            return result;
        choice->resolutions[step] = r;
        choice->checked = (uint32_t)step + 1;
        if (step > 1 && same(&choice->topology[step - 2], &choice->topology[step - 1]) &&
            same(&choice->topology[step - 1], &choice->topology[step])) {
            choice->resolution = r / 2;
            choice->settled = 1;
            return GB_OK;
        }
    }
    choice->resolution = GB_AUTO_RESOLUTION_MAX;
    return GB_OK;
}
