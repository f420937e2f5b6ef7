// int32_grid.cpp — an int32 grid in a frame, to a file and back (int32_grid.h).
#include "int32_grid.h"

#include <cstdlib>

#include "adapter_host.h"
#include "dense_sparse.h"
#include "grid_file.h"
#include "grid_frame.h"
#include "released_pages.h"

namespace gb_openvdb {

namespace {

const char *const INT32_CREATOR = "gibake 0.1";

// With release, the pages of values are given back slab by slab as the
// tree takes them over (values is then to be freed, not read).
gb_result write_int32_grid(const char *path, const gb_voxel_grid *frame, const char *name,
                           const int32_t *values, bool release, gb_error *error)
{
    if (!path || !frame || !name || !*name || !values || !frame_is_valid(frame))
        return host->fail(error, GB_ERROR_ARGUMENT, "%s: int32 grid to write is not valid",
                          path ? path : "(null)");
    return guarded(path, GB_ERROR_IO, [&] {
        return write_grids(path, [&] {
            auto grid = dense_to_grid<openvdb::Int32Grid>(
                frame, -1, [=](size_t index) { return values[index] >= 0; },
                [=](size_t index) { return values[index]; },
                [=](size_t begin, size_t end) {
                    if (release)
                        release_pages(values + begin, values + end);
                });
            attach_frame(*grid, frame, name, INT32_CREATOR, INT32_FORMAT_VERSION);
            return openvdb::GridPtrVec{grid};
        }, error);
    }, error);
}

// The dense values of grid (-1 where inactive) in frame, malloc'ed.
gb_result grid_to_dense(const char *path, const char *name, const openvdb::Int32Grid &grid,
                        const gb_voxel_grid *frame, int32_t **values, gb_error *error)
{
    size_t count = frame_voxel_count(frame);
    int32_t *dense = (int32_t *)std::malloc(count * sizeof *dense);
    if (!dense)
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory for %zu voxels",
                          path, count);
    for (size_t index = 0; index < count; ++index)
        dense[index] = -1;
    bool negative = false;
    bool inside = for_each_active_voxel(grid, frame, [&](size_t index, int32_t value) {
        negative |= value < 0;
        dense[index] = value;
    });
    if (!inside || negative) {
        std::free(dense);
        return host->fail(error, GB_ERROR_FORMAT,
                          inside ? "%s: grid '%s' has a negative active value"
                                 : "%s: grid '%s' has voxels outside its grid_size",
                          path, name);
    }
    *values = dense;
    return GB_OK;
}

} // namespace

gb_result write_int32(const char *path, const gb_voxel_grid *frame, const char *name,
                      const int32_t *values, gb_error *error)
{
    return write_int32_grid(path, frame, name, values, false, error);
}

gb_result write_int32_and_free(const char *path, const gb_voxel_grid *frame, const char *name,
                               int32_t *values, gb_error *error)
{
    gb_result result = write_int32_grid(path, frame, name, values, true, error);
    std::free(values);
    return result;
}

gb_result read_int32(const char *path, const char *name, gb_voxel_grid *frame,
                     int32_t **values, gb_error *error)
{
    if (!path || !name || !frame || !values)
        return host->fail(error, GB_ERROR_ARGUMENT, "int32 grid read: missing argument");
    return guarded(path, GB_ERROR_FORMAT, [&] {
        Reader reader(path);
        openvdb::Int32Grid::Ptr grid;
        gb_voxel_grid read;
        gb_result result = reader.open(error);
        if (result == GB_OK)
            result = reader.read<openvdb::Int32Grid>(name, "int32", &grid, error);
        if (result == GB_OK)
            result = read_frame(path, *grid, INT32_FORMAT_VERSION, "thin --grid", 4.0, &read,
                                error);
        if (result == GB_OK)
            result = grid_to_dense(path, name, *grid, &read, values, error);
        if (result == GB_OK)
            *frame = read;
        return result;
    }, error);
}

} // namespace gb_openvdb
