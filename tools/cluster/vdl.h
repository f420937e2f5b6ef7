/* vdl.h — virtual directional lights of one leaf (vivianloc-2007 §3.1.2,
 * §4.2.2): each k-means cluster of the gathered photons becomes a VDL =
 * (irradiance RGB, direction), irradiance = Σ Φ_i / (π r²) over the cluster,
 * direction = the cluster's centroid (toward the light).
 *
 * Beyond the paper, the number of VDLs is chosen by error: the fewest k in
 * 1 .. K_max whose spread (kmeans.h, the paper's §5.3.2 error) is at most
 * max_spread degrees; K_max when none is (K_max is tried first, and kept at
 * once when even it spreads more). The spread falls as k grows, so k is
 * found by bisection: at most 1 + log2(K_max) clusterings a leaf (4 for
 * K_max 8, where counting up from 1 took up to 8). Clusters that end up
 * empty give no VDL. VDLs are sorted brightest first (sum of RGB).
 *
 * A workspace holds one leaf's photons and the k-means arrays; one per
 * thread, owned by the caller (gb_vdl_workspace_free).
 */
#ifndef GB_CLUSTER_VDL_H
#define GB_CLUSTER_VDL_H

#include <stdint.h>

#include "kmeans.h"
#include "light_octree.h"
#include "photon_map.h"
#include "random.h"
#include "result.h"

typedef struct gb_vdl_workspace {
    uint32_t capacity, vdls_max;    /* K photons, K_max clusters */
    uint32_t count;                 /* photons loaded */
    float *directions;              /* capacity x 3, unit, toward the light */
    float *powers;                  /* capacity x 3 */
    float *weights;                 /* capacity: sum of RGB power */
    uint32_t *assignment;           /* capacity */
    float *centroids;               /* vdls_max x 3 */
    double *scratch;                /* max(capacity, 3 vdls_max) */
    uint32_t *kept_assignment;      /* capacity: the best clustering so far */
    float *kept_centroids;          /* vdls_max x 3 */
    void *storage;                  /* the one allocation the arrays above view */
    gb_kmeans_options kmeans;       /* zeroed by create: the defaults */
} gb_vdl_workspace;

gb_result gb_vdl_workspace_create(gb_vdl_workspace *workspace, uint32_t capacity,
                                  uint32_t vdls_max, gb_error *error);
void gb_vdl_workspace_free(gb_vdl_workspace *workspace);

/* Loads photons photon_indices[0..n) of map (n <= capacity). */
void gb_vdl_workspace_load(gb_vdl_workspace *workspace, const gb_photon_map *map,
                           const uint32_t *photon_indices, uint32_t n);

/* Clusters the loaded photons gathered on a disc of radius `radius` into at
 * most K_max VDLs (out: room for K_max); returns how many, and the spread
 * (degrees) of the clustering chosen in *spread. */
uint32_t gb_vdls_from_photons(gb_vdl_workspace *workspace, float radius, float max_spread,
                              gb_random *rng, gb_light_octree_vdl *out, double *spread);

#endif
