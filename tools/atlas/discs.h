/* discs.h — a chart as a mesh of its own, whether it is a topological disc
 * (which LSCM needs), and how to cut it when it is not.
 *
 * A chart's triangles are glued across the edges charts.h joins
 * (gb_mesh_adjacency) when both sides are in the chart; corners of one
 * scene vertex are one chart vertex only when glued through such edges, so
 * two fans meeting at a vertex get a vertex each and the chart mesh is
 * always a manifold with border. It is a disc when it is connected and its
 * Euler characteristic V - E + F is 1 (an orientable connected surface
 * with b borders and genus g has 2 - 2g - b).
 *
 * Decided here: a chart that is not a disc is cut in two by a breadth-first
 * flood from two seeds at once, the triangles farthest apart (the one whose
 * centroid is farthest from the chart's centroid, then the one farthest
 * from it); each half is connected, and repeated halving ends at single
 * triangles, which are discs.
 *
 * The caller owns the gb_chart_mesh (gb_chart_mesh_free) and the triangle
 * lists. local_of is a scratch array of scene->triangle_count entries, all
 * GB_NO_NEIGHBOUR between calls (each call leaves it so).
 */
#ifndef GB_ATLAS_DISCS_H
#define GB_ATLAS_DISCS_H

#include <stdint.h>

#include "charts.h"
#include "result.h"
#include "scene.h"

typedef struct gb_chart_mesh {
    uint32_t triangle_count;    /* the chart's, in the order given */
    const uint32_t *triangles;  /* scene triangle indices (the caller's) */
    uint32_t vertex_count;
    uint32_t *corners;          /* 3 per triangle: its chart vertices */
    double *positions;          /* 3 per chart vertex */
    uint32_t *neighbours;       /* 3 per triangle: the chart triangle across
                                   edge e, or GB_NO_NEIGHBOUR */
    int64_t euler;              /* V - E + F */
    uint32_t components;        /* connected over glued edges */
} gb_chart_mesh;

gb_result gb_chart_mesh_build(const gb_scene *scene, const gb_mesh_adjacency *adjacency,
                              const uint32_t *triangles, uint32_t triangle_count,
                              uint32_t *local_of, gb_chart_mesh *mesh, gb_error *error);
void gb_chart_mesh_free(gb_chart_mesh *mesh);

static inline int gb_chart_mesh_is_disc(const gb_chart_mesh *mesh)
{
    return mesh->components == 1 && mesh->euler == 1;
}

/* Each triangle's part (0 .. *part_count - 1, into part, triangle_count of
 * the caller's): the connected components when there are several, else the
 * two halves of the flood. */
gb_result gb_chart_mesh_split(const gb_chart_mesh *mesh, uint32_t *part, uint32_t *part_count,
                              gb_error *error);

/* The connected components of the chart triangles with keep[i] set, over
 * glued edges: component[i] for each kept triangle (others untouched),
 * *component_count. */
gb_result gb_chart_mesh_components(const gb_chart_mesh *mesh, const uint8_t *keep,
                                   uint32_t *component, uint32_t *component_count,
                                   gb_error *error);

#endif
