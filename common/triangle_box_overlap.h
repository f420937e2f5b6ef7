/* triangle_box_overlap.h — exact separating-axis test between a triangle and
 * axis-aligned boxes (Akenine-Möller, "Fast 3D triangle-box overlap testing",
 * JGT 2001): the triangle and a box are disjoint iff their projections are
 * disjoint on one of 13 axes — the 3 box face normals, the triangle normal,
 * and the 9 cross products of a triangle edge with a box edge.
 *
 * Conservative: a triangle that only touches the closed box (a vertex on a
 * face, an edge along an edge, a wall lying in a face) overlaps it. Each
 * projection gap is compared against a bound of its own floating-point
 * rounding error, so rounding can add a touching box but never drop one.
 * Degenerate triangles (a segment, a point) are handled by the same axes:
 * their zero axes never separate, and the remaining ones are exactly the
 * separating axes of a segment or a point.
 *
 * A triangle is prepared once (its axes and projected intervals) for boxes of
 * one size, then tested against many box centres, which is what a voxelizer
 * does. The caller owns the gb_triangle_boxes (plain data, no release).
 */
#ifndef GB_TRIANGLE_BOX_OVERLAP_H
#define GB_TRIANGLE_BOX_OVERLAP_H

enum { GB_TRIANGLE_AXIS_COUNT = 10 }; /* normal + 9 edge cross products */

typedef struct gb_triangle_boxes {
    double lower[3], upper[3];          /* bounds of the triangle (face axes) */
    double half[3];                     /* half extent of every box */
    double axis[GB_TRIANGLE_AXIS_COUNT][3];
    double low[GB_TRIANGLE_AXIS_COUNT];  /* triangle's projection on axis */
    double high[GB_TRIANGLE_AXIS_COUNT];
    double radius[GB_TRIANGLE_AXIS_COUNT];/* box's half projection on axis */
    double slack[GB_TRIANGLE_AXIS_COUNT];/* rounding bound per unit coordinate */
    double magnitude;                   /* largest |vertex coordinate| */
} gb_triangle_boxes;

/* Prepares the triangle vertex[0..2] for boxes of half extent half. */
void gb_triangle_boxes_prepare(gb_triangle_boxes *triangle, const double vertex[3][3],
                               const double half[3]);

/* 1 if the prepared triangle touches the closed box of centre centre. */
int gb_triangle_boxes_overlap(const gb_triangle_boxes *triangle, const double centre[3]);

/* Same as the two above for one box: 1 if the triangle touches the closed box
 * centre ± half. */
int gb_triangle_box_overlap(const double vertex[3][3], const double centre[3],
                            const double half[3]);

#endif
