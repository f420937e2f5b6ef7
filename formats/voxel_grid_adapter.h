/* voxel_grid_adapter.h — between formats/voxel_grid.c and the OpenVDB
 * adapter (formats/openvdb/, adapter_entry.cpp), a shared object loaded on the
 * first voxel file read, written or checksummed (formats/adapter.h says
 * why: OpenVDB costs a process about 70 ms of relocations at start-up).
 *
 * The adapter's entry, gb_openvdb_adapter (a gb_adapter_entry), takes a
 * gb_voxel_grid_host, the gibake functions it calls (which outlive it), and
 * returns its gb_voxel_grid_adapter.
 */
#ifndef GB_VOXEL_GRID_ADAPTER_H
#define GB_VOXEL_GRID_ADAPTER_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "output_file.h"
#include "result.h"
#include "voxel_grid.h"

typedef struct gb_voxel_grid_host {
    gb_result (*fail)(gb_error *error, gb_result result, const char *format, ...)
        __attribute__((format(printf, 3, 4)));
    gb_result (*file_check)(const void *bytes, size_t size, const char *path, gb_error *error);
    gb_result (*allocate)(gb_voxel_grid *grid, const int32_t size[3], gb_error *error);
    void (*free)(gb_voxel_grid *grid);
    const gb_output_file_functions *output; /* the one output writer */
} gb_voxel_grid_host;

/* What the functions of voxel_grid.h of the same names do. */
typedef struct gb_voxel_grid_adapter {
    gb_result (*write)(const char *path, const gb_voxel_grid *grid, gb_error *error);
    gb_result (*write_and_free)(const char *path, gb_voxel_grid *grid, gb_error *error);
    gb_result (*read)(const char *path, gb_voxel_grid *grid, gb_error *error);
    gb_result (*write_int32)(const char *path, const gb_voxel_grid *frame, const char *name,
                             const int32_t *values, gb_error *error);
    gb_result (*write_int32_and_free)(const char *path, const gb_voxel_grid *frame,
                                      const char *name, int32_t *values, gb_error *error);
    gb_result (*read_int32)(const char *path, const char *name, gb_voxel_grid *frame,
                            int32_t **values, gb_error *error);
    int (*file_checksum)(const void *bytes, size_t size, char uuid[37]);
} gb_voxel_grid_adapter;

#ifdef __cplusplus
}
#endif

#endif
