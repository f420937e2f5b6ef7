/* flux_probes.c — the stored power in a grid over the bounds (flux_probes.h). */
#include "flux_probes.h"

#include <math.h>
#include <stdlib.h>

enum { CELL_COUNT = GB_FLUX_PROBES_CELLS * GB_FLUX_PROBES_CELLS * GB_FLUX_PROBES_CELLS };

/* The cell of coordinate x along one axis of [low, high]. */
static int cell_of(float x, float low, float high)
{
    float extent = high - low;
    int i = extent > 0.0f ? (int)((x - low) / extent * GB_FLUX_PROBES_CELLS) : 0;
    return i < 0 ? 0 : i >= GB_FLUX_PROBES_CELLS ? GB_FLUX_PROBES_CELLS - 1 : i;
}

gb_result gb_flux_probes_measure(const gb_photon_map *map, gb_flux_probes *probes,
                                 gb_error *error)
{
    probes->flux = calloc(CELL_COUNT, sizeof *probes->flux);
    if (!probes->flux)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "photons: out of memory");
    const float *low = map->header.bounds_min, *high = map->header.bounds_max;
    for (uint64_t i = 0; i < map->count; ++i) {
        const float *p = &map->positions[3 * i], *power = &map->powers[3 * i];
        int cell = (cell_of(p[2], low[2], high[2]) * GB_FLUX_PROBES_CELLS +
                    cell_of(p[1], low[1], high[1])) * GB_FLUX_PROBES_CELLS +
                   cell_of(p[0], low[0], high[0]);
        probes->flux[cell] += (double)power[0] + power[1] + power[2];
    }
    return GB_OK;
}

double gb_flux_probes_change(const gb_flux_probes *earlier, const gb_flux_probes *later)
{
    double difference = 0.0, norm = 0.0;
    for (int c = 0; c < CELL_COUNT; ++c) {
        double d = later->flux[c] - earlier->flux[c];
        difference += d * d;
        norm += later->flux[c] * later->flux[c];
    }
    if (norm == 0.0)
        return difference == 0.0 ? 0.0 : 1.0;
    return sqrt(difference / norm);
}

void gb_flux_probes_free(gb_flux_probes *probes)
{
    free(probes->flux);
    probes->flux = NULL;
}
