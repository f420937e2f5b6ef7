/* segmentation.h — the segmented skeleton, its visibility clusters and its
 * visibility gates (segment's output, read by the runtime) in memory and in
 * its `.seg` file (noel-biri-2014 §IV.B and §IV.C).
 *
 * The segmented skeleton keeps the classified nodes of thin's skeleton
 * (topology, curvature and coverage nodes) and joins them by segmented edges;
 * every skeleton node maps to one segmented node (node_map), every segmented
 * node belongs to one visibility cluster (cluster), and each segmented edge
 * between two clusters carries a visibility gate: the paper's disk at the
 * edge's middle, orthogonal to it. When segment had the voxels (segment
 * --voxels --grid, gates_fitted 1) each gate's disk is fitted to the opening
 * between its two clusters' voxels instead, and an opening gate, on no edge
 * (GB_SEGMENTATION_NO_EDGE), joins each pair of clusters whose voxels touch
 * with no edge between them: the gates the runtime draws, as they are.
 * The file is a gibake container of kind "SEGM" (formats/FORMATS.md,
 * "Segmentation file") with sections "header", "nodes", "edges",
 * "clusters", "node_map" and "gates"; it records the voxel frame and scene
 * hash of the skeleton it was made from.
 *
 *   gb_segmentation s = {0};                       // segment fills it (tools/segment)
 *   gb_segmentation_write("scene.seg", &s, &error);    // temporary file + rename
 *   gb_segmentation_read("scene.seg", &s, &error);     // checks every field
 *   gb_segmentation_free(&s);
 *
 * The lookup the runtime does for a point (§V.A): voxel → thin's
 * "nearest_node" grid → node_map → cluster:
 *   gb_segmentation_check_grid(&s, &frame, nearest, "scene.grid.vdb", &error);
 *   int32_t c = gb_segmentation_cluster_at(&s, nearest, point);   // -1: none
 *   int32_t *per_voxel = gb_segmentation_voxel_clusters(&s, nearest);  // free()
 *
 * The caller owns the gb_segmentation; gb_segmentation_read and gb_segment
 * fill it with malloc'ed arrays that gb_segmentation_free releases (also on a
 * zeroed one).
 */
#ifndef GB_SEGMENTATION_H
#define GB_SEGMENTATION_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"
#include "voxel_grid.h"

/* 2: the gates_fitted field (was reserved) and the opening gates; a file
 * of version 1 is refused ("bake it again"). */
enum { GB_SEGMENTATION_VERSION = 2 };

/* The edge of an opening gate: none. */
#define GB_SEGMENTATION_NO_EDGE UINT32_MAX

/* Why a skeleton node was kept (§IV.B.1). */
typedef enum gb_node_class {
    GB_NODE_UNCLASSIFIED = 0,   /* removed from the segmented skeleton */
    GB_NODE_TOPOLOGY = 1,       /* degree != 2, or the anchor that opens a ring */
    GB_NODE_CURVATURE = 2,      /* curv(n) = dist(n, L1Lk) / maxball(n) > 1 */
    GB_NODE_COVERAGE = 3,       /* outside the maximal balls of its line's extrema */
} gb_node_class;

typedef struct gb_segmented_node {
    uint32_t skeleton_node;     /* index into the skeleton's nodes */
    uint32_t node_class;        /* gb_node_class, never GB_NODE_UNCLASSIFIED */
    float position[3];          /* copied from the skeleton node, world units */
    float radius;               /* maxball, world units */
} gb_segmented_node;

/* The paper's gate, or with gates_fitted the disk of its opening: centre,
 * normal and radius fitted, radius at least the paper's. */
typedef struct gb_visibility_gate {
    float centre[3];            /* middle of the edge */
    float normal[3];            /* unit, from the edge's first node to its second
                                   (fitted: from clusters[0] to clusters[1]) */
    float radius;               /* min(maxball(n1), maxball(n2)) */
    uint32_t clusters[2];       /* cluster of the edge's first node, of its second
                                   (opening gate: the smaller first) */
    uint32_t edge;              /* index of the segmented edge, or
                                   GB_SEGMENTATION_NO_EDGE (an opening gate) */
} gb_visibility_gate;

