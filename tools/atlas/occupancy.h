/* occupancy.h — the atlas's occupied texels while packing.h places the
 * charts' padded masks (chart_mask.h) one after the other: a bit a texel,
 * and per row its longest run of free texels.
 *
 * A mask fits at (x, y) when its box lies in the atlas and none of its
 * texels is occupied. The search for the first place (lowest row, then
 * leftmost column) skips the places it can rule out: the mask at row y
 * fits nowhere when a row y + r of the atlas has no free run as long as
 * the mask's longest run in its row r; and at a column x where a run of
 * the mask, of n texels starting at a, meets an occupied texel p, every
 * column before q - a, q the first column past p where n free texels
 * start in that row of the atlas, would meet an occupied texel too, so
 * the next column tried is q - a (the row that blocked is tried first
 * there).
 *
 * The caller owns the occupancy (gb_occupancy_free) and the masks.
 */
#ifndef GB_ATLAS_OCCUPANCY_H
#define GB_ATLAS_OCCUPANCY_H

#include <stdint.h>

#include "chart_mask.h"

typedef struct gb_occupancy {
    uint32_t width, height;
    uint32_t words;             /* per row */
    uint64_t *bits;             /* height rows of words: 1 occupied */
    uint32_t *longest_free;     /* per row */
} gb_occupancy;

/* An empty width x height atlas; 0 when out of memory. */
int gb_occupancy_init(gb_occupancy *occupancy, uint32_t width, uint32_t height);
void gb_occupancy_free(gb_occupancy *occupancy);

/* The first place, from row first_row on, where one of the count masks
 * fits: the lowest row, then the leftmost column, then the first mask; 1
 * with *which, *x, *y (the box's top left corner), or 0 when none fits.
 * first_row: 0, or a row above which these masks are known not to fit
 * (where the same shapes were placed last: texels are only ever taken). */
int gb_occupancy_find(const gb_occupancy *occupancy, const gb_chart_mask *const *masks,
                      int count, uint32_t first_row, int *which, uint32_t *x, uint32_t *y);

/* Occupies the mask's texels at (x, y), where it fits. */
void gb_occupancy_mark(gb_occupancy *occupancy, const gb_chart_mask *mask, uint32_t x,
                       uint32_t y);

#endif
