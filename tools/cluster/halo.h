/* halo.h — the photons one part of the octree's leaves can gather (cluster
 * --shard I/N), so a part indexes and holds only those, not the whole map.
 *
 * A leaf keeps photons within its gathering radius r <= R of its gathering
 * point (gathering.h), so a part needs exactly the photons within R of its
 * points. The halo is a superset: the photons inside the box of the part's
 * gathering points grown by R (and a relative 1e-5 for rounding), in the
 * map's order. Every leaf of the part then finds among them the photons it
 * finds in the whole map, the ones within R, so the part's VDLs are the
 * whole run's byte for byte (ties in distance apart: two photons exactly as
 * far from a gathering point may come back in the other order).
 *
 * The caller owns *halo (gb_photon_map_free); it copies the header of map,
 * whose photons it may then release.
 */
#ifndef GB_CLUSTER_HALO_H
#define GB_CLUSTER_HALO_H

#include <stdint.h>

#include "photon_map.h"
#include "result.h"

/* The photons of map within R of the box of points [first, end) (x3). */
gb_result gb_cluster_halo(const gb_photon_map *map, const float *points, uint32_t first,
                          uint32_t end, float R, gb_photon_map *halo, gb_error *error);

#endif
