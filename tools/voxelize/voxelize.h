/* voxelize.h — scene triangles to the voxel grid of the topological pipeline
 * (noel-biri-2014, section IV.A): the voxels every triangle touches
 * (surface, conservative); the others are the empty space.
 *
 * Frame: voxels are cubes of edge voxel_size = longest side of the bounds of
 * the triangles / resolution; the grid covers the bounds plus pad voxels on
 * every side; world_origin = bounds min - pad * voxel_size. Vertices are
 * taken relative to the bounds min in double precision, so a scene far from
 * the world origin (1e6) or very small (1e-4) voxelizes as well as a unit one.
 *
 * Surface: a voxel is surface iff a triangle touches its closed box (exact
 * separating-axis test, common/triangle_box_overlap.h), so no
 * 6-connected path of empty voxels crosses a wall, however thin or oriented.
 *
 * Work is split over options->thread_count threads by voxel slabs; the result
 * does not depend on the thread count. The library never prints: it reports
 * the fraction done to options->progress (common/progress.h), which may stop
 * it.
 */
#ifndef GB_VOXELIZE_H
#define GB_VOXELIZE_H

#include <stdint.h>

#include "progress.h"
#include "result.h"
#include "scene.h"
#include "voxel_grid.h"

enum {
    GB_VOXELIZE_DEFAULT_RESOLUTION = 256,
    GB_VOXELIZE_MAX_RESOLUTION = 2048, /* keeps thin's squared distances exact */
    GB_VOXELIZE_DEFAULT_PAD = 2,
    GB_VOXELIZE_MAX_PAD = 64,
    GB_VOXELIZE_NO_PAD = -1,           /* pad value meaning "no empty border" */
    GB_VOXELIZE_DEFAULT_THREADS = 2,
};

/* Zeroed fields mean the defaults. */
typedef struct gb_voxelize_options {
    uint32_t resolution;          /* voxels along the longest axis; 0: 256 */
    int32_t pad;                  /* empty voxels around the bounds; 0: 2;
                                     GB_VOXELIZE_NO_PAD: none */
    int32_t thread_count;         /* 0: 2 */
    gb_progress_callback progress;/* NULL: no report; called from the calling
                                     thread with the fraction done; nonzero
                                     stops the work, which then fails with
                                     GB_ERROR_INTERRUPTED */
    void *progress_user;
} gb_voxelize_options;

/* Triangles as positions (vertex_count * 3 floats) and indices
 * (triangle_count * 3). Fills grid (which the caller frees with
 * gb_voxel_grid_free) with the frame and surface; scene_hash is 0.
 * Fails with GB_ERROR_INVALID on no triangle, an index out of range, a
 * non-finite position or bounds of zero extent; GB_ERROR_ARGUMENT on options
 * out of range. Degenerate triangles are voxelized as the segment or point
 * they are. options may be NULL. */
gb_result gb_voxelize_triangles(const float *positions, uint32_t vertex_count,
                                const uint32_t *indices, uint32_t triangle_count,
                                const gb_voxelize_options *options, gb_voxel_grid *grid,
                                gb_error *error);

/* gb_voxelize_triangles on the scene's mesh, with the scene's hash. */
gb_result gb_voxelize_scene(const gb_scene *scene, const gb_voxelize_options *options,
                            gb_voxel_grid *grid, gb_error *error);

/* The frame (size, voxel_size, world_origin, resolution) for triangles of
 * bounds lower..upper, without arrays. */
gb_result gb_voxelize_frame(const double lower[3], const double upper[3],
                            const gb_voxelize_options *options, gb_voxel_grid *frame,
                            gb_error *error);

/* Marks the surface voxels of the triangles in grid->surface (allocated, in
 * grid's frame; voxels already set stay set). A vertex p has the voxel
 * coordinates (p - reference) / voxel_size + reference_voxel: reference is a
 * point near the triangles (the bounds min) and reference_voxel its exact
 * place in voxel units, so precision follows the scene's size, not its
 * position, and a wall on a voxel face stays exactly on it. */
gb_result gb_voxelize_surface(gb_voxel_grid *grid, const double reference[3],
                              const double reference_voxel[3], const float *positions,
                              uint32_t vertex_count, const uint32_t *indices,
                              uint32_t triangle_count, const gb_voxelize_options *options,
                              gb_error *error);

#endif
