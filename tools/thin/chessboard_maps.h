/* chessboard_maps.h — the chessboard distance and opening maps of the empty
 * space (persistence.h's maps, which say when an isthmus is kept).
 *
 * distance: of an empty cube's voxel to the nearest non-empty voxel, on the
 * chessboard metric (1 next to one); opening: the radius of the largest
 * chessboard ball (a cube of side 2r - 1) of the empty space holding it.
 * Both are 0 on cells that hold no cube, in voxels, below
 * GB_CHESSBOARD_FAR: either is at most half the lattice's smallest side.
 * The caller owns maps, GB_CHESSBOARD_MAP_BYTES a cell of the complex, 12
 * bits of each value, read with gb_map_distance and gb_map_opening; every
 * byte is written.
 */
#ifndef GB_CHESSBOARD_MAPS_H
#define GB_CHESSBOARD_MAPS_H

#include <stddef.h>
#include <stdint.h>

#include "cubical_complex.h"
#include "progress.h"
#include "result.h"

enum { GB_CHESSBOARD_MAP_BYTES = 3, GB_CHESSBOARD_FAR = 4095, GB_CHESSBOARD_MAX_THREADS = 8 };

/* Fills maps for the cubes of complex (a freshly built complex: every cube
 * is an empty voxel), the openings on up to thread_count threads (the maps
 * do not depend on it). progress may be NULL; a nonzero return from it
 * cancels with GB_ERROR_INTERRUPTED. */
gb_result gb_chessboard_maps(const gb_cubical_complex *complex, unsigned char *maps,
                             int thread_count, gb_progress_callback progress,
                             void *progress_user, gb_error *error);

/* The two maps of a cell, packed in 3 bytes: distance in byte 0 and the low
 * half of byte 1, opening in the high half of byte 1 and byte 2. */
static inline uint16_t gb_map_distance(const unsigned char *maps, size_t cell)
{
    const unsigned char *at = maps + GB_CHESSBOARD_MAP_BYTES * cell;
    return (uint16_t)(at[0] | (at[1] & 0x0f) << 8);
}

static inline uint16_t gb_map_opening(const unsigned char *maps, size_t cell)
{
    const unsigned char *at = maps + GB_CHESSBOARD_MAP_BYTES * cell;
    return (uint16_t)(at[1] >> 4 | at[2] << 4);
}

#endif
