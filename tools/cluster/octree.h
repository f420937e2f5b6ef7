/* octree.h — the geometric octree of vivianloc-2007 §4.1 ("built on the
 * whole scene, using a geometric subdivision criterion"): the cells of a
 * 2^δ grid over the scene's bounding cube that some triangle touches (exact
 * triangle/box overlap, common/triangle_box_overlap.h), each with the
 * area-weighted average normal of the triangles touching it (§5.3.1: "a voxel
 * has no normal ... approximated as an average amongst the intersecting
 * geometry") and the groups of their normals (surface_normals.h), and the
 * node pool that reaches them in δ fetches.
 *
 * The caller owns the gb_octree_leaves (gb_octree_leaves_free).
 */
#ifndef GB_CLUSTER_OCTREE_H
#define GB_CLUSTER_OCTREE_H

#include <stdint.h>

#include "light_octree.h"
#include "result.h"
#include "scene.h"
#include "surface_normals.h"

typedef struct gb_octree_leaves {
    uint32_t depth;             /* δ */
    float origin[3], size;      /* the cube: origin .. origin + size */
    uint32_t count;
    uint64_t *keys;             /* count, increasing: Morton code of the cell, x in bit 0 */
    float *normals;             /* count x 3, unit */
    float *points;              /* count x 3: where the leaf gathers, on its geometry
                                   (area-weighted mean of the points of its triangles
                                   nearest to the cell centre) */
    gb_surface_normal *surfaces;    /* count x GB_SURFACE_NORMALS: the normals of the
                                   triangles touching the cell, grouped */
    uint32_t *surface_counts;   /* count: groups of each leaf */
} gb_octree_leaves;

/* The leaves of depth `depth` (1..10) of scene's geometry, in Morton order. */
gb_result gb_octree_build(const gb_scene *scene, uint32_t depth, gb_octree_leaves *leaves,
                          gb_error *error);

/* The node pool over the leaves (light_octree.h): node 0 the root, children
 * of the last level are leaf indices. *nodes is malloc'ed. */
gb_result gb_octree_nodes(const gb_octree_leaves *leaves, gb_light_octree_node **nodes,
                          uint32_t *node_count, gb_error *error);

/* The normals at which leaf i is shaded (surface_normals.h): the groups of
 * its cell and of the 26 around it, merged; returns how many (at most
 * GB_SURFACE_NORMALS) it wrote to out. */
uint32_t gb_octree_shading_normals(const gb_octree_leaves *leaves, uint32_t i,
                                   gb_surface_normal out[GB_SURFACE_NORMALS]);

/* Leaf i's integer cell, and the edge of a leaf. */
void gb_octree_leaf_cell(const gb_octree_leaves *leaves, uint32_t i, uint32_t cell[3]);
float gb_octree_leaf_edge(const gb_octree_leaves *leaves);

void gb_octree_leaves_free(gb_octree_leaves *leaves);

#endif
