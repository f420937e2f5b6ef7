/* implicit_closed_parts.h — which surfaces have a back that can be seen
 * (implicit_closed_parts.c), decided once when the model is made.
 *
 * Elements are two-sided (implicit_model.h's sides) so that a surface seen
 * from behind shows and sends what reaches its back: a wall made of one
 * quad facing out of its room. But the back of a closed surface faces into
 * the volume it closes, where, in most scenes, no receiver and no eye can
 * be: linking it costs (Table 1's closed sphere, its inside linked with
 * itself: a frame 4.1-4.4x slower) and shows nothing. So a connected part
 * of the mesh (triangles joined through shared edges, vertices matched by
 * position) keeps its elements one-sided, a front only, when
 *   1. every edge of it is used by exactly two triangles, once in each
 *      direction (closed and consistently wound),
 *   2. its fronts face out: its signed volume (sum of p0 . (p1 x p2) / 6)
 *      is positive, so its backs face the inside, and
 *   3. no camera and no point or spot light of the scene lies inside it
 *      (its winding number about the point, the sum of its triangles'
 *      signed solid angles over 4 pi, below 1/2 in magnitude).
 * Every other part is open: its elements get a back. Rules 2 and 3 are
 * the closed rooms: a room wound inward (2) shows its backs outside; one
 * wound outward, a closed surface like the sphere's, holds the eye and
 * the light (3; tests/cli/implicit_sides.t).
 *
 * Cost: O(triangles) expected: one hash of the corners' positions and one
 * of the edges, a union-find over the triangles (near-constant a step),
 * one pass for the volumes, and one for the winding numbers of the points
 * that lie in a closed part's box (O(triangles x such points): the scene's
 * cameras and lights, few). Memory 100-180 bytes a triangle, freed before
 * returning.
 *
 * Decided here: a triangle with two corners at one position (no area)
 * joins no part and leaves its segment as the others make it. A zero-area
 * triangle with three distinct corners (a T-junction's filler) counts as
 * any other, and may open its part: a part wrongly open is only slower,
 * one wrongly closed would be wrong. The camera the window flies is not
 * watched: a scene whose eye may enter a closed part wound outward needs
 * a camera or a light inside it.
 */
#ifndef GB_IMPLICIT_CLOSED_PARTS_H
#define GB_IMPLICIT_CLOSED_PARTS_H

#include <stdint.h>

#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* open[t] (triangle_count bytes, the caller's) = 1 when triangle t's part
 * is open (above: not rules 1-3 together), 0 when closed (or t has two
 * corners at one position). positions: 3 floats a vertex; indices: 3 a
 * triangle; points: point_count * 3, the eyes and lights (rule 3). */
gb_result gb_implicit_open_triangles(const float *positions, const uint32_t *indices,
                                     uint32_t triangle_count, const float *points,
                                     uint32_t point_count, uint8_t *open, gb_error *error);

/* model->segment_open (segment_count bytes, the model owns it): 1 when
 * any triangle of the segment is in an open part (the points: the
 * scene's cameras and point and spot lights). A segment is grown
 * across edges of shared vertices (implicit_hierarchy.c), so it lies in
 * one part: its elements are two-sided exactly when their part is open.
 * Needs model->triangle_segment. */
gb_result gb_implicit_open_segments(const gb_scene *scene, gb_implicit_model *model,
                                    gb_error *error);

#endif
