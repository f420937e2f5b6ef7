/* persistence.h — when a 1-D isthmus of the collapsing complex is kept
 * (Chaussard, Noël, Biri, Couprie, DGCI 2013, after Couprie & Bertrand's
 * isthmus persistence).
 *
 * An edge is a 1-D isthmus from the iteration its last square is collapsed:
 * it is then a facet of the complex, its "birth". Collapse keeps removing
 * the ends of such lines; an edge is protected (never collapsed again) once
 * its lifespan, the number of iterations since its birth, exceeds
 *
 *     persistence * (opening - distance) + min_lifespan
 *
 * where distance is the chessboard distance of the empty voxels around the
 * edge to the nearest non-empty voxel and opening the radius of the largest
 * chessboard ball of the empty space containing them (maxima over the 4
 * voxels around the edge, in voxels). In the middle of a corridor the two are
 * equal and the isthmus is kept at once; near a corner of a room the opening
 * is the room's and the distance small, so the short lines collapse grows
 * there die before they are old enough.
 *
 * The caller owns the gb_persistence and frees it with gb_persistence_free.
 */
#ifndef GB_PERSISTENCE_H
#define GB_PERSISTENCE_H

#include <stdint.h>

#include "chessboard_maps.h"
#include "cubical_complex.h"
#include "progress.h"
#include "result.h"

typedef struct gb_persistence {
    unsigned char *maps;    /* the chessboard distance and opening of each cell
                               (chessboard_maps.h); gb_persistence_init refuses a
                               lattice whose smallest side is above
                               2 (GB_CHESSBOARD_FAR - 1) */
    /* births of the isthmus edges that outlived their first iteration: an
     * open-addressing table, key 1 + 3 * cell + axis (0: free slot) */
    uint64_t *birth_keys;
    uint32_t *births;
    size_t birth_capacity, birth_count;
    double persistence;     /* the scale of opening - distance */
    double min_lifespan;    /* iterations */
} gb_persistence;

/* Computes the distance and opening maps of the empty cubes of complex (a
 * freshly built complex: every cube there is an empty voxel), on up to
 * thread_count threads. progress may be NULL; a nonzero return from it
 * cancels with GB_ERROR_IO. */
gb_result gb_persistence_init(gb_persistence *persistence, const gb_cubical_complex *complex,
                              double scale, double min_lifespan, int thread_count,
                              gb_progress_callback progress, void *progress_user,
                              gb_error *error);
void gb_persistence_free(gb_persistence *persistence);

static inline uint16_t gb_persistence_distance(const gb_persistence *persistence, size_t cell)
{
    return gb_map_distance(persistence->maps, cell);
}

static inline uint16_t gb_persistence_opening(const gb_persistence *persistence, size_t cell)
{
    return gb_map_opening(persistence->maps, cell);
}

/* The edge along axis at cell became a facet at iteration: its birth (an
 * edge becomes a facet once; a second call keeps the first birth). */
gb_result gb_persistence_record_birth(gb_persistence *persistence, size_t cell, int axis,
                                      uint32_t iteration, gb_error *error);

/* The edge along axis at cell, a facet at iteration: is it protected, its
 * lifespan above its threshold? An edge without a recorded birth is taken
 * as born at iteration (lifespan 0), which never is: opening is at least
 * distance and the parameters are not negative. */
int gb_persistence_is_protected(const gb_persistence *persistence,
                                const gb_cubical_complex *complex, size_t cell, int axis,
                                uint32_t iteration);

#endif
