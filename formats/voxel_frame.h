/* voxel_frame.h — the voxel frame a skeleton or a segmentation was baked
 * on (the voxel grid's voxel size, world origin and size), as their file
 * headers store it and as their readers check it.
 *
 * In a header the frame is 44 bytes, little-endian: the voxel size (f64),
 * the world origin (3 f64), the grid size (3 u32). See FORMATS.md.
 * The caller owns every array passed; nothing is kept.
 */
#ifndef GB_VOXEL_FRAME_H
#define GB_VOXEL_FRAME_H

#include <stdint.h>

#include "result.h"

enum { GB_VOXEL_FRAME_SIZE = 44 };

void gb_voxel_frame_put(unsigned char bytes[GB_VOXEL_FRAME_SIZE], double voxel_size,
                        const double world_origin[3], const int32_t grid_size[3]);
void gb_voxel_frame_get(const unsigned char bytes[GB_VOXEL_FRAME_SIZE], double *voxel_size,
                        double world_origin[3], int32_t grid_size[3]);

/* GB_ERROR_INVALID, naming path, unless the voxel size is positive and
 * finite, the origin finite and every grid size positive. */
gb_result gb_voxel_frame_check(double voxel_size, const double world_origin[3],
                               const int32_t grid_size[3], const char *path, gb_error *error);

#endif
