/* min_area_rect.h — the smallest-area rectangle around a set of 2-D points
 * (Freeman & Shapira 1975: one of its sides lies along an edge of the
 * convex hull), found by the convex hull (Andrew's monotone chain) and
 * each hull edge's direction tried in turn (what rotating calipers sweep,
 * measured directly: O(h^2) for h hull points, small for a chart).
 *
 * gb_min_area_rect gives the rotation that makes that rectangle axis
 * aligned: (x, y) -> (c x + s y, -s x + c y) with *c = cos, *s = sin of the
 * edge's angle. Fewer than three distinct points, or all collinear: the
 * rotation putting them along x. The caller owns points (count * 2
 * doubles, unchanged); scratch is the caller's too, room for count + 1
 * points (2 doubles each).
 */
#ifndef GB_ATLAS_MIN_AREA_RECT_H
#define GB_ATLAS_MIN_AREA_RECT_H

#include <stddef.h>

/* The convex hull of points, counterclockwise, into hull (room for
 * count + 1 points); returns its number of points (collinear ones left
 * out). points itself is reordered (sorted). */
size_t gb_convex_hull(double *points, size_t count, double *hull);

void gb_min_area_rect(double *points, size_t count, double *scratch, double *c, double *s);

#endif
