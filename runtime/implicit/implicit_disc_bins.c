/* implicit_disc_bins.c — the bins through which a point sees a disc (see
 * implicit_disc_bins.h). */
#include "implicit_disc_bins.h"

#include <math.h>

#include "vec3.h"

/* Where the discs of one surface overlap, a bin's ray meets several at the
 * same distance, and rounding would choose between them. The distance
 * visited is lengthened by up to this fraction, by how far from the centre
 * the ray meets the disc, so that the disc whose centre is nearest holds
 * the bin: the element whose cell the ray meets. */
#define OFF_CENTRE_LENGTHENING 0x1p-10f

/* The larger and the smaller of x and y; y when x is not a number. For a
 * y that is a number, fmaxf and fminf, which are library calls at -O2 (and
 * link creation calls these millions of times). */
static inline float larger(float x, float y)
{
    return x > y ? x : y;
}

static inline float smaller(float x, float y)
{
    return x < y ? x : y;
}

/* The cells [first, last] of a face's n that the interval [lowest, highest]
 * of u (or v) reaches. */
static void cell_range(float lowest, float highest, int n, int *first, int *last)
{
    int i = (int)floorf(0.5f * (larger(lowest, -1.0f) + 1.0f) * (float)n);
    int j = (int)floorf(0.5f * (smaller(highest, 1.0f) + 1.0f) * (float)n);
    *first = i < 0 ? 0 : i >= n ? n - 1 : i;
    *last = j < 0 ? 0 : j >= n ? n - 1 : j;
}

/* The range of x / a over x in [x0, x1], a in [a0, a1] with 0 < a0. */
static void quotient_range(float x0, float x1, float a0, float a1, float *lowest,
                           float *highest)
{
    *lowest = smaller(x0 / a0, x0 / a1);
    *highest = larger(x1 / a0, x1 / a1);
}

void gb_implicit_disc_bins(const gb_implicit_bins *bins, const float from[3],
                           const float centre[3], const float normal[3], float radius,
                           gb_implicit_disc_bin_visit visit, void *user)
{
    const int n = bins->n;
    float d[3], extent[3];
    for (int k = 0; k < 3; ++k) {
        d[k] = centre[k] - from[k];
        /* how far the disc reaches from its centre along axis k */
        extent[k] = radius * sqrtf(larger(1.0f - normal[k] * normal[k], 0.0f));
    }
    float height = gb_dot3(d, normal);
    float radius2 = radius * radius;
    if (height == 0.0f || !(radius2 > 0.0f))
        return;                     /* seen edge on, or a disc of no area (a radius
                                       under 1e-19 squares to 0) */
    for (int face = 0; face < 6; ++face) {
        int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
        float sign = face % 2 ? -1.0f : 1.0f;
        float major0 = sign * d[axis] - extent[axis], major1 = sign * d[axis] + extent[axis];
        if (major1 <= 0.0f)
            continue;               /* the disc lies behind this face */
        float u0 = -1.0f, u1 = 1.0f, v0 = -1.0f, v1 = 1.0f;
        if (major0 > 0.0f) {        /* wholly in front: its projection is bounded */
            quotient_range(d[u] - extent[u], d[u] + extent[u], major0, major1, &u0, &u1);
            quotient_range(d[v] - extent[v], d[v] + extent[v], major0, major1, &v0, &v1);
        }
        int column0, column1, row0, row1;
        cell_range(u0, u1, n, &column0, &column1);
        cell_range(v0, v1, n, &row0, &row1);
        for (int row = row0; row <= row1; ++row)
            for (int column = column0; column <= column1; ++column) {
                int bin = (face * n + row) * n + column;
                const float *direction = &bins->directions[3 * bin];
                float facing = gb_dot3(direction, normal);
                if (facing == 0.0f)
                    continue;       /* the ray runs parallel to the disc */
                float t = height / facing;
                if (!(t > 0.0f) || !isfinite(t))
                    continue;
                float q[3];         /* from the centre to where the ray meets the plane */
                for (int k = 0; k < 3; ++k)
                    q[k] = t * direction[k] - d[k];
                float r2 = gb_dot3(q, q);
                if (r2 <= radius2)
                    visit(user, bin, t * (1.0f + OFF_CENTRE_LENGTHENING * r2 / radius2));
            }
    }
}
