/* implicit_hidden.h — elements no camera sees, and the element shown in
 * their place (implicit_hidden.c).
 *
 * An element lies on its own surface, which the finer mesh does not cut
 * where another surface covers it: the ceiling's vertices under the
 * Cornell box's light, 0.5 mm below it, are elements whose whole
 * hemisphere is the light's back. Their light (implicit's display) or
 * their depth map (flc-iv's visibility, where every bin is 0.5 mm deep)
 * is right for them but is seen nowhere; yet the finer triangles that
 * reach from them to the lit ceiling beside the light carry it there,
 * interpolated (implicit) or as the triangle's element (flc-iv): dark
 * wedges and black spikes at the light's ends. So each side of each
 * element gets the element to show in its place: itself, or when that side
 * is hidden the nearest element of its own segment, across the finer
 * triangles, whose side is not.
 *
 * Hidden: a triangle of another segment of the finer mesh lies along the
 * side's normal (front: the node's normal; back: its opposite) within
 * GB_IMPLICIT_HIDDEN_DISTANCE element sizes and faces it within
 * GB_IMPLICIT_HIDDEN_DEGREES. A surface that touches the element (t = 0,
 * a coplanar twin) does not hide it: each would hide the other. Only the
 * element's centre is tested: the element stands for a point of the
 * surface, as in the display.
 */
#ifndef GB_IMPLICIT_HIDDEN_H
#define GB_IMPLICIT_HIDDEN_H

#include <stdint.h>

#include "implicit_model.h"
#include "result.h"

/* A tenth of an element: 3.4 mm in the Cornell box (its light is 0.5 mm
 * under the ceiling); an element this near a surface in front of it is
 * seen only at grazing angles, which the element's extent blurs anyway. */
#define GB_IMPLICIT_HIDDEN_DISTANCE 0.1f
/* A covering triangle's normal within this angle of the ray's (either
 * way): surfaces along the ray (a wall meeting the floor at the element)
 * cover nothing. */
#define GB_IMPLICIT_HIDDEN_DEGREES 60.0

/* shown: 2 * element_count, side after side (implicit_model.h's layout):
 * the element shown for side s of element e at [s * element_count + e],
 * which is e unless that side is hidden and an element of the same
 * segment, joined to it by the finer triangles, has that side seen. The
 * back of an element that has none (gb_implicit_node_two_sided) is its
 * front's. hidden, when not NULL, gets 2 * element_count flags (1: that
 * side is hidden), same layout. Returns the count of hidden sides in
 * *hidden_count when not NULL. Deterministic. */
gb_result gb_implicit_shown_elements(const gb_implicit_model *model, uint32_t *shown,
                                     uint8_t *hidden, uint32_t *hidden_count, gb_error *error);

#endif