typedef struct gb_segmentation {
    uint32_t skeleton_node_count;
    uint32_t node_count;        /* segmented nodes */
    uint32_t edge_count;        /* segmented edges */
    uint32_t cluster_count;     /* visibility clusters */
    uint32_t gate_count;        /* visibility gates */
    gb_segmented_node *nodes;   /* node_count, increasing skeleton_node */
    uint32_t *edges;            /* edge_count pairs (a, b) of segmented nodes: a < b,
                                   sorted, no duplicate */
    uint32_t *cluster;          /* node_count: the visibility cluster of each node */
    uint32_t *node_map;         /* skeleton_node_count: skeleton node -> segmented node */
    gb_visibility_gate *gates;  /* gate_count: one per edge between two clusters,
                                   increasing edge; then (gates_fitted) the
                                   opening gates, increasing cluster pair */

    double alpha;               /* percent, as used by the clustering */
    uint64_t scene_hash;        /* from the skeleton */
    double voxel_size;          /* the voxel frame of the skeleton */
    double world_origin[3];
    int32_t grid_size[3];
    uint32_t resolution;
    uint32_t gates_fitted;      /* 1: gates fitted to the voxels, opening gates
                                   added (segment --voxels); 0: the paper's */
} gb_segmentation;

gb_result gb_segmentation_write(const char *path, const gb_segmentation *segmentation,
                                gb_error *error);
/* On failure *segmentation is zeroed. */
gb_result gb_segmentation_read(const char *path, gb_segmentation *segmentation,
                               gb_error *error);
/* The same on a file's bytes in memory (tests, fuzzing); path is for messages. */
gb_result gb_segmentation_parse(const void *bytes, size_t size, const char *path,
                                gb_segmentation *segmentation, gb_error *error);
/* Checks what the reader checks, on a segmentation in memory (the writer
 * calls it): every index in range, finite values, unit normals, every
 * cluster used, gates that match their edges (fitted: their edge's clusters,
 * a centre in the voxel frame, at least the paper's radius), opening gates
 * only when fitted, each on a pair of clusters no other gate joins. */
gb_result gb_segmentation_validate(const gb_segmentation *segmentation, const char *path,
                                   gb_error *error);
void gb_segmentation_free(gb_segmentation *segmentation);

/* Checks that a voxel file (voxelize's .vdb, or the frame of thin's grid)
 * was made in the segmentation's voxel frame: same voxel size, origin, size
 * and scene hash (GB_ERROR_STALE otherwise). path is the file's, for
 * messages. */
gb_result gb_segmentation_check_frame(const gb_segmentation *segmentation,
                                      const gb_voxel_grid *frame, const char *path,
                                      gb_error *error);

/* Checks that a nearest-node grid (frame and values, as
 * gb_voxel_grid_read_int32 returns them) belongs with the segmentation:
 * gb_segmentation_check_frame, and every value -1 or a skeleton node. path
 * is the grid's, for messages. */
gb_result gb_segmentation_check_grid(const gb_segmentation *segmentation,
                                     const gb_voxel_grid *frame, const int32_t *nearest,
                                     const char *path, gb_error *error);

/* The visibility cluster of a world point: its voxel, that voxel's nearest
 * skeleton node, its segmented node, its cluster. -1 when the point is
 * outside the grid or its voxel has no node. nearest must have passed
 * gb_segmentation_check_grid. */
int32_t gb_segmentation_cluster_at(const gb_segmentation *segmentation,
                                   const int32_t *nearest, const double point[3]);

/* The visibility cluster of every voxel of the frame (x fastest, then y,
 * then z; -1 where the voxel has no node): the lookup above folded once
 * over the whole grid, for segment's gate openings and the runtime's 3-D
 * texture. nearest must have passed gb_segmentation_check_grid. malloc'ed,
 * the caller frees it; NULL when out of memory. */
int32_t *gb_segmentation_voxel_clusters(const gb_segmentation *segmentation,
                                        const int32_t *nearest);

#endif
