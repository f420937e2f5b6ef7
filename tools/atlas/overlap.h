/* overlap.h — the exact test that no two triangles of an atlas overlap in
 * UV space: neither two of different charts nor two of one chart, beyond
 * the edges and corners they may share.
 *
 * Corners are integers (the atlas's UVs in fixed point: u * 2^24, see
 * atlas_build.h), so the orientation predicate is exact in 64-bit
 * integers (|coordinate| <= 2^24: products below 2^51). Two triangles
 * overlap when their interiors meet, that is when no line through an edge
 * of either has the other wholly on its far side or on it (two convex
 * polygons whose interiors are disjoint are separated by the line of one
 * of their edges). Candidate pairs come from a uniform grid over UV space,
 * about one triangle per cell: pairs whose bounding boxes overlap (more
 * than touch), each tested once, in the cell holding the low corner of
 * the boxes' overlap.
 * Every triangle must be counterclockwise with positive area (the caller
 * has checked that).
 *
 * The caller owns every array.
 */
#ifndef GB_ATLAS_OVERLAP_H
#define GB_ATLAS_OVERLAP_H

#include <stdint.h>

#include "result.h"

#define GB_OVERLAP_ONE (INT64_C(1) << 24)

/* Whether triangles a and b (6 coordinates each, counterclockwise)
 * overlap: 1 or 0. */
int gb_triangles_overlap(const int64_t *a, const int64_t *b);

/* Twice the signed area of a triangle (6 coordinates). */
static inline int64_t gb_fixed_twice_area(const int64_t *p)
{
    return (p[2] - p[0]) * (p[5] - p[1]) - (p[3] - p[1]) * (p[4] - p[0]);
}

/* Finds overlapping pairs among count triangles of corners (6 each, every
 * coordinate in 0 .. GB_OVERLAP_ONE): the first pairs_capacity of them in
 * pairs (2 triangle indices each), all of them counted in *pair_count. */
gb_result gb_find_overlaps(const int64_t *corners, uint32_t count, uint32_t *pairs,
                           uint32_t pairs_capacity, uint64_t *pair_count, gb_error *error);

/* One chart's UVs (6 doubles per triangle, any scale) in fixed point
 * over their own box (one scale for both axes, the box's longer side
 * 0 .. GB_OVERLAP_ONE): into fixed (6 per triangle, the caller's). */
void gb_uvs_to_fixed(const double *uvs, uint32_t count, int64_t *fixed);

/* Whether a chart's UVs are sound at the precision of gb_uvs_to_fixed:
 * every triangle of positive area (else folded[i] = 1) and no two
 * overlapping. Returns the number of folded triangles in *folds and of
 * overlapping pairs in *overlaps. */
gb_result gb_chart_uvs_check(const double *uvs, uint32_t count, uint8_t *folded, uint32_t *folds,
                             uint64_t *overlaps, gb_error *error);

#endif
