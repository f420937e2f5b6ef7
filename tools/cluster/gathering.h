/* gathering.h — the KNN gathering of vivianloc-2007 §3.1.1: up to K nearest
 * photons of a leaf within an ellipsoid aligned with the leaf normal.
 *
 * The photon positions go to FLANN as they are (a single kd-tree index,
 * FLANN_INDEX_KDTREE_SINGLE: exact, and ~6x faster than randomized trees on
 * 3-D points, ../shared/ANCHORS.md). A batch of leaves' gathering points (on
 * their geometry, octree.h) is searched at once (FLANN spreads it over
 * `threads`), then each leaf keeps the photons of its K nearest that lie in
 * its ellipsoid:
 *   r = min(R, distance of the K-th nearest)       the gathering radius
 *   keep p when  t² + (n / flattening)² <= r²      t, n: the tangent and normal
 *                                                  parts of p - centre
 * Every photon of that ellipsoid is among the K (the ellipsoid lies in the
 * sphere of radius r), so Σ Φ / (π r²) over the kept photons is the usual
 * photon density estimate of the irradiance on the disc of radius r.
 *
 * The caller owns the gb_gathering (gb_gathering_free).
 */
#ifndef GB_CLUSTER_GATHERING_H
#define GB_CLUSTER_GATHERING_H

#include <stdint.h>

#include "photon_map.h"
#include "result.h"

typedef struct gb_gathering {
    const gb_photon_map *map;
    void *index;                /* flann_index_t, NULL when the map is empty */
    int threads;
    uint32_t knn;               /* K, at most the whole run's photon count */
    uint32_t searched;          /* K, at most map's photon count */
} gb_gathering;

/* Builds the kd-tree over map's positions (the map must outlive it). knn is
 * K, at most the photon count of the whole run, which map may be only a part
 * of (a halo, halo.h): the neighbours it lacks come back as index -1 at
 * infinite distance, as if they lay beyond any radius. */
gb_result gb_gathering_build(const gb_photon_map *map, uint32_t knn, int threads,
                             gb_gathering *gathering, gb_error *error);

/* The K nearest photons of each of count points (count x 3): indices and
 * squared distances, count x K each, nearest first. */
gb_result gb_gathering_knn(const gb_gathering *gathering, const float *centres,
                           uint32_t count, int *indices, float *distances2, gb_error *error);

/* Keeps, of one centre's K nearest, those inside its ellipsoid (see above):
 * writes their indices to kept (room for K), returns how many, and the
 * radius r in *radius (never below min_radius). */
uint32_t gb_gather_ellipsoid(const gb_gathering *gathering, const float centre[3],
                             const float normal[3], const int *indices,
                             const float *distances2, float max_radius, float min_radius,
                             float flattening, uint32_t *kept, float *radius);

void gb_gathering_free(gb_gathering *gathering);

#endif
