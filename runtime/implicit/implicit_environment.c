/* implicit_environment.c — environment map lighting (Dong 2007, 4.4): the
 * empty bins of an element see the environment, so the map is reduced once
 * to one radiance a bin (the bins are fixed in world space) and each
 * element gathers its empty bins' radiance, weighted like its links
 * (implicit_links.c). The map is the scene's lat-long image
 * (formats/environment.h has the convention). */
#include "implicit_environment.h"

#include <math.h>
#include <stddef.h>

#include "environment.h"

/* Mean radiance over bin (face, row, column): samples at the centres of a
 * grid over the bin's square, weighted by their solid angle 1 / |p|^3. */
static void bin_radiance(const gb_texture *map, int n, int face, int row, int column,
                         float out[3])
{
    double sum[3] = {0, 0, 0}, weight = 0.0;
    int axis = face / 2;
    for (int j = 0; j < GB_IMPLICIT_MAP_SAMPLES; ++j)
        for (int i = 0; i < GB_IMPLICIT_MAP_SAMPLES; ++i) {
            double u = -1.0 + 2.0 * (column + (i + 0.5) / GB_IMPLICIT_MAP_SAMPLES) / n;
            double v = -1.0 + 2.0 * (row + (j + 0.5) / GB_IMPLICIT_MAP_SAMPLES) / n;
            double d[3];
            d[axis] = face % 2 ? -1.0 : 1.0;
            d[(axis + 1) % 3] = u;
            d[(axis + 2) % 3] = v;
            double length = sqrt(1.0 + u * u + v * v), w = 1.0 / (length * length * length);
            for (int k = 0; k < 3; ++k)
                d[k] /= length;
            float direction[3] = {(float)d[0], (float)d[1], (float)d[2]}, rgb[3];
            gb_environment_map_radiance(map, direction, rgb);
            for (int k = 0; k < 3; ++k)
                sum[k] += w * rgb[k];
            weight += w;
        }
    for (int k = 0; k < 3; ++k)
        out[k] = (float)(sum[k] / weight);
}

gb_result gb_implicit_environment_bins(const gb_implicit_bins *bins, const gb_texture *map,
                                       float scale, float *radiance, gb_error *error)
{
    gb_result result = gb_environment_map_check(map, "implicit", error);
    if (result != GB_OK)
        return result;
    if (!(scale >= 0.0f) || !isfinite(scale))
        return gb_fail(error, GB_ERROR_ARGUMENT, "implicit: environment scale %g is not >= 0",
                       (double)scale);
    int n = bins->n;
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < n; ++row)
            for (int column = 0; column < n; ++column) {
                float *out = &radiance[3 * (size_t)((face * n + row) * n + column)];
                bin_radiance(map, n, face, row, column, out);
                for (int k = 0; k < 3; ++k)
                    out[k] *= scale;
            }
    return GB_OK;
}
