/* triangle_box_overlap.c — exact separating-axis triangle/box test
 * (Akenine-Möller 2001), prepared once per triangle, conservative under
 * rounding (see triangle_box_overlap.h). */
#include "triangle_box_overlap.h"

#include <float.h>
#include <math.h>

/* Rounding of a dot product of 3 terms, a sum and a comparison stays below
 * this many units of DBL_EPSILON times |axis|_1 times the largest coordinate
 * involved (a generous bound: 3 for the dot products, 2 for the sums). */
static const double SLACK_EPSILONS = 16.0;

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The triangle normal, then edge_e x unit_u for e, u in 0..2. */
static void set_axes(gb_triangle_boxes *triangle, const double vertex[3][3])
{
    double edge[3][3];
    for (int e = 0; e < 3; ++e)
        for (int d = 0; d < 3; ++d)
            edge[e][d] = vertex[(e + 1) % 3][d] - vertex[e][d];
    cross(edge[0], edge[1], triangle->axis[0]);
    for (int e = 0; e < 3; ++e)
        for (int u = 0; u < 3; ++u) {
            double unit[3] = {0, 0, 0};
            unit[u] = 1;
            cross(edge[e], unit, triangle->axis[1 + 3 * e + u]);
        }
}

/* Projection interval of the triangle, half projection of the box and the
 * rounding bound of every axis. */
static void set_intervals(gb_triangle_boxes *triangle, const double vertex[3][3])
{
    for (int a = 0; a < GB_TRIANGLE_AXIS_COUNT; ++a) {
        const double *axis = triangle->axis[a];
        double p0 = dot(axis, vertex[0]), p1 = dot(axis, vertex[1]), p2 = dot(axis, vertex[2]);
        triangle->low[a] = fmin(p0, fmin(p1, p2));
        triangle->high[a] = fmax(p0, fmax(p1, p2));
        double norm1 = fabs(axis[0]) + fabs(axis[1]) + fabs(axis[2]);
        triangle->radius[a] = triangle->half[0] * fabs(axis[0])
                              + triangle->half[1] * fabs(axis[1])
                              + triangle->half[2] * fabs(axis[2]);
        triangle->slack[a] = SLACK_EPSILONS * DBL_EPSILON * norm1;
    }
}

void gb_triangle_boxes_prepare(gb_triangle_boxes *triangle, const double vertex[3][3],
                               const double half[3])
{
    triangle->magnitude = 0;
    for (int d = 0; d < 3; ++d) {
        triangle->half[d] = half[d];
        triangle->lower[d] = fmin(vertex[0][d], fmin(vertex[1][d], vertex[2][d]));
        triangle->upper[d] = fmax(vertex[0][d], fmax(vertex[1][d], vertex[2][d]));
        triangle->magnitude = fmax(triangle->magnitude,
                                   fmax(fabs(triangle->lower[d]), fabs(triangle->upper[d])));
    }
    set_axes(triangle, vertex);
    set_intervals(triangle, vertex);
}

int gb_triangle_boxes_overlap(const gb_triangle_boxes *triangle, const double centre[3])
{
    double largest_half = fmax(triangle->half[0], fmax(triangle->half[1], triangle->half[2]));
    double scale = triangle->magnitude + largest_half
                   + fmax(fabs(centre[0]), fmax(fabs(centre[1]), fabs(centre[2])));
    /* The 3 face normals: the bounds of the triangle against the box. */
    for (int d = 0; d < 3; ++d) {
        double slack = 2 * DBL_EPSILON * scale;
        if (centre[d] + triangle->half[d] < triangle->lower[d] - slack
            || centre[d] - triangle->half[d] > triangle->upper[d] + slack)
            return 0;
    }
    /* The normal and the 9 edge cross products. */
    for (int a = 0; a < GB_TRIANGLE_AXIS_COUNT; ++a) {
        double s = dot(triangle->axis[a], centre);
        double slack = triangle->slack[a] * scale;
        if (s + triangle->radius[a] < triangle->low[a] - slack
            || s - triangle->radius[a] > triangle->high[a] + slack)
            return 0;
    }
    return 1;
}

int gb_triangle_box_overlap(const double vertex[3][3], const double centre[3],
                            const double half[3])
{
    gb_triangle_boxes triangle;
    gb_triangle_boxes_prepare(&triangle, vertex, half);
    return gb_triangle_boxes_overlap(&triangle, centre);
}
