/* uv_distance.h — how far apart two triangles of an atlas are along x or
 * y, measured apart from the atlas's own raster (formats/atlas_mask.h):
 * the Chebyshev distance min over points a, b of max(|ax - bx|, |ay - by|),
 * which two charts' disjoint padded masks make at least twice the padding
 * (test_atlas.c, fuzz_atlas.c check it pair by pair).
 *
 * For convex sets the distance in a norm is the largest gap between them
 * along a direction n of dual norm 1 (|nx| + |ny| = 1 for the max norm):
 * min over b of n.b - max over a of n.a. The best n is an axis (the
 * square of the max norm meets the other set along a side) or a normal of
 * an edge of either triangle (it meets it at a corner), so those ten
 * directions, both ways, suffice. Corners are texel coordinates, 6 each.
 */
#ifndef GB_TEST_UV_DISTANCE_H
#define GB_TEST_UV_DISTANCE_H

#include <math.h>

/* min over b of n.b - max over a of n.a, n scaled to |nx| + |ny| = 1. */
static inline double uv_gap_along(const double *a, const double *b, double nx, double ny)
{
    double norm = fabs(nx) + fabs(ny);
    if (!(norm > 0.0))
        return -INFINITY;
    nx /= norm;
    ny /= norm;
    double a_max = -INFINITY, b_min = INFINITY;
    for (int k = 0; k < 3; ++k) {
        a_max = fmax(a_max, nx * a[2 * k] + ny * a[2 * k + 1]);
        b_min = fmin(b_min, nx * b[2 * k] + ny * b[2 * k + 1]);
    }
    return b_min - a_max;
}

/* The distance along x or y between triangles a and b (0 when they meet). */
static inline double uv_distance(const double *a, const double *b)
{
    double directions[10][2] = {{1, 0}, {0, 1}};
    int count = 2;
    for (int t = 0; t < 2; ++t) {
        const double *p = t ? b : a;
        for (int e = 0; e < 3; ++e) {
            const double *s = p + 2 * e, *q = p + 2 * ((e + 1) % 3);
            directions[count][0] = q[1] - s[1];
            directions[count][1] = s[0] - q[0];
            ++count;
        }
    }
    double best = 0.0;
    for (int i = 0; i < count; ++i)
        for (int sign = -1; sign <= 1; sign += 2)
            best = fmax(best, uv_gap_along(a, b, sign * directions[i][0],
                                           sign * directions[i][1]));
    return best;
}

#endif
