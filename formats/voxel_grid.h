/* voxel_grid.h — the voxelized scene as the topological tools use it in
 * memory, and its OpenVDB file (written by voxelize, read by thin and segment).
 *
 * In memory the grid is dense over the padded scene bounds (a byte per
 * voxel, x fastest, then y, then z), which is what neighbourhood algorithms
 * want; on disk it is sparse OpenVDB, with tiles for uniform regions
 * (formats/FORMATS.md, "Voxel file"). No distance is stored: a reader that
 * needs the distance of a voxel to the surface computes it (thin's node
 * radii: tools/thin/surface_distance.h). Voxel (i,j,k) covers the world box
 * world_origin + voxel_size * [i,i+1] x [j,j+1] x [k,k+1].
 *
 * The caller owns the gb_voxel_grid and frees it with gb_voxel_grid_free.
 */
#ifndef GB_VOXEL_GRID_H
#define GB_VOXEL_GRID_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"

typedef struct gb_voxel_grid {
    int32_t size[3];            /* voxels along x, y, z */
    double voxel_size;          /* edge of a voxel, world units */
    double world_origin[3];     /* world position of the corner of voxel (0,0,0) */
    uint8_t *surface;           /* 1 where a triangle touches the voxel, else 0 */
    uint64_t scene_hash;
    uint32_t resolution;        /* voxels along the longest axis, as asked */
} gb_voxel_grid;

static inline size_t gb_voxel_index(const gb_voxel_grid *grid, int32_t i, int32_t j, int32_t k)
{
    return (size_t)i + (size_t)grid->size[0] * ((size_t)j + (size_t)grid->size[1] * (size_t)k);
}

/* Allocates surface for size, zero-filled. */
gb_result gb_voxel_grid_allocate(gb_voxel_grid *grid, const int32_t size[3], gb_error *error);
void gb_voxel_grid_free(gb_voxel_grid *grid);

/* Writes grids "surface" and "empty" with the metadata of FORMATS.md,
 * through the one output writer (output_file.h: a temporary and a rename,
 * or straight to a device, FIFO or "-"). */
gb_result gb_voxel_grid_write(const char *path, const gb_voxel_grid *grid, gb_error *error);
/* Fills grid (frame and surface) from the file, checked (FORMATS.md). */
gb_result gb_voxel_grid_read(const char *path, gb_voxel_grid *grid, gb_error *error);

/* gb_voxel_grid_write then gb_voxel_grid_free, giving the surface array's
 * memory back while the sparse grids are built: peak memory is about the
 * larger of the two instead of their sum. grid is freed whatever the
 * result. */
gb_result gb_voxel_grid_write_and_free(const char *path, gb_voxel_grid *grid,
                                       gb_error *error);

/* An int32 grid named name in the frame (size, voxel size, origin, hash) of
 * grid, e.g. thin's "nearest_node"; voxels whose value is negative are
 * inactive (not stored). values has one entry per voxel of the frame. Read
 * fills frame (without a surface array) and a malloc'ed *values. */
gb_result gb_voxel_grid_write_int32(const char *path, const gb_voxel_grid *frame,
                                    const char *name, const int32_t *values,
                                    gb_error *error);
/* gb_voxel_grid_write_int32, giving the pages of values back as the sparse
 * grid takes them over (as gb_voxel_grid_write_and_free does): the peak is
 * about the larger of the two instead of their sum. values (malloc'ed) is
 * freed whatever the result. */
gb_result gb_voxel_grid_write_int32_and_free(const char *path, const gb_voxel_grid *frame,
                                             const char *name, int32_t *values,
                                             gb_error *error);
gb_result gb_voxel_grid_read_int32(const char *path, const char *name,
                                   gb_voxel_grid *frame, int32_t **values,
                                   gb_error *error);

/* The checksum that the voxel file held in bytes (size bytes, the whole
 * file) should carry at bytes 21..56 (FORMATS.md, "Voxel file",
 * "Checksum"), as 36 characters and a NUL in uuid; for tests and fuzz
 * targets that mend a mutated file. Returns 0 (and writes nothing) when
 * size is below 57. */
int gb_voxel_file_checksum(const void *bytes, size_t size, char uuid[37]);

#endif
