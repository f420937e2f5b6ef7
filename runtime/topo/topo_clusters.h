/* topo_clusters.h — the visibility cluster of a fragment (Noël & Biri
 * 2014, §V, the GP pass; topo_clusters.c): on the GPU a compute pass over
 * the G-buffer, on the CPU its twin for VPLs and tests. The caller owns the
 * voxel clusters array and a pass from create until destroy. */
#ifndef GB_TOPO_CLUSTERS_H
#define GB_TOPO_CLUSTERS_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "result.h"
#include "segmentation.h"

/* The cluster of each voxel of the nearest-node grid, -1 where none
 * (gb_segmentation_voxel_clusters, formats/segmentation.h), is what the GPU
 * looks a fragment up in. */

/* Marks the voxels voxelize flagged as surface: cluster c becomes
 * GB_TOPO_SURFACE_CLUSTER(c) = -c - 2 (its own inverse), which the lookups
 * below use only as a last resort: thin gives a surface voxel the node of
 * its best empty neighbour, often across the wall. */
#define GB_TOPO_SURFACE_CLUSTER(c) (-(c) - 2)
void gb_topo_voxel_clusters_mark_surface(const gb_segmentation *segmentation,
                                         int32_t *voxel_clusters, const uint8_t *surface);

/* The cluster of a surface point x of geometric normal ng: x moved into the
 * empty side by |ng|_1 voxels (out of the surface's own voxels), then 1 and
 * 2 voxels more, until one has a cluster; failing that, the first marked
 * surface voxel's cluster on the way. -1: none. The CPU twin of the GPU
 * lookup. */
int32_t gb_topo_surface_cluster(const gb_segmentation *segmentation, const int32_t *voxel_clusters,
                                const float x[3], const float ng[3]);

/* GPU: the compute program that fills the G-buffer's clusters.x. */
typedef struct gb_topo_cluster_pass {
    GLuint program;
    GLuint voxel_clusters;      /* 3-D R32I texture */
} gb_topo_cluster_pass;

gb_result gb_topo_cluster_pass_create(const gb_segmentation *segmentation,
                                      const int32_t *voxel_clusters, gb_topo_cluster_pass *pass,
                                      gb_error *error);
/* view_to_world: column-major; tan_half_fov x, y. Writes clusters (RG32UI)
 * x = visibility cluster, y = GB_NO_CLUSTER. */
void gb_topo_cluster_pass_run(const gb_topo_cluster_pass *pass, GLuint depth, GLuint normal,
                              GLuint clusters, int width, int height, const float view_to_world[16],
                              const float tan_half_fov[2], float near);
void gb_topo_cluster_pass_destroy(gb_topo_cluster_pass *pass);

#endif
