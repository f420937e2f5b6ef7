/* parameterize.h — the UVs of each chart: a chart of charts.h, cut into
 * discs (discs.h), each disc mapped by LSCM (lscm.h), until every triangle
 * has positive UV area.
 *
 * Decided here, for each piece (a list of scene triangles, connected):
 * - one triangle is laid flat exactly (its longest edge along u, its
 *   corners counterclockwise), a "lone" chart;
 * - a piece that is not a disc, or that CGAL cannot parameterise (an error
 *   code or an exception), is split in two (discs.h) and each half tried
 *   again;
 * - LSCM's result is scaled so that the chart's UV area equals its world
 *   area, and mirrored (v -> -v) when its total signed area is negative;
 * - a chart with a triangle still of UV area <= 0 (folded), or with two
 *   of its triangles overlapping (LSCM is not injective on every disc),
 *   is split in two, each half tried again (both tested in fixed point
 *   over the chart's own box, overlap.h). Halving until the folded
 *   triangle stands alone, rather than laying it alone at once, keeps
 *   its neighbours in larger charts: on Sponza (cone 60) 4270 charts (348 lone
 *   triangles) against 5561 (1531), fill ratio 0.332 against 0.313;
 * - so is a chart with a corner whose UV angle differs from its 3-D angle
 *   by more than max_distortion degrees (LSCM bends the slivers of a
 *   chart of many tiny triangles): a triangle laid alone keeps its angles;
 * - so is a chart that covers less than GB_MIN_RECT_FILL of its smallest
 *   rectangle when that rectangle exceeds its UV area by more than
 *   max_waste (world units squared; atlas_build.h sets it to a share of
 *   the scene's area): an arc of a spiral stair or a long L would leave
 *   most of its rect empty, and the atlas packs rects. Only large waste
 *   counts: splitting small charts costs more padding than it saves.
 * Every path shrinks the piece, so the work ends; no UV is ever NaN.
 *
 * A gb_chart's uvs are per triangle corner, in world units, in the scene's
 * corner order. The caller owns the gb_chart_list (gb_chart_list_free).
 */
#ifndef GB_ATLAS_PARAMETERIZE_H
#define GB_ATLAS_PARAMETERIZE_H

#include <stdint.h>

#include "charts.h"
#include "result.h"
#include "scene.h"

#define GB_MIN_RECT_FILL 0.5

typedef struct gb_chart {
    uint32_t triangle_count;
    uint32_t *triangles;        /* scene triangle indices */
    double *uvs;                /* 6 per triangle: (u, v) of corners 0, 1, 2 */
    double area;                /* world units squared */
} gb_chart;

typedef struct gb_chart_list {
    gb_chart *charts;
    uint32_t count;
    size_t capacity;
} gb_chart_list;

typedef struct gb_parameterize_stats {
    uint32_t lscm_charts;       /* discs LSCM mapped and kept */
    uint32_t lscm_failures;     /* CGAL errors (each piece then split) */
    uint32_t splits;            /* pieces split for not being discs */
    uint32_t folded;            /* LSCM charts split for a triangle of UV area <= 0 */
    uint32_t overlapping;       /* LSCM charts split for overlapping themselves */
    uint32_t wasteful;          /* split for wasting more than max_waste of their rectangle */
    uint32_t distorted;         /* split for a corner distorted beyond max_distortion */
} gb_parameterize_stats;

/* What every piece is parameterised with; the caller's. */
typedef struct gb_parameterize_context {
    const gb_scene *scene;
    const gb_mesh_adjacency *adjacency;
    uint32_t *local_of;         /* discs.h's scratch array */
    double max_waste;           /* world units squared; 0: no limit */
    double max_distortion;      /* degrees, per corner */
    gb_parameterize_stats stats;/* counts added to */
} gb_parameterize_context;

/* Appends the charts of the connected piece triangles[0..count-1] to list. */
gb_result gb_parameterize_piece(gb_parameterize_context *context, const uint32_t *triangles,
                                uint32_t count, gb_chart_list *list, gb_error *error);

/* Appends the piece triangles[0..count-1] as one chart, *mapped = 1, when
 * it is a disc that LSCM maps soundly (no CGAL failure, no fold, no two
 * triangles overlapping, no corner distorted beyond max_distortion; the
 * waste of its rectangle is the caller's to judge); else *mapped = 0 and
 * the list is unchanged. Counts nothing in context->stats. */
gb_result gb_parameterize_disc(const gb_parameterize_context *context, const uint32_t *triangles,
                               uint32_t count, gb_chart_list *list, int *mapped, gb_error *error);

/* The largest angle distortion (degrees) of a chart's corners at its UVs:
 * |UV angle - 3-D angle|. */
double gb_chart_max_distortion(const gb_scene *scene, const gb_chart *chart);

/* Appends one chart of scene triangle t laid flat. */
gb_result gb_chart_list_add_flat(const gb_scene *scene, uint32_t t, gb_chart_list *list,
                                 gb_error *error);

/* A new chart of count triangles at the end of list, its arrays allocated
 * and unset, its area 0; NULL when out of memory (the list unchanged). */
gb_chart *gb_chart_list_append(gb_chart_list *list, uint32_t count);
/* Removes chart i (its arrays freed), moving the last chart into its place. */
void gb_chart_list_remove(gb_chart_list *list, uint32_t i);
void gb_chart_list_free(gb_chart_list *list);

#endif
