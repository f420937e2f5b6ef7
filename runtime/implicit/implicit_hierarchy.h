/* implicit_hierarchy.h — CreateGeometricHierarchy (4.1; implicit_hierarchy.c):
 * segments of the scene's triangles and a quadtree over each segment's
 * elements. */
#ifndef GB_IMPLICIT_HIERARCHY_H
#define GB_IMPLICIT_HIERARCHY_H

#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* implicit_hierarchy.c: segments of the scene's triangles. */
gb_result gb_implicit_segment_faces(const gb_scene *scene, gb_implicit_model *model,
                                    gb_error *error);
/* implicit_hierarchy.c: the quadtrees over the elements already made. */
gb_result gb_implicit_create_geometric_hierarchy(gb_implicit_model *model, gb_error *error);
/* implicit_hierarchy.c: an internal node's position (area-weighted mean),
 * normal, area and box from its children's. */
void gb_implicit_summarise(gb_implicit_model *model, gb_implicit_node *node);

#endif
