/* segment.h — from thin's curvilinear skeleton to the segmented skeleton,
 * its visibility clusters and its visibility gates (noel-biri-2014 §IV.B and
 * §IV.C), the gates fitted to the openings the voxels show, and the measure
 * of how well they predict visibility.
 *
 * The steps, one file each, in the paper's order and with its names:
 *   topology_nodes.h      degree != 2 (rings get an anchor)
 *   lines.h               lines between classified nodes, recursive split
 *   curvature_nodes.h     curv(n) = dist(n, L1Lk) / maxball(n) > 1 splits
 *   coverage_nodes.h      nodes outside the extrema's maximal balls split
 *   segmented_skeleton.h  classified nodes, edges, skeleton node -> nearest extremum
 *   visibility_clusters.h stack-based greedy growth with alpha
 *   visibility_gates.h    a disk at the middle of every edge between clusters
 *   gate_openings.h       (with the voxels) the disks fitted to the openings,
 *                         a gate where clusters touch with no edge
 *   evaluate.c            random surface point pairs against Embree
 * Each header states the cases the paper leaves open and how they are decided
 * (rings, loops, coincident nodes, isolated nodes, equal radii).
 *
 *   gb_segment_options options = {0};          // zero = defaults (alpha 20 %)
 *   gb_segmentation seg;
 *   gb_segment(&skeleton, &options, &seg, NULL, &error);
 *   gb_segment_fit_gates(&seg, &voxels, nearest, NULL, &error);   // optional
 *   gb_segmentation_write("scene.seg", &seg, &error);
 *   gb_segmentation_free(&seg);
 *
 * Sequential, every choice ordered by index: the same skeleton and options
 * give the same segmentation, byte for byte. The caller owns every output.
 */
#ifndef GB_SEGMENT_H
#define GB_SEGMENT_H

#include <stdint.h>

#include "progress.h"
#include "result.h"
#include "scene.h"
#include "segmentation.h"
#include "skeleton.h"
#include "voxel_grid.h"

enum { GB_SEGMENT_DEFAULT_ALPHA = 20, GB_SEGMENT_DEFAULT_PAIRS = 100000 };

typedef struct gb_segment_options {
    /* How similar (in % of the cluster's largest maxball) a neighbour's
     * maxball must be to join a visibility cluster, §IV.B.2. 0 means the
     * default GB_SEGMENT_DEFAULT_ALPHA; negative means 0; at most 100. */
    double alpha;
} gb_segment_options;

typedef struct gb_segment_stats {
    uint32_t topology_nodes;    /* ring anchors and loop openers included */
    uint32_t curvature_nodes;
    uint32_t coverage_nodes;
    uint32_t rings;             /* rings (cycles without topology node) anchored */
    uint32_t loops;             /* lines from a node back to itself, opened */
    uint32_t lines;             /* lines between topology nodes, before any split */
    uint32_t opening_gates;     /* gates added where clusters touch with no edge */
    uint32_t fitted_gates;      /* gates whose disk was fitted to their opening */
    double seconds;
} gb_segment_stats;

/* skeleton: checked as gb_skeleton_validate does. options and stats may be
 * NULL. On success out holds the segmentation (gb_segmentation_free); on
 * failure out is left empty. */
gb_result gb_segment(const gb_skeleton *skeleton, const gb_segment_options *options,
                     gb_segmentation *out, gb_segment_stats *stats, gb_error *error);

/* The gates of a segmentation gb_segment made (not yet fitted), fitted to
 * the voxels (gate_openings.h): opening gates added, every disk fitted,
 * gates_fitted set. voxels: voxelize's grid, whose surface flags it reads;
 * nearest: thin's nearest-node grid; both in the segmentation's frame
 * (gb_segmentation_check_frame, gb_segmentation_check_grid). stats may be
 * NULL; it gets opening_gates and fitted_gates, and the time is added to its
 * seconds. On failure the gates may be half fitted: free the segmentation. */
gb_result gb_segment_fit_gates(gb_segmentation *segmentation, const gb_voxel_grid *voxels,
                               const int32_t *nearest, gb_segment_stats *stats,
                               gb_error *error);

/* ---- evaluation ---- */

typedef struct gb_segment_evaluate_options {
    uint32_t pairs;             /* 0: GB_SEGMENT_DEFAULT_PAIRS */
    uint64_t seed;              /* pair i draws from PCG32 stream i of this seed */
    gb_progress_callback progress;  /* may be NULL; nonzero return cancels */
    void *progress_user;
} gb_segment_evaluate_options;

/* A predictor of "visible" against the truth. */
typedef struct gb_visibility_score {
    uint64_t true_positive, false_positive, false_negative, true_negative;
} gb_visibility_score;

typedef struct gb_segment_evaluation {
    uint64_t pairs;             /* pairs evaluated */
    uint64_t grazing;           /* draws rejected: a point in the other's plane */
    uint64_t visible;           /* pairs whose segment Embree finds unoccluded */
    uint64_t unlocated;         /* pairs with a point in no cluster: predicted hidden */
    gb_visibility_score same_cluster;  /* visible when both points share a cluster */
    gb_visibility_score one_gate;      /* ... or when the segment crosses a gate
                                          between their two clusters */
    double seconds;
} gb_segment_evaluation;

/* Samples pairs of points on the scene's triangles, uniform by area. A pair
 * where either point lies in the other's plane (|cosine| < 1e-3: they
 * exchange no light) is drawn again from the pair's stream, at most 64 times
 * before the pair is dropped. Surfaces are two-sided: each point is taken on
 * the side facing the other. Each point's cluster comes from
 * gb_segmentation_cluster_at, looked up |n|_1 voxels off the surface on
 * that side (n its unit normal: out of the voxels the surface touches), then
 * 1 and 2 voxels further, at the point itself when none has a node (the
 * runtime's lookup, runtime/topo/topo_clusters.c); the truth is an
 * Embree shadow ray between the two points, each moved 1e-4 of the scene's
 * diagonal off its surface on that side. nearest: thin's grid, checked with
 * gb_segmentation_check_grid. Fails with GB_ERROR_STALE when the
 * segmentation was made from another scene. options may be NULL. */
gb_result gb_segment_evaluate(const gb_scene *scene, const gb_segmentation *segmentation,
                              const int32_t *nearest, const gb_segment_evaluate_options *options,
                              gb_segment_evaluation *out, gb_error *error);

/* TP / (TP + FP), 1 when nothing is predicted visible. */
double gb_visibility_precision(const gb_visibility_score *score);
/* TP / (TP + FN), 1 when nothing is visible. */
double gb_visibility_recall(const gb_visibility_score *score);

#endif
