/* charts.h — the scene cut into charts for the atlas (vivianloc-2007
 * §4.2.3, "the scene is cut into charts"): regions grown over shared edges
 * while every triangle's normal stays within a cone of the chart's seed.
 *
 * Decided here:
 * - Triangles are joined only across an edge that exactly two triangles
 *   use, in opposite directions. Vertices are welded by position: two
 *   indices of the very same (x, y, z) floats are one vertex (Sponza's OBJ
 *   repeats 42% of its positions under new indices: 8780 pieces by index,
 *   91 by position). A non-manifold edge, a border, or two triangles wound
 *   against each other always separate charts.
 * - Seeds are taken by decreasing area (ties by index), so large flat
 *   triangles start charts; a chart grows best first: the candidate whose
 *   normal is closest to the seed's is added next, and a triangle joins
 *   when n . n_seed >= cos(cone).
 * - A triangle without a normal (zero area in doubles) joins whichever
 *   chart reaches it first: it has no direction to disagree with.
 * Charts come out connected; they need not be discs yet (discs.h splits
 * them).
 *
 * The caller owns every array; gb_mesh_adjacency_free releases one.
 */
#ifndef GB_ATLAS_CHARTS_H
#define GB_ATLAS_CHARTS_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

#define GB_NO_NEIGHBOUR UINT32_MAX

/* Per triangle t, per edge e (corners e and e+1 mod 3): the triangle
 * across it, or GB_NO_NEIGHBOUR (border, non-manifold, or wound the same
 * way round). Symmetric: if t's edge e has neighbour n, n has t. */
typedef struct gb_mesh_adjacency {
    uint32_t triangle_count;
    uint32_t *neighbours;       /* 3 * triangle_count */
} gb_mesh_adjacency;

gb_result gb_mesh_adjacency_build(const gb_scene *scene, gb_mesh_adjacency *adjacency,
                                  gb_error *error);
void gb_mesh_adjacency_free(gb_mesh_adjacency *adjacency);

/* The edge of triangle n that runs back to triangle t (its neighbour):
 * 0..2, or -1 if n does not list t. */
int gb_mesh_adjacency_edge_to(const gb_mesh_adjacency *adjacency, uint32_t n, uint32_t t);

/* Grows the charts: chart_of (triangle_count, the caller's) gets each
 * triangle's chart, numbered from 0 in order of their seeds; *chart_count
 * their number. cone_degrees in (0, 180]. */
gb_result gb_charts_grow(const gb_scene *scene, const gb_mesh_adjacency *adjacency,
                         double cone_degrees, uint32_t *chart_of, uint32_t *chart_count,
                         gb_error *error);

#endif
