/* vdl.h — virtual directional lights of one leaf (vivianloc-2007 §3.1.2,
 * §4.2.2): each k-means cluster of the gathered photons becomes a VDL =
 * (irradiance RGB, direction), irradiance = Σ Φ_i / (π r²) over the cluster,
 * direction = the cluster's centroid (toward the light).
 *
 * Beyond the paper, the number of VDLs is chosen by the irradiance error
 * it leaves: the fewest k in 1 .. K_max whose VDLs light every normal the
 * leaf is shaded at (surface_normals.h) as its photons do, within the
 * tolerance, relative to the leaf's irradiance. At normal n, a VDL of
 * irradiance E from w gives E c(n, w), c = max(0, n.w) / max(|n_leaf.w|,
 * MIN_COS), the runtime's shading (common/light_octree_shading.h), and the
 * photons give the same sum with one VDL a photon; the error is the
 * largest difference over the normals (sums of RGB), over the leaf's
 * irradiance. At the leaf's own normal any k is exact (the VDLs sum to the
 * estimate), so a flat leaf of one surface needs 1; a corner, where the
 * light on the floor and on the wall differ, needs more. k = 1, 2, 4 ... is
 * tried until one passes, then the k between the last that failed and it
 * by bisection (the error falls as k grows); K_max when none passes, and
 * always with a negative tolerance (the paper). Clusters that end up
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
#include "surface_normals.h"

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

/* What a leaf's VDLs are chosen for (above). */
typedef struct vdl_target {
    float radius;               /* of the disc the photons were gathered on */
    float leaf_normal[3];       /* unit */
    const gb_surface_normal *normals;   /* where the leaf is shaded */
    uint32_t normal_count;      /* 0..GB_SURFACE_NORMALS */
    float tolerance;            /* relative; negative: K_max always */
} vdl_target;

/* Clusters the loaded photons into at most K_max VDLs for target (out: room
 * for K_max); returns how many, and the error of the clustering chosen in
 * *error. */
uint32_t gb_vdls_from_photons(gb_vdl_workspace *workspace, const vdl_target *target,
                              gb_random *rng, gb_light_octree_vdl *out, double *error);

#endif
