/* cluster.h — the light octree of a scene from its photon map
 * (vivianloc-2007 §3.1, Figure 4):
 *
 *   octree.build(scene.geometry);            octree.c: leaves at depth δ where
 *                                            geometry is, area-weighted normals
 *   KDTree.build(scene.photonMap);           gathering.c: FLANN single kd-tree
 *   foreach octree.leaves {
 *       photons = gather(K, R, KDtree);      gathering.c: K nearest in an
 *                                            ellipsoid along the leaf normal
 *       VDLs = cluster(K_max, photons);      kmeans.c + vdl.c: chord-length
 *   }                                        k-means, VDL count chosen by the
 *                                            irradiance error it leaves
 *
 * A leaf gathers around its point on the geometry (octree.h), not its cell
 * centre, so that on a surface the photons lie in the disc the estimate
 * assumes. Irradiance of a leaf: the photon density estimate
 * E = Σ Φ_i / (π r²) over the photons gathered, r the gathering radius (the K-th neighbour's
 * distance, at most R). Each VDL carries the part of E of its cluster, so the
 * VDLs of a leaf sum to its estimate exactly (to float rounding).
 *
 * Determinism: leaves are processed in Morton order, in chunks whose results
 * land in per-leaf slots; leaf i seeds k-means++ (and its restarts) from
 * PCG32 stream i of the seed. The file is the same whatever the threads.
 *
 * Options: a zeroed gb_cluster_options means the defaults. The caller owns
 * the octree it gets (gb_light_octree_free).
 */
#ifndef GB_CLUSTER_H
#define GB_CLUSTER_H

#include <stdint.h>

#include "light_octree.h"
#include "photon_map.h"
#include "progress.h"
#include "scene.h"

enum {
    GB_CLUSTER_DEFAULT_DEPTH = 6,       /* δ: 64^3 leaves */
    GB_CLUSTER_DEFAULT_KNN = 300,       /* K */
    GB_CLUSTER_DEFAULT_VDLS = 8,        /* K_max, the paper's GPU limit */
};
#define GB_CLUSTER_DEFAULT_TOLERANCE 0.2f   /* vdl.h: relative irradiance error */
#define GB_CLUSTER_DEFAULT_RADIUS_LEAVES 3.0f /* R in leaf edges when not given */
#define GB_CLUSTER_FLATTENING 0.5f      /* ellipsoid normal semi-axis / tangent semi-axis */

typedef struct gb_cluster_options {
    unsigned depth;             /* δ, 1..10; 0: 6 */
    unsigned knn;               /* K; 0: 300 */
    float radius;               /* R, world units; 0: 3 leaf edges */
    unsigned vdls_max;          /* K_max, 1..64; 0: 8 */
    float tolerance;            /* the fewest VDLs a leaf whose irradiance error is
                                   at most this (vdl.h); 0: 0.2; negative:
                                   always K_max */
    unsigned restarts;          /* k-means runs per clustering, the best kept
                                   (kmeans.h); 0: 1 */
    uint32_t interpolation;     /* the octree's, light_octree.h: GB_LIGHT_OCTREE_TRILINEAR
                                   (0) or GB_LIGHT_OCTREE_SURFACE (the
                                   command's default) */
    uint64_t seed;
    int threads;                /* 0: every core */
    uint32_t part, part_count;  /* --shard I/N: only the leaves of part I of N
                                   (gb_cluster_part_leaves) are clustered, the
                                   others get no VDL, and only the photons they
                                   can gather are indexed (halo.h); part_count
                                   0 or 1: all */
    gb_progress_callback progress; /* fraction done, from the calling thread; may be NULL */
    void *progress_user;
} gb_cluster_options;

typedef struct gb_cluster_stats {
    uint32_t leaves, vdls;
    uint32_t vdl_histogram[GB_LIGHT_OCTREE_MAX_VDLS + 1]; /* leaves per VDL count */
    double octree_seconds, index_seconds, query_seconds, kmeans_seconds, seconds;
    uint64_t queries;
    uint64_t indexed;           /* photons in the kd-tree: the map's, or a part's halo */
    double mean_gathered;       /* photons per leaf after the ellipsoid */
    double mean_error;          /* vdl.h's, over leaves with VDLs */
    double mean_spread;         /* kmeans.h's, degrees, over leaves with VDLs */
    int threads;
} gb_cluster_stats;

/* Builds the light octree of scene from map (traced in that scene). stats
 * may be NULL. Fails on bad options (GB_ERROR_ARGUMENT), a map of another
 * scene (GB_ERROR_STALE), a bad map (NaN...) or an interrupt. */
gb_result gb_cluster_build(const gb_scene *scene, const gb_photon_map *map,
                           const gb_cluster_options *options, gb_light_octree *octree,
                           gb_cluster_stats *stats, gb_error *error);

/* The leaves of part of part_count: [*first, *end), a contiguous range of the
 * leaf order, the same for every run of the same leaf_count. */
void gb_cluster_part_leaves(uint32_t leaf_count, uint32_t part, uint32_t part_count,
                            uint32_t *first, uint32_t *end);

/* The light octree made from the count octrees of --shard 0/count ..
 * count-1/count (parts[i] the one of I = i): each leaf's VDLs taken from the
 * part it belongs to, so that the bytes are those of the whole run. A part
 * of another octree (header, nodes, leaves), or with VDLs outside its own
 * leaves (a part of another split, or the parts out of order), is refused,
 * naming it by names[i]. merged owns its storage (gb_light_octree_free). */
gb_result gb_cluster_merge(const gb_light_octree *parts, const char *const *names,
                           uint32_t count, gb_light_octree *merged, gb_error *error);

#endif
