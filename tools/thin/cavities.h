/* cavities.h — opening the closed surfaces that collapse cannot remove.
 *
 * An object floating in a room encloses a cavity of the empty space's
 * complement: the empty space then has a 2-cycle (second Betti number b2 > 0)
 * and collapse, which keeps the homotopy type, stops on a closed surface of
 * squares around the object. A curvilinear skeleton cannot represent it, so
 * thin opens each such surface by removing one of its squares and collapses
 * again: the skeleton keeps the components and the independent cycles (b0,
 * b1) of the empty space and drops its cavities (b2 = 0).
 *
 * Which squares: the complement of the remaining complex is cut into regions
 * (cells joined through the squares that are gone). The region outside the
 * scene is flooded first; a square with a flooded cell on one side and an
 * unflooded one on the other separates it from a cavity, so removing it
 * joins the two regions and lowers b2 by one without creating a 1-cycle;
 * the cavity is then flooded too. Squares are taken in cell order (z, then
 * y, then x), passes repeated until none separates: one square per cavity.
 */
#ifndef GB_CAVITIES_H
#define GB_CAVITIES_H

#include <stdint.h>

#include "collapse.h"
#include "cubical_complex.h"
#include "result.h"

/* Counts the squares left in the complex into *squares_left (a sweep of the
 * complex) and, when there are any, opens every 2-cycle as above, telling the
 * collapse about the removed squares; *opened is the number of squares
 * removed. */
gb_result gb_open_cavities(gb_cubical_complex *complex, gb_collapse *collapse,
                           uint64_t *squares_left, uint32_t *opened, gb_error *error);

#endif
