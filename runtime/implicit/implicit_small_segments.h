/* implicit_small_segments.h — segments smaller than an element, regrouped
 * (implicit_small_segments.c). Changes model->triangle_segment and
 * model->segment_count in place and sets model->segment_regrouped; the
 * model owns them. */
#ifndef GB_IMPLICIT_SMALL_SEGMENTS_H
#define GB_IMPLICIT_SMALL_SEGMENTS_H

#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* Every segment of less area than smallest_area is dissolved, and its
 * triangles regrouped into one segment per material and grid cell of side
 * cell (the cell its centroid rounds to), marked in segment_regrouped: it
 * is to be one element (implicit_elements.c). The other segments keep
 * their triangles. Segments are renumbered in order of their first
 * triangle. */
gb_result gb_implicit_merge_small_segments(const gb_scene *scene, gb_implicit_model *model,
                                           float smallest_area, float cell, gb_error *error);

#endif
