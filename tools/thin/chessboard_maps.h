/* chessboard_maps.h — the chessboard distance and opening maps of the empty
 * space (persistence.h's maps, which say when an isthmus is kept).
 *
 * distance: of an empty cube's voxel to the nearest non-empty voxel, on the
 * chessboard metric (1 next to one); opening: the radius of the largest
 * chessboard ball (a cube of side 2r - 1) of the empty space holding it.
 * Both are 0 on cells that hold no cube. The caller owns maps, of
 * GB_PERSISTENCE_MAP_BYTES per cell of the complex, packed as persistence.h
 * says; every byte is written.
 */
#ifndef GB_CHESSBOARD_MAPS_H
#define GB_CHESSBOARD_MAPS_H

#include "cubical_complex.h"
#include "progress.h"
#include "result.h"

/* Fills maps for the cubes of complex (a freshly built complex: every cube
 * is an empty voxel). progress may be NULL; a nonzero return from it
 * cancels with GB_ERROR_INTERRUPTED. */
gb_result gb_chessboard_maps(const gb_cubical_complex *complex, unsigned char *maps,
                             gb_progress_callback progress, void *progress_user,
                             gb_error *error);

#endif
