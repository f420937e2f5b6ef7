/* chart_mask.h — a chart's padded mask, the shape packing.h places: the
 * texels its triangles overlap, grown by the padding along x and y, by
 * the raster the atlas file is checked with (formats/atlas_mask.h), as
 * runs of texels row by row.
 *
 * The chart's corners are given in its own texel coordinates: its rect's
 * top left corner at (0, 0), every corner inside the rect less the margin
 * on every side, so that the mask's box is the rect grown by the padding
 * and the mask at (x, y) is the chart's at rect (x + P, y + P) (the raster
 * moves with a whole-texel translation).
 *
 * The caller owns the mask (gb_chart_mask_free) and the corners.
 */
#ifndef GB_ATLAS_CHART_MASK_H
#define GB_ATLAS_CHART_MASK_H

#include <stdint.h>

#include "atlas_mask.h"

typedef struct gb_chart_mask {
    uint32_t width, height;     /* the box: the rect's sides plus twice the padding */
    uint32_t *row_starts;       /* height + 1: row r's runs are runs[row_starts[r] ..
                                   row_starts[r + 1]) */
    uint32_t *runs;             /* 2 per run: its first and last column, left to right */
    uint32_t *row_longest;      /* height: each row's longest run, texels */
    uint32_t widest_row;        /* the row of the longest run */
    uint32_t longest_run;       /* texels */
    uint64_t texels;            /* in the mask */
} gb_chart_mask;

/* The mask of triangle_count triangles (corners: 6 per triangle) in a
 * rect of rect_width x rect_height texels, rastered with margin (atlas_mask.h)
 * and padding. scratch: the caller's, zeroed before first use, freed with
 * gb_atlas_mask_free. Returns 1, or 0 when out of memory. */
int gb_chart_mask_make(gb_chart_mask *mask, const double *corners, uint32_t triangle_count,
                       uint32_t rect_width, uint32_t rect_height, double margin,
                       uint32_t padding, gb_atlas_mask *scratch);
void gb_chart_mask_free(gb_chart_mask *mask);

#endif
