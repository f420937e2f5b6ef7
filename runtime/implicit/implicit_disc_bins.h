/* implicit_disc_bins.h — the bins of the cube map (implicit_bins.h) through
 * which a point sees a disc: those whose centre direction, cast from the
 * point, meets the disc (implicit_disc_bins.c).
 *
 * The links of a near disc need it: a disc that fills much of a bin's
 * neighbourhood (the ceiling 5 mm above a cornice fills half its
 * hemisphere) is seen through every bin whose direction meets it, which
 * points spread over the disc reach only where they fall densely enough.
 * Only the bins in a box around the disc's projection on each cube face
 * are tested, so the cost follows the bins the disc covers.
 */
#ifndef GB_IMPLICIT_DISC_BINS_H
#define GB_IMPLICIT_DISC_BINS_H

#include "implicit_bins.h"

/* Called once a bin the disc covers, with the distance from the point to
 * the disc along the bin's centre direction (lengthened by at most 2^-10
 * the farther from the centre it meets the disc: see the .c). */
typedef void (*gb_implicit_disc_bin_visit)(void *user, int bin, float distance);

/* Visits the bins of bins through which from sees the disc of the given
 * centre, unit normal and radius; none when from lies in the disc's plane
 * or the disc has no area (its radius squares to 0). */
void gb_implicit_disc_bins(const gb_implicit_bins *bins, const float from[3],
                           const float centre[3], const float normal[3], float radius,
                           gb_implicit_disc_bin_visit visit, void *user);

#endif
