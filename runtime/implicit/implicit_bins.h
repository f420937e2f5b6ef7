/* implicit_bins.h — the cube map of 6 x N x N direction bins a link falls
 * in (Dong 2007, 4.2.2; implicit_bins.c). The caller owns a gb_implicit_bins
 * from create until free. */
#ifndef GB_IMPLICIT_BINS_H
#define GB_IMPLICIT_BINS_H

#include <math.h>
#include <stdint.h>

#include "result.h"

/* Cube map of bins: face = 2 * axis + (direction[axis] < 0), u and v the
 * next two axes (axis + 1, axis + 2 mod 3) over |direction[axis]|. */
typedef struct gb_implicit_bins {
    int n;                      /* bins a face edge */
    uint32_t count;             /* 6 n n */
    float *directions;          /* count * 3: unit direction of each bin's centre */
    float *solid_angles;        /* count: exact solid angle of each bin (sr) */
} gb_implicit_bins;

gb_result gb_implicit_bins_create(int n, gb_implicit_bins *bins, gb_error *error);
void gb_implicit_bins_free(gb_implicit_bins *bins);

/* The one bin of direction d (need not be unit), in [0, 6 n n); -1 for the
 * zero vector or a non-finite one. Ties between faces go to the lowest
 * axis; u or v exactly on a face's edge go to the last row or column.
 * Inline: link creation calls it millions of times a frame. */
static inline int gb_implicit_bin(int n, const float d[3])
{
    if (n <= 0 || !isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2]))
        return -1;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (fabsf(d[a]) > fabsf(d[axis]))
            axis = a;
    float major = fabsf(d[axis]);
    if (major == 0.0f)
        return -1;
    int face = 2 * axis + (d[axis] < 0.0f);
    int cell[2];
    for (int k = 0; k < 2; ++k) {
        float t = d[(axis + 1 + k) % 3] / major;           /* in [-1, 1] */
        /* the cast truncates, which is floor on [0, n] */
        int i = (int)(0.5f * (t + 1.0f) * (float)n);
        cell[k] = i < 0 ? 0 : i >= n ? n - 1 : i;
    }
    return (face * n + cell[1]) * n + cell[0];
}

#endif
