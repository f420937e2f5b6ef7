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
enum {
    GB_COLLAPSE_KINDS = 3,
    GB_COLLAPSE_DIRECTIONS = 6,
    GB_COLLAPSE_SUBSTEPS = GB_COLLAPSE_DIRECTIONS * GB_COLLAPSE_KINDS
};

typedef struct gb_collapse {
    gb_cubical_complex *complex;
    gb_persistence *persistence;
    /* per substep: cells that may hold the g of a pair it removes, examined in
     * this iteration (border) or the next (pending); a cell may be listed
     * twice */
    gb_cell_list border[GB_COLLAPSE_SUBSTEPS];
    gb_cell_list pending[GB_COLLAPSE_SUBSTEPS];
    int substep;                /* the one running, GB_COLLAPSE_SUBSTEPS between
                                   iterations */
    gb_cell_list born[3];       /* per axis: cells whose edge along it became a facet
                                   this iteration (an edge does so once) */
    uint64_t *pairs;            /* free pairs of one substep: cell << 8 | face bit of g */
    uint8_t *cube_found;        /* a bit per cell: its cube is in the pairs of the
                                   running cube substep */
    size_t pair_count, pair_capacity;
    uint32_t iteration;         /* iterations done so far (persistence's clock) */
    uint64_t cubes, cubes_removed;
    uint64_t pairs_removed;
    uint64_t cells_examined;    /* border cells looked at, all substeps summed */
} gb_collapse;

/* Prepares the collapse of complex (freshly built: its first border is the
 * cubes beside a non-empty voxel), with persistence for the isthmuses. */
gb_result gb_collapse_init(gb_collapse *collapse, gb_cubical_complex *complex,
                           gb_persistence *persistence, gb_error *error);
void gb_collapse_free(gb_collapse *collapse);

/* Runs iterations until no free pair is left (protected edges aside).
 * progress may be NULL; a nonzero return from it cancels (GB_ERROR_IO). */
gb_result gb_collapse_run(gb_collapse *collapse, gb_progress_callback progress,
                          void *progress_user, gb_error *error);

/* Tells the collapse that faces of cell were removed from outside (cavity
 * breaking), so that the next run looks at the cells around it. */
gb_result gb_collapse_reconsider(gb_collapse *collapse, size_t cell, gb_error *error);

#endif
