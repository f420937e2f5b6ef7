// grid_frame.h — a gb_voxel_grid's frame (size, voxel size, origin, scene
// hash, resolution) as the metadata and transform of an OpenVDB grid
// (FORMATS.md, "Voxel file", "Metadata on every grid"), and back, checked.
//
// Index space: voxel (i,j,k) of the dense frame is OpenVDB coordinate
// (i,j,k); its centre is at world_origin + voxel_size * (i+1/2, j+1/2, k+1/2),
// which is what the grids' linear transform says.
#ifndef GB_OPENVDB_GRID_FRAME_H
#define GB_OPENVDB_GRID_FRAME_H

#define IMATH_HALF_NO_LOOKUP_TABLE
#include <openvdb/openvdb.h>

#include "voxel_grid.h"

namespace gb_openvdb {

// The largest side of a frame, in voxels.
const int32_t MAX_SIDE = 1 << 20;

bool frame_is_valid(const gb_voxel_grid *frame);
size_t frame_voxel_count(const gb_voxel_grid *frame);
bool same_frame(const gb_voxel_grid *a, const gb_voxel_grid *b);

// Names grid, sets its creator, its transform and the frame's metadata with
// gibake_format = version.
void attach_frame(openvdb::GridBase &grid, const gb_voxel_grid *frame, const char *name,
                  const char *creator, int32_t version);

// Reads the frame metadata of grid (of the file at path, for messages) into
// frame, without arrays, and checks it: gibake_format must be version (an
// older one is named in the error, with what makes the file again: remake),
// the frame valid, its dense array (bytes_per_voxel) within this machine's
// memory, the transform the one the metadata says.
gb_result read_frame(const char *path, const openvdb::GridBase &grid, int32_t version,
                     const char *remake, double bytes_per_voxel, gb_voxel_grid *frame,
                     gb_error *error);

} // namespace gb_openvdb

#endif
