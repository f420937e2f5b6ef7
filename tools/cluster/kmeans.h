/* kmeans.h — k-means of photon directions (vivianloc-2007 §3.1.2): "the
 * distance is defined as the cord length formed by the two photon incoming
 * directions", |a - b| for unit a, b. Each photon weighs its power (the sum
 * of its RGB), so a centroid is the normalised power-weighted mean direction
 * of its cluster, and what k-means lowers, Σ w |d - c|², is exactly what the
 * spread below measures.
 *
 * Seeding is k-means++ (Arthur & Vassilvitskii 2007) drawn from the caller's
 * PCG32 stream, so the result depends only on the input and the stream.
 * Lloyd iterations follow until no photon changes cluster (at most
 * GB_KMEANS_MAX_ITERATIONS); a cluster left empty takes the photon that adds
 * most to Σ w |d - c|². With restarts > 1 the whole run is repeated from new
 * seeds and the run of least Σ w |d - c|² is kept (the first on ties). Ties
 * between centroids go to the lowest cluster index.
 */
#ifndef GB_CLUSTER_KMEANS_H
#define GB_CLUSTER_KMEANS_H

#include <stdint.h>

#include "random.h"

enum {
    GB_KMEANS_MAX_ITERATIONS = 32,
    GB_KMEANS_MAX_CLUSTERS = 64,
};

/* Zeroed fields mean the defaults; NULL means all defaults. */
typedef struct gb_kmeans_options {
    uint32_t restarts;          /* runs from independent seeds, best kept; 0: 1 */
} gb_kmeans_options;

/* Clusters n unit directions (n x 3) of weights > 0 into at most k
 * (<= GB_KMEANS_MAX_CLUSTERS) clusters: centroids (k x 3, unit) and
 * assignment (n), every photon assigned to its nearest centroid. Returns the
 * clusters made: fewer than k when the directions have fewer than k distinct
 * values (all identical: 1), 0 when n is 0. scratch: room for max(n, 3k)
 * doubles. */
uint32_t gb_kmeans_directions(const float *directions, const float *weights, uint32_t n,
                              uint32_t k, const gb_kmeans_options *options, gb_random *rng,
                              float *centroids, uint32_t *assignment, double *scratch);

/* The paper's intra-cluster error (§5.3.2, "standard deviation between the
 * direction of cluster centroid and the directions of the clustered photons,
 * expressed in cord length"): the power-weighted RMS chord between each
 * direction and its centroid, sqrt(Σ w |d - c|² / Σ w), given as the angle
 * of that chord in degrees (2 asin(chord / 2)). */
double gb_kmeans_spread(const float *directions, const float *weights, uint32_t n,
                        const float *centroids, const uint32_t *assignment);

#endif
