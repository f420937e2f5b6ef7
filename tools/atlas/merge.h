/* merge.h — small charts joined to a neighbour when the join packs into
 * less atlas: a chart pays the texels it covers and a gutter of `padding`
 * texels around them (packing.h), so a chart of a few texels pays mostly
 * gutter, and two such charts that meet along an edge cost less as one.
 * The cost is measured on the chart's rectangle grown by the gutter, which
 * bounds its padded mask, at the density of a packing by rectangles.
 *
 * Decided here:
 * - a chart's cost is the area of its smallest rectangle (min_area_rect.h)
 *   at the density, rounded up to whole texels (at least 1) and grown by
 *   the padding on every side: what packing.h places;
 * - charts are taken in order of increasing cost (ties by index); one
 *   whose gutter costs more than its rectangle (small) is joined with the
 *   neighbour (across an edge gb_mesh_adjacency glues) sharing the most
 *   edges with it, then the next, GB_MERGE_CANDIDATES at most, whose union
 *   of at most GB_MERGE_MAX_TRIANGLES triangles LSCM maps soundly
 *   (gb_parameterize_disc: a disc, no fold, no overlap, no corner distorted
 *   beyond the context's max_distortion) and costs less than the two
 *   apart; the first such neighbour wins; passes repeat until one joins
 *   nothing (GB_MERGE_PASSES at most);
 * - the union takes the neighbour's place in the list, the small chart is
 *   removed; the order of the list is otherwise kept, so the result does
 *   not depend on anything but the charts and the density.
 *
 * The caller owns the list and the context (parameterize.h).
 */
#ifndef GB_ATLAS_MERGE_H
#define GB_ATLAS_MERGE_H

#include <stdint.h>

#include "parameterize.h"
#include "result.h"

#define GB_MERGE_CANDIDATES 4
#define GB_MERGE_MAX_TRIANGLES 4096
#define GB_MERGE_PASSES 2

/* The packing cost (texels) of a chart at density with padding. */
double gb_chart_cost(const gb_chart *chart, double density, uint32_t padding);

/* Joins charts of list as above; *merged: how many joins. */
gb_result gb_charts_merge(const gb_parameterize_context *context, gb_chart_list *list,
                          double density, uint32_t padding, uint32_t *merged, gb_error *error);

#endif
