/* flux_probes.h — what `photons -n auto` watches converge: the power of the
 * stored photons summed in a grid of cells over the map's bounds (a probe
 * set of the light the map carries, in W a cell: Σ power / emitted photons
 * is already in each photon's power).
 *
 * Between two maps of N and 2N photons of one run the relative change
 *   ||F_2N - F_N|| / ||F_2N||     (L2 over cells, R + G + B a cell)
 * falls as 1/sqrt(N), as Monte Carlo noise does; photons -n auto doubles N
 * until it is below the tolerance (photons.h).
 *
 * The caller owns the probes (gb_flux_probes_free).
 */
#ifndef GB_PHOTONS_FLUX_PROBES_H
#define GB_PHOTONS_FLUX_PROBES_H

#include "photon_map.h"
#include "result.h"

enum { GB_FLUX_PROBES_CELLS = 16 };    /* a side of the grid */

typedef struct gb_flux_probes {
    double *flux;               /* CELLS^3, x fastest */
} gb_flux_probes;

/* The probes of map, summed in the map's order (the same at any thread
 * count). */
gb_result gb_flux_probes_measure(const gb_photon_map *map, gb_flux_probes *probes,
                                 gb_error *error);

/* ||later - earlier|| / ||later||; 0 when both are zero, 1 when only later is. */
double gb_flux_probes_change(const gb_flux_probes *earlier, const gb_flux_probes *later);

void gb_flux_probes_free(gb_flux_probes *probes);

#endif
