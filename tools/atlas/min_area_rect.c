/* min_area_rect.c — convex hull and rotating calipers (min_area_rect.h). */
#include "min_area_rect.h"

#include <math.h>
#include <stdlib.h>

static int by_x_then_y(const void *a, const void *b)
{
    const double *p = a, *q = b;
    if (p[0] != q[0])
        return p[0] < q[0] ? -1 : 1;
    return (p[1] > q[1]) - (p[1] < q[1]);
}

static double turn(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

size_t gb_convex_hull(double *points, size_t count, double *hull)
{
    qsort(points, count, 2 * sizeof *points, by_x_then_y);
    size_t k = 0;
    for (size_t i = 0; i < count; ++i) {   /* lower hull */
        while (k >= 2 && turn(hull + 2 * (k - 2), hull + 2 * (k - 1), points + 2 * i) <= 0.0)
            --k;
        hull[2 * k] = points[2 * i];
        hull[2 * k + 1] = points[2 * i + 1];
        ++k;
    }
    for (size_t i = count - 1, lower = k + 1; i-- > 0;) {   /* upper hull */
        while (k >= lower && turn(hull + 2 * (k - 2), hull + 2 * (k - 1), points + 2 * i) <= 0.0)
            --k;
        hull[2 * k] = points[2 * i];
        hull[2 * k + 1] = points[2 * i + 1];
        ++k;
    }
    return k > 1 ? k - 1 : k;   /* the last point is the first again */
}

/* Width along (c, s) times width across it, of the hull. */
static double area_along(const double *hull, size_t n, double c, double s)
{
    double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY, hi_y = -INFINITY;
    for (size_t i = 0; i < n; ++i) {
        double x = c * hull[2 * i] + s * hull[2 * i + 1];
        double y = -s * hull[2 * i] + c * hull[2 * i + 1];
        lo_x = fmin(lo_x, x);
        hi_x = fmax(hi_x, x);
        lo_y = fmin(lo_y, y);
        hi_y = fmax(hi_y, y);
    }
    return (hi_x - lo_x) * (hi_y - lo_y);
}

void gb_min_area_rect(double *points, size_t count, double *scratch, double *c, double *s)
{
    *c = 1.0;
    *s = 0.0;
    if (count < 2)
        return;
    size_t n = gb_convex_hull(points, count, scratch);
    double best = INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const double *a = scratch + 2 * i, *b = scratch + 2 * ((i + 1) % n);
        double dx = b[0] - a[0], dy = b[1] - a[1], length = hypot(dx, dy);
        if (!(length > 0.0))
            continue;
        double area = area_along(scratch, n, dx / length, dy / length);
        if (area < best) {
            best = area;
            *c = dx / length;
            *s = dy / length;
        }
    }
}
