/* collapse.h — parallel directional collapse of a cubical complex with
 * persistent 1-D isthmuses kept (Chaussard & Couprie, IWCIA 2009,
 * ParDirCollapse; Chaussard, Noël, Biri, Couprie, DGCI 2013).
 *
 * A face f is free when it is a proper face of exactly one face g of the
 * complex; removing the pair (f, g) is an elementary collapse and keeps the
 * homotopy type. The direction of the pair is the axis from the centre of g
 * to the centre of f, its orientation the sign, its dimension dim g. All
 * free pairs of one direction, orientation and dimension can be removed at
 * once (ibid.: they are disjoint and stay free). One iteration removes them
 * for the 6 direction-orientations (-x, +x, -y, +y, -z, +z) and, for each,
 * the dimensions 3, 2, 1 in turn: a layer is peeled from every side, which
 * keeps the result centred. Iterations go on until no pair can be removed.
 * An edge g that persistence (persistence.h) protects is never removed.
 *
 * Cost: a removal can only free the pairs (h, k) where h is a face of the
 * removed pair left with a single coface k. That happens once to a pair,
 * and the geometry of h and k gives the pair's direction, orientation and
 * dimension: k's cell goes to the list of the one substep that can remove
 * it, later in this iteration or else in the next. Nothing else is ever
 * looked at: the work follows the removals, never the whole complex, and a
 * listed cell is examined once, not in every substep. Iterations end when
 * no substep has a candidate left for the next one.
 *
 * Threads: the lattice is cut into chunks of consecutive cells, each at
 * least 8 planes long, and a chunk belongs to a thread. A removal reads and
 * writes cells less than 3 planes from its own, so the removals in chunks of
 * one parity (every other chunk) never touch the same cell: a substep finds
 * its pairs in each thread's chunks, then removes those of the even chunks,
 * then those of the odd chunks, a barrier between, and no face is changed
 * or read under another thread's change. The pairs of a substep are all the
 * free ones of its kind whatever the order of removal, so the complex left
 * after each substep, hence the skeleton, does not depend on the thread
 * count. Which cells a removal lists does (a cell freed by two removals is
 * listed by the first), so only the iterations that removed a pair count for
 * persistence: a last iteration that found nothing changes nothing. An
 * iteration that looks small (fewer than parallel_cells cells listed at its
 * start and examined by the iteration before) runs on one thread.
 *
 * The caller owns the gb_collapse and frees it with gb_collapse_free; it
 * borrows the complex and the persistence maps it was given.
 */
#ifndef GB_COLLAPSE_H
#define GB_COLLAPSE_H

#include <stdint.h>

#include "cell_list.h"
#include "cubical_complex.h"
#include "persistence.h"
#include "progress.h"
#include "result.h"

/* What a listed cell may hold the g of: a cube, a square or an edge (the
 * pairs of dimension 3, 2, 1); and the direction-orientations -x, +x, -y,
 * +y, -z, +z (2 axis + (orientation > 0)). An iteration runs the substeps
 * in the order direction, then kind: substep 3 direction + kind. */
/* Free pairs found: cell << 8 | the face bit of g. */
typedef struct gb_pair_list {
    uint64_t *items;
    size_t count, capacity;
} gb_pair_list;

enum {
    GB_COLLAPSE_KINDS = 3,
    GB_COLLAPSE_DIRECTIONS = 6,
    GB_COLLAPSE_SUBSTEPS = GB_COLLAPSE_DIRECTIONS * GB_COLLAPSE_KINDS,
    GB_COLLAPSE_PARALLEL_CELLS = 32768,
    GB_COLLAPSE_MAX_THREADS = 8
};

/* What one thread of the collapse owns. */
typedef struct gb_collapse_worker {
    struct gb_collapse *collapse; /* the one it works for */
    /* per substep and bucket (a chunk's parity, then its thread: 2 *
     * thread_count buckets a substep; collapse.c's list_index): cells that
     * may hold the g of a pair the substep removes, examined in this
     * iteration (border) or the next (pending); a cell may be listed twice,
     * and by two threads */
    gb_cell_list *border, *pending;
    int substep;                /* the one running, GB_COLLAPSE_SUBSTEPS between
                                   iterations */
    gb_cell_list born[3];       /* per axis: cells whose edge along it became a facet
                                   this iteration (an edge does so once) */
    gb_pair_list pairs[2];      /* free pairs of one substep, in even and odd chunks */
    uint64_t cubes_removed, pairs_removed;
    uint64_t cells_examined;    /* border cells looked at, all substeps summed */
    gb_result result;           /* the first failure, in error */
    gb_error error;
} gb_collapse_worker;

typedef struct gb_collapse {
    gb_cubical_complex *complex;
    gb_persistence *persistence;
    gb_collapse_worker *workers;
    int thread_count;           /* workers: a power of two, at most
                                   GB_COLLAPSE_MAX_THREADS */
    int chunk_shift;            /* a cell's chunk is cell >> chunk_shift */
    size_t parallel_cells;      /* cells listed from which an iteration is shared
                                   (GB_COLLAPSE_PARALLEL_CELLS; tests lower it) */
    int parallel;               /* the running iteration is shared by the threads */
    int running;                /* gb_collapse_run goes on with an iteration */
    int failed;                 /* a worker failed (atomic) */
    uint8_t *cube_found;        /* a bit per cell: its cube is in the pairs of the
                                   running cube substep */
    uint32_t iteration;         /* iterations that removed a pair so far
                                   (persistence's clock) */
    uint32_t shared_iterations; /* iterations the threads shared */
    uint64_t cubes;
    /* sums over the workers, at the end of each iteration */
    uint64_t cubes_removed, pairs_removed, cells_examined;
    uint64_t cells_examined_before; /* by the iterations before the last one */
} gb_collapse;

/* Prepares the collapse of complex (freshly built: its first border is the
 * cubes beside a non-empty voxel), with persistence for the isthmuses, on
 * up to thread_count threads (the largest power of two not above it and
 * GB_COLLAPSE_MAX_THREADS; the result does not depend on it). */
gb_result gb_collapse_init(gb_collapse *collapse, gb_cubical_complex *complex,
                           gb_persistence *persistence, int thread_count, gb_error *error);
void gb_collapse_free(gb_collapse *collapse);

/* Runs iterations until no free pair is left (protected edges aside).
 * progress may be NULL; a nonzero return from it cancels (GB_ERROR_IO). */
gb_result gb_collapse_run(gb_collapse *collapse, gb_progress_callback progress,
                          void *progress_user, gb_error *error);

/* Tells the collapse that faces of cell were removed from outside (cavity
 * breaking), so that the next run looks at the cells around it. */
gb_result gb_collapse_reconsider(gb_collapse *collapse, size_t cell, gb_error *error);

#endif
