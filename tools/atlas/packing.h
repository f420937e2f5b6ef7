/* packing.h — the charts placed in one atlas (vivianloc-2007 §4.2.3,
 * "packed into one 2-D atlas") by their shape, as xatlas packs: each
 * chart turned to its smallest-area bounding rectangle and scaled to one
 * texel density, then its padded mask (chart_mask.h: the texels its
 * triangles overlap, grown by `padding` texels along x and y) placed on
 * the atlas's occupied texels (occupancy.h) where it meets none of them.
 * Two charts' padded masks never share a texel, which is the file's rule
 * (formats/atlas.h): the charts' triangles are at least twice the padding
 * apart along x or y.
 *
 * Decided here:
 * - a chart is turned so that its rectangle's long side runs along u;
 * - a chart's rect (gb_atlas_chart.rect, padding excluded) is its extent
 *   in texels plus four times the margin, rounded up (at least 1), and
 *   its box starts twice the margin from the rect's top left corner, so
 *   that every corner is at least twice the margin inside: its mask,
 *   rastered with the margin before the UVs are rounded (atlas_mask.h),
 *   covers what the reader rasters after and stays in the rect. At --size
 *   twice the margin is exactly two units of the fixed point, so a
 *   needle's lowest corner rounds to itself and the needle keeps the
 *   area it has (a chart centred in its rect would round every corner and
 *   collapse more needles). The mask's box is the rect grown by the
 *   padding; rects may overlap;
 * - every chart is scaled up, the same along u and v (its angles kept),
 *   until its box fills its rect less the margins on one side: a chart of
 *   a fraction of a texel gets the texel it costs anyway (so no triangle
 *   shrinks to nothing), a large one gains under a texel a side;
 * - charts are placed biggest first (their padded rect's area, then
 *   height, then index), each at the first place where its mask, as it is
 *   or turned a quarter ((x, y) -> (height - y, x): a turn keeps every
 *   triangle counterclockwise, a mirror would not), fits: the lowest row,
 *   then the leftmost column, then unturned;
 * - --size N: the largest density at which every mask fits an N x N
 *   atlas: first the largest at which the padded rects fit by a skyline
 *   packer (bisection on the density's logarithm, 40 steps, cheap; a mask
 *   lies in its padded rect, so those places are a valid packing too),
 *   then by shape from it up: GB_PACKING_SHAPE_STEPS more densities, each
 *   the last that fitted grown as its rows would grow to the atlas's (the
 *   area goes as the density squared; by 1 % at least) until one fails,
 *   then bisection (on the logarithm) between the last that fitted and the
 *   first that failed, below the density at which the charts alone would
 *   fill the atlas; the densest packing that fitted is kept (the
 *   skyline's if none by shape). A hint (the density of the last round of
 *   atlas_build.h's repairs) is tried first and kept if it fits;
 * - --texels-per-unit T: the atlas as wide as the square root of the
 *   padded rects' area over 0.9 (at least the widest mask), as tall as the
 *   masks pile.
 *
 * The caller owns the list and every output array.
 */
#ifndef GB_ATLAS_PACKING_H
#define GB_ATLAS_PACKING_H

#include <stdint.h>

#include "parameterize.h"
#include "result.h"

#define GB_PACKING_SHAPE_STEPS 5

typedef struct gb_packing_options {
    double texels_per_unit;     /* > 0: this density; 0: the largest that fits size */
    uint32_t size;              /* the atlas side when choosing the density */
    uint32_t padding;           /* texels of gutter around every chart's mask */
    double margin;              /* texels a corner may move after packing (rounding), >= 0 */
    double hint;                /* with size: a density tried first, kept if it fits; 0: none */
} gb_packing_options;

typedef struct gb_packing {
    uint32_t width, height;     /* texels */
    double texels_per_unit;
    uint32_t *rects;            /* 4 per chart: x, y, width, height (padding excluded) */
    double *boxes;              /* 4 per chart: u and v minimum, u and v extent (world) */
    uint8_t *turned;            /* per chart: 1 when turned a quarter */
    double margin;              /* the options' */
} gb_packing;

/* Turns every chart's UVs (in place) to its smallest rectangle, long side
 * along u. */
gb_result gb_packing_orient(gb_chart_list *list, gb_error *error);

/* Places the oriented charts by shape; on GB_OK the caller frees packing
 * with gb_packing_free. Fails (GB_ERROR_UNSUPPORTED) when they cannot fit. */
gb_result gb_pack(const gb_chart_list *list, const gb_packing_options *options,
                  gb_packing *packing, gb_error *error);
/* The same by padded rects alone (the skyline): quicker, less dense; what
 * merge.h's choice of density needs. */
gb_result gb_pack_rects(const gb_chart_list *list, const gb_packing_options *options,
                        gb_packing *packing, gb_error *error);
void gb_packing_free(gb_packing *packing);

/* The texel coordinates (x right, y down, as the atlas's u and v times its
 * size) of chart i's corners: 6 per triangle into texels. */
void gb_packing_texels(const gb_chart_list *list, const gb_packing *packing, uint32_t i,
                       double *texels);

#endif
