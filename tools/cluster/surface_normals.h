/* surface_normals.h — the normals at which a leaf's VDLs are shaded, so
 * that vdl.h can choose their count by the error there: the normals of the
 * geometry in the leaf's cell and in the 26 cells around it, since the
 * runtime's trilinear interpolation (common/light_octree_shading.h) reads a
 * leaf from points up to one cell away.
 *
 * A group list holds area-weighted unit normals: a normal within
 * GB_SURFACE_NORMAL_MERGE_COS of a group's joins it, else it starts one;
 * a list keeps at most GB_SURFACE_NORMALS groups, the largest areas. The
 * caller owns the arrays. */
#ifndef GB_CLUSTER_SURFACE_NORMALS_H
#define GB_CLUSTER_SURFACE_NORMALS_H

#include <stdint.h>

enum {
    GB_SURFACE_NORMALS = 8,         /* groups a leaf keeps */
    GB_SURFACE_NORMALS_GATHERED = 64, /* groups a list holds while it is filled */
};
#define GB_SURFACE_NORMAL_MERGE_COS 0.97f   /* 14 degrees */

typedef struct gb_surface_normal {
    float normal[3];            /* unit */
    float area;
} gb_surface_normal;

/* Adds the unit normal of weight area to groups[0..*count) (room for
 * capacity); when full, a normal that joins no group is dropped. */
void gb_surface_normals_add(gb_surface_normal *groups, uint32_t *count, uint32_t capacity,
                            const float normal[3], float area);

/* Sorts groups[0..*count) by area, largest first (ties by normal, so the
 * order is fixed), and keeps at most `keep`. */
void gb_surface_normals_keep_largest(gb_surface_normal *groups, uint32_t *count, uint32_t keep);

#endif
