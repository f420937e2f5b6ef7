// voxel_file.cpp — the voxel file's two grids from the dense surface and
// back (voxel_file.h).
//
// "surface" is built from the dense bytes (dense_sparse.h); "empty" is not
// read from them again: it is the frame's box filled with tiles (Tree::fill
// makes a tile of every node the box covers whole) minus the topology of
// "surface" (Tree::topologyDifference), pruned. The reader fills the dense
// surface from "surface" and checks "empty" sparsely: inside the frame,
// disjoint from "surface", and the two counts adding up to the frame's
// voxels — which together make it the complement.
#include "voxel_file.h"

#include <cstdlib>

#include "adapter_host.h"
#include "dense_sparse.h"
#include "grid_file.h"
#include "grid_frame.h"
#include "released_pages.h"

namespace gb_openvdb {

namespace {

const char *const VOXELIZE_CREATOR = "gibake-voxelize 0.1";
const char *const REMAKE = "voxelize";

// The empty space of frame: its box but the active voxels of surface.
openvdb::MaskGrid::Ptr complement_of(const openvdb::BoolGrid &surface,
                                     const gb_voxel_grid *frame)
{
    auto empty = openvdb::MaskGrid::create(false);
    empty->tree().fill(frame_box(frame), true, true);
    empty->tree().topologyDifference(surface.tree());
    openvdb::tools::prune(empty->tree());
    return empty;
}

gb_result write_voxel_grids(const char *path, const gb_voxel_grid *grid, bool release,
                            gb_error *error)
{
    if (!path || !grid || !grid->surface || !frame_is_valid(grid))
        return host->fail(error, GB_ERROR_ARGUMENT, "%s: voxel grid to write is not valid",
                          path ? path : "(null)");
    const uint8_t *bytes = grid->surface;
    return guarded(path, GB_ERROR_IO, [&] {
        return write_grids(path, [&] {
            auto surface = dense_to_grid<openvdb::BoolGrid>(
                grid, false, [=](size_t index) { return bytes[index] != 0; },
                [](size_t) { return true; },
                [=](size_t begin, size_t end) {
                    if (release)
                        release_pages(bytes + begin, bytes + end);
                });
            auto empty = complement_of(*surface, grid);
            attach_frame(*surface, grid, "surface", VOXELIZE_CREATOR, VOXEL_FORMAT_VERSION);
            attach_frame(*empty, grid, "empty", VOXELIZE_CREATOR, VOXEL_FORMAT_VERSION);
            return openvdb::GridPtrVec{surface, empty};
        }, error);
    }, error);
}

gb_result check_same_frame(const char *path, const openvdb::GridBase &grid,
                           const gb_voxel_grid *expected, gb_error *error)
{
    gb_voxel_grid frame;
    gb_result result = read_frame(path, grid, VOXEL_FORMAT_VERSION, REMAKE, 1.0, &frame, error);
    if (result == GB_OK && !same_frame(&frame, expected))
        result = host->fail(error, GB_ERROR_FORMAT,
                            "%s: grid '%s' has another frame than grid 'surface'", path,
                            grid.getName().c_str());
    return result;
}

// Whether empty is the complement of surface in frame (see the top).
bool is_complement(const openvdb::MaskGrid &empty, const openvdb::BoolGrid &surface,
                   const gb_voxel_grid *frame)
{
    openvdb::CoordBBox box = empty.evalActiveVoxelBoundingBox();
    if (!empty.tree().empty() && !frame_box(frame).isInside(box))
        return false;
    openvdb::MaskTree overlap(empty.tree());
    overlap.topologyIntersection(surface.tree());
    return overlap.activeVoxelCount() == 0
           && empty.tree().activeVoxelCount() + surface.tree().activeVoxelCount()
                  == frame_voxel_count(frame);
}

// Fills grid (frame and surface) from the grids of reader.
gb_result read_voxel_grids(const char *path, Reader &reader, gb_voxel_grid *grid,
                           gb_error *error)
{
    openvdb::BoolGrid::Ptr surface;
    openvdb::MaskGrid::Ptr empty;
    gb_result result = reader.read<openvdb::BoolGrid>("surface", "bool", &surface, error);
    gb_voxel_grid frame;
    if (result == GB_OK)
        result = read_frame(path, *surface, VOXEL_FORMAT_VERSION, REMAKE, 1.0, &frame, error);
    if (result == GB_OK)
        result = reader.read<openvdb::MaskGrid>("empty", "mask", &empty, error);
    if (result == GB_OK)
        result = check_same_frame(path, *empty, &frame, error);
    if (result == GB_OK) {
        int32_t size[3] = {frame.size[0], frame.size[1], frame.size[2]};
        gb_error reason;
        result = host->allocate(&frame, size, &reason);
        if (result != GB_OK)
            host->fail(error, result, "%s: %s", path, reason.message);
    }
    if (result != GB_OK)
        return result;
    uint8_t *occupied = frame.surface;
    if (!for_each_active_voxel(*surface, &frame, [&](size_t index, bool) { occupied[index] = 1; }))
        result = host->fail(error, GB_ERROR_FORMAT,
                            "%s: grid 'surface' has voxels outside its grid_size", path);
    else if (!is_complement(*empty, *surface, &frame))
        result = host->fail(error, GB_ERROR_FORMAT,
                            "%s: grid 'empty' is not the complement of 'surface'", path);
    if (result != GB_OK) {
        host->free(&frame);
        return result;
    }
    *grid = frame;
    return GB_OK;
}

} // namespace

gb_result write_voxel_file(const char *path, const gb_voxel_grid *grid, gb_error *error)
{
    return write_voxel_grids(path, grid, false, error);
}

gb_result write_voxel_file_and_free(const char *path, gb_voxel_grid *grid, gb_error *error)
{
    gb_result result = write_voxel_grids(path, grid, true, error);
    host->free(grid);
    return result;
}

gb_result read_voxel_file(const char *path, gb_voxel_grid *grid, gb_error *error)
{
    if (!path || !grid)
        return host->fail(error, GB_ERROR_ARGUMENT, "voxel grid read: no path or no grid");
    return guarded(path, GB_ERROR_FORMAT, [&] {
        Reader reader(path);
        gb_result result = reader.open(error);
        return result == GB_OK ? read_voxel_grids(path, reader, grid, error) : result;
    }, error);
}

} // namespace gb_openvdb
