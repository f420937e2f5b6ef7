// voxel_file.h — the voxel file (FORMATS.md, "Voxel file"): the grids
// "surface" and "empty" of a gb_voxel_grid, both sparse with tiles for
// uniform regions; gb_voxel_grid_write, gb_voxel_grid_write_and_free and
// gb_voxel_grid_read of voxel_grid.h.
#ifndef GB_OPENVDB_VOXEL_FILE_H
#define GB_OPENVDB_VOXEL_FILE_H

#include "voxel_grid.h"

namespace gb_openvdb {

// 3: no "distance" grid (2: a float distance for every empty voxel; 1: the
// checksum left out the header and the length).
const int32_t VOXEL_FORMAT_VERSION = 3;

gb_result write_voxel_file(const char *path, const gb_voxel_grid *grid, gb_error *error);
gb_result write_voxel_file_and_free(const char *path, gb_voxel_grid *grid, gb_error *error);
gb_result read_voxel_file(const char *path, gb_voxel_grid *grid, gb_error *error);

} // namespace gb_openvdb

#endif
