/* implicit_bins.c — the sphere of directions as a cube map of 6 x N x N
 * bins (Dong 2007, 4.2.2 "Discretization"), fixed in world space. */
#include "implicit_bins.h"

#include <math.h>
#include <stdlib.h>

/* The solid angle of [0, u] x [0, v] on the face at distance 1, signed. */
static double face_area(double u, double v)
{
    return atan2(u * v, sqrt(u * u + v * v + 1.0));
}

static void fill_bin(int n, int face, int row, int column, float direction[3],
                     float *solid_angle)
{
    double u0 = 2.0 * column / n - 1.0, u1 = 2.0 * (column + 1) / n - 1.0;
    double v0 = 2.0 * row / n - 1.0, v1 = 2.0 * (row + 1) / n - 1.0;
    *solid_angle = (float)(face_area(u1, v1) - face_area(u0, v1) - face_area(u1, v0) +
                           face_area(u0, v0));
    int axis = face / 2;
    double d[3];
    d[axis] = face % 2 ? -1.0 : 1.0;
    d[(axis + 1) % 3] = 0.5 * (u0 + u1);
    d[(axis + 2) % 3] = 0.5 * (v0 + v1);
    double length = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; ++k)
        direction[k] = (float)(d[k] / length);
}

gb_result gb_implicit_bins_create(int n, gb_implicit_bins *bins, gb_error *error)
{
    bins->n = n;
    bins->count = 6u * (uint32_t)n * (uint32_t)n;
    bins->directions = NULL;
    bins->solid_angles = NULL;
    if (n < 1 || n > 64)
        return gb_fail(error, GB_ERROR_ARGUMENT, "implicit: bins %d is not in 1..64", n);
    bins->directions = malloc(bins->count * 3 * sizeof *bins->directions);
    bins->solid_angles = malloc(bins->count * sizeof *bins->solid_angles);
    if (!bins->directions || !bins->solid_angles) {
        gb_implicit_bins_free(bins);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    }
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < n; ++row)
            for (int column = 0; column < n; ++column) {
                uint32_t b = (uint32_t)((face * n + row) * n + column);
                fill_bin(n, face, row, column, &bins->directions[3 * b], &bins->solid_angles[b]);
            }
    return GB_OK;
}

void gb_implicit_bins_free(gb_implicit_bins *bins)
{
    free(bins->directions);
    free(bins->solid_angles);
    bins->directions = NULL;
    bins->solid_angles = NULL;
}
