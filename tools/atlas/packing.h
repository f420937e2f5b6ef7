/* packing.h — the charts placed in one atlas (vivianloc-2007 §4.2.3,
 * "packed into one 2-D atlas"): each chart turned to its smallest-area
 * bounding rectangle, scaled to one texel density, and its rectangle
 * placed by a skyline packer, tallest first, with `padding` texels of
 * gutter around it.
 *
 * Decided here:
 * - a chart is turned so that its rectangle's long side runs along u;
 * - a chart's rect (gb_atlas_chart.rect, padding excluded) is its extent
 *   in texels rounded up (at least 1), the chart at its top left corner;
 *   the texels its triangles touch are the rect's, so with a padding of
 *   at least 1 a bilinear read anywhere on the chart touches only its own
 *   rect and its gutter;
 * - every chart is scaled up, the same along u and v (its angles kept),
 *   until its box fills its rect on one side: a chart of a fraction of a
 *   texel gets the texel its rect costs anyway (so no triangle shrinks to
 *   nothing), a large one gains under a texel a side;
 * - the skyline packer puts each rect at the lowest place it fits, then
 *   the leftmost; ties in the order by height, width, then chart index;
 * - --size N: the largest density (bisection on its logarithm, 40 steps)
 *   at which every rect fits an N x N atlas; --texels-per-unit T: the
 *   atlas as wide as the square root of the rects' area over 0.9 (at least
 *   the widest rect), as tall as they pile.
 *
 * The caller owns the list and every output array.
 */
#ifndef GB_ATLAS_PACKING_H
#define GB_ATLAS_PACKING_H

#include <stdint.h>

#include "parameterize.h"
#include "result.h"

typedef struct gb_packing_options {
    double texels_per_unit;     /* > 0: this density; 0: the largest that fits size */
    uint32_t size;              /* the atlas side when choosing the density */
    uint32_t padding;           /* texels of gutter around every rect */
} gb_packing_options;

typedef struct gb_packing {
    uint32_t width, height;     /* texels */
    double texels_per_unit;
    uint32_t *rects;            /* 4 per chart: x, y, width, height (padding excluded) */
    double *boxes;              /* 4 per chart: u and v minimum, u and v extent (world) */
} gb_packing;

/* Turns every chart's UVs (in place) to its smallest rectangle, long side
 * along u. */
gb_result gb_packing_orient(gb_chart_list *list, gb_error *error);

/* Places the oriented charts; on GB_OK the caller frees packing with
 * gb_packing_free. Fails (GB_ERROR_UNSUPPORTED) when they cannot fit. */
gb_result gb_pack(const gb_chart_list *list, const gb_packing_options *options,
                  gb_packing *packing, gb_error *error);
void gb_packing_free(gb_packing *packing);

/* The texel coordinates (x right, y down, as the atlas's u and v times its
 * size) of chart i's corners: 6 per triangle into texels. */
void gb_packing_texels(const gb_chart_list *list, const gb_packing *packing, uint32_t i,
                       double *texels);

#endif
