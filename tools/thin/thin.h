/* thin.h — the curvilinear skeleton of a voxelized scene's empty space and
 * the grid of every voxel's nearest skeleton node (noel-biri-2014 §IV.A,
 * after Chaussard, Noël, Biri, Couprie, "A 3D Curvilinear Skeletonization
 * Algorithm with Application to Path Tracing", DGCI 2013).
 *
 * The empty voxels become a cubical complex (cubical_complex.h), which is
 * collapsed directionally, layer by layer from every side, until only a
 * graph is left (collapse.h); a line that the collapse thins out of the
 * volume (a 1-D isthmus) is kept once it has lived longer than its local
 * "opening minus distance" (persistence.h), which keeps the corridors and
 * drops the short spurs of corners. Collapse preserves topology: the graph
 * has the components and the independent cycles of the empty space. Closed
 * surfaces around floating objects (cavities, which no graph can hold) are
 * opened (cavities.h). The graph's nodes are the corners of the remaining
 * complex, with their maximal ball radius (skeleton_graph.h); every voxel
 * then gets its geodesic nearest node (nearest_node.h).
 *
 *   gb_thin_options options = {0};             // zero = defaults
 *   gb_skeleton skeleton = {0};
 *   int32_t *nearest = NULL;                   // one per voxel, or NULL to skip
 *   gb_thin(&grid, &options, &skeleton, &nearest, NULL, &error);
 *   ...
 *   gb_skeleton_free(&skeleton); free(nearest);
 *
 * Preconditions: grid has a surface array; voxels outside it count as not
 * empty. The node radii are exact distances to the surface, computed for
 * the nodes only (surface_distance.h). The result is the same bytes for the same grid,
 * persistence and min_lifespan, whatever the number of threads: the collapse
 * removes at each substep exactly the set of free pairs of that substep, the
 * nearest-node grid is the unique least (distance, node) of every voxel.
 * The caller owns the skeleton and *nearest; on failure both are left empty.
 */
#ifndef GB_THIN_H
#define GB_THIN_H

#include <stdint.h>

#include "progress.h"
#include "result.h"
#include "skeleton.h"
#include "voxel_grid.h"

enum {
    GB_THIN_DEFAULT_PERSISTENCE = 1,
    GB_THIN_DEFAULT_MIN_LIFESPAN = 0,
    GB_THIN_DEFAULT_THREADS = 2,
    GB_THIN_MAX_THREADS = 64,
};

typedef struct gb_thin_options {
    /* An isthmus edge is kept once its lifespan (collapse iterations since it
     * became 1-D) exceeds persistence * (opening - distance) + min_lifespan.
     * 0 means the default; a negative persistence means 0 (keep every
     * isthmus at once), a negative min_lifespan means 0. */
    double persistence;         /* default GB_THIN_DEFAULT_PERSISTENCE */
    double min_lifespan;        /* iterations, default GB_THIN_DEFAULT_MIN_LIFESPAN */
    /* Threads for the collapse (a power of two, at most 8: collapse.h) and
     * for the nearest-node grid when it needs Dijkstra's algorithm (a maze;
     * the maps' and nearest-node grid's raster sweeps run on one thread); 0
     * means GB_THIN_DEFAULT_THREADS, at most GB_THIN_MAX_THREADS. The
     * result does not depend on it. */
    int threads;
    /* Called with the fraction done (0..1) of the whole work; a nonzero
     * return cancels and gb_thin fails with GB_ERROR_IO. May be NULL. */
    gb_progress_callback progress;
    void *progress_user;
} gb_thin_options;

typedef struct gb_thin_stats {
    uint64_t empty_voxels;
    uint32_t iterations;        /* collapse iterations that removed a pair, cavity
                                   rounds included */
    uint32_t shared_iterations; /* iterations (those that removed nothing too)
                                   the threads shared */
    uint32_t cavities_opened;   /* squares removed to open 2-cycles */
    uint64_t squares_left;      /* 2-faces left in the result: 0 when thin */
    uint64_t cells_examined;    /* border cells the collapse looked at (its cost; it
                                   can differ a little with the thread count) */
    uint64_t pairs_removed;     /* elementary collapses */
    double seconds_maps;        /* complex, distance and opening maps */
    double seconds_collapse;    /* collapse and cavities */
    double seconds_graph;
    double seconds_nearest;
    /* CPU seconds, every thread counted: the skeleton (maps, collapse and
     * graph: what a thinning alone does) and the nearest-node grid */
    double cpu_seconds_skeleton, cpu_seconds_nearest;
} gb_thin_stats;

/* options and stats may be NULL; nearest may be NULL (no grid computed). */
gb_result gb_thin(const gb_voxel_grid *grid, const gb_thin_options *options,
                  gb_skeleton *skeleton, int32_t **nearest, gb_thin_stats *stats,
                  gb_error *error);
/* gb_thin, which frees grid->surface (and sets it NULL) as soon as it has
 * read it, before the collapse's maps are made, whatever the result: a
 * caller that keeps nothing else of the grid (thin's main) then holds
 * only its frame while it thins (the habit of gb_voxel_grid_write_and_free). */
gb_result gb_thin_and_free(gb_voxel_grid *grid, const gb_thin_options *options,
                           gb_skeleton *skeleton, int32_t **nearest, gb_thin_stats *stats,
                           gb_error *error);

#endif
