/* voxel_grid.c — allocation of the dense in-memory voxel grid, and the
 * front of its file functions, which the OpenVDB adapter does
 * (formats/openvdb/, a shared object loaded on first use). */
#include "voxel_grid.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "adapter.h"
#include "huge_pages.h"
#include "output_file.h"
#include "voxel_check.h"
#include "voxel_grid_adapter.h"

/* Number of voxels of size, or 0 when a side is not positive or the count
 * (times the bytes per voxel) would not fit in a size_t. */
static size_t voxel_count_of(const int32_t size[3])
{
    size_t count = 1;
    for (int axis = 0; axis < 3; ++axis) {
        if (size[axis] <= 0)
            return 0;
        if (count > SIZE_MAX / 8 / (size_t)size[axis])
            return 0;
        count *= (size_t)size[axis];
    }
    return count;
}

gb_result gb_voxel_grid_allocate(gb_voxel_grid *grid, const int32_t size[3], gb_error *error)
{
    size_t count = voxel_count_of(size);
    if (count == 0)
        return gb_fail(error, GB_ERROR_ARGUMENT, "voxel grid: bad size %d x %d x %d",
                       (int)size[0], (int)size[1], (int)size[2]);
    uint8_t *surface = calloc(count, sizeof *surface);
    /* a hundred MiB at 512, written all over: a page fault every 2 MiB,
     * not every 4 KiB (huge_pages.h) */
    gb_advise_huge_pages(surface, count * sizeof *surface);
    if (!surface)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                       "voxel grid: out of memory for %d x %d x %d voxels",
                       (int)size[0], (int)size[1], (int)size[2]);
    for (int axis = 0; axis < 3; ++axis)
        grid->size[axis] = size[axis];
    grid->surface = surface;
    return GB_OK;
}

void gb_voxel_grid_free(gb_voxel_grid *grid)
{
    if (!grid)
        return;
    free(grid->surface);
    memset(grid, 0, sizeof *grid);
}

/* ---- the file, through the OpenVDB adapter (voxel_grid_adapter.h) ---- */

static const gb_voxel_grid_host host = {
    .fail = gb_fail,
    .file_check = gb_voxel_file_check,
    .allocate = gb_voxel_grid_allocate,
    .free = gb_voxel_grid_free,
    .output = &gb_output_file_table,
};

/* Defined only in programs that link the adapter in (adapter.h). */
extern gb_adapter_entry gb_openvdb_adapter __attribute__((weak));

static gb_adapter openvdb = GB_ADAPTER_INITIALIZER("openvdb", &host, gb_openvdb_adapter);

static const gb_voxel_grid_adapter *voxel_adapter(gb_error *error)
{
    return gb_adapter_functions(&openvdb, error);
}

gb_result gb_voxel_grid_write(const char *path, const gb_voxel_grid *grid, gb_error *error)
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(error);
    return adapter ? adapter->write(path, grid, error) : GB_ERROR_IO;
}

gb_result gb_voxel_grid_write_and_free(const char *path, gb_voxel_grid *grid, gb_error *error)
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(error);
    if (adapter)
        return adapter->write_and_free(path, grid, error);
    gb_voxel_grid_free(grid);
    return GB_ERROR_IO;
}

gb_result gb_voxel_grid_read(const char *path, gb_voxel_grid *grid, gb_error *error)
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(error);
    return adapter ? adapter->read(path, grid, error) : GB_ERROR_IO;
}

gb_result gb_voxel_grid_write_int32(const char *path, const gb_voxel_grid *frame,
                                    const char *name, const int32_t *values, gb_error *error)
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(error);
    return adapter ? adapter->write_int32(path, frame, name, values, error) : GB_ERROR_IO;
}

gb_result gb_voxel_grid_write_int32_and_free(const char *path, const gb_voxel_grid *frame,
                                             const char *name, int32_t *values, gb_error *error)
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(error);
    if (adapter)
        return adapter->write_int32_and_free(path, frame, name, values, error);
    free(values);
    return GB_ERROR_IO;
}

gb_result gb_voxel_grid_read_int32(const char *path, const char *name, gb_voxel_grid *frame,
                                   int32_t **values, gb_error *error)
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(error);
    return adapter ? adapter->read_int32(path, name, frame, values, error) : GB_ERROR_IO;
}

int gb_voxel_file_checksum(const void *bytes, size_t size, char uuid[37])
{
    const gb_voxel_grid_adapter *adapter = voxel_adapter(NULL);
    return adapter ? adapter->file_checksum(bytes, size, uuid) : 0;
}
