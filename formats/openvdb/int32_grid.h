// int32_grid.h — an int32 grid in a voxel file's frame, such as thin's
// "nearest_node" (FORMATS.md, "Nearest-node grid"): gb_voxel_grid_write_int32,
// gb_voxel_grid_write_int32_and_free and gb_voxel_grid_read_int32 of
// voxel_grid.h. Voxels of a negative value are inactive (not stored).
#ifndef GB_OPENVDB_INT32_GRID_H
#define GB_OPENVDB_INT32_GRID_H

#include "voxel_grid.h"

namespace gb_openvdb {

// The version of the int32 grid's layout (gibake_format): 2, as the voxel
// file's before it lost its distance grid.
const int32_t INT32_FORMAT_VERSION = 2;

gb_result write_int32(const char *path, const gb_voxel_grid *frame, const char *name,
                      const int32_t *values, gb_error *error);
gb_result write_int32_and_free(const char *path, const gb_voxel_grid *frame, const char *name,
                               int32_t *values, gb_error *error);
gb_result read_int32(const char *path, const char *name, gb_voxel_grid *frame,
                     int32_t **values, gb_error *error);

} // namespace gb_openvdb

#endif
