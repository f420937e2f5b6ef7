/* voxel_frame.c — see voxel_frame.h. */
#include "voxel_frame.h"

#include <math.h>

#include "little_endian.h"

void gb_voxel_frame_put(unsigned char bytes[GB_VOXEL_FRAME_SIZE], double voxel_size,
                        const double world_origin[3], const int32_t grid_size[3])
{
    gb_put_f64(bytes, voxel_size);
    for (int a = 0; a < 3; ++a)
        gb_put_f64(bytes + 8 + 8 * a, world_origin[a]);
    for (int a = 0; a < 3; ++a)
        gb_put_u32(bytes + 32 + 4 * a, (uint32_t)grid_size[a]);
}

void gb_voxel_frame_get(const unsigned char bytes[GB_VOXEL_FRAME_SIZE], double *voxel_size,
                        double world_origin[3], int32_t grid_size[3])
{
    *voxel_size = gb_get_f64(bytes);
    for (int a = 0; a < 3; ++a)
        world_origin[a] = gb_get_f64(bytes + 8 + 8 * a);
    for (int a = 0; a < 3; ++a)
        grid_size[a] = (int32_t)gb_get_u32(bytes + 32 + 4 * a);
}

gb_result gb_voxel_frame_check(double voxel_size, const double world_origin[3],
                               const int32_t grid_size[3], const char *path, gb_error *error)
{
    if (!isfinite(voxel_size) || !(voxel_size > 0.0))
        return gb_fail(error, GB_ERROR_INVALID, "%s: voxel size %g is not positive", path,
                       voxel_size);
    for (int a = 0; a < 3; ++a) {
        if (!isfinite(world_origin[a]))
            return gb_fail(error, GB_ERROR_INVALID, "%s: world origin is not finite", path);
        if (grid_size[a] <= 0)
            return gb_fail(error, GB_ERROR_INVALID, "%s: grid size %d on axis %d is not positive",
                           path, (int)grid_size[a], a);
    }
    return GB_OK;
}
