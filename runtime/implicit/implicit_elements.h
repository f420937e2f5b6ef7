/* implicit_elements.h — steps 1-2 of Algorithm 1 (implicit_elements.c):
 * CreateSurfels, the elements, and the model they start. */
#ifndef GB_IMPLICIT_ELEMENTS_H
#define GB_IMPLICIT_ELEMENTS_H

#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* Steps 1-2. element_size 0: the default. element_cell: the grid cell
 * whose vertices make one element, a fraction of element_size (the
 * runtime's: GB_IMPLICIT_ELEMENT_CELL); 0: one element a vertex, as in
 * the paper. */
gb_result gb_implicit_model_create(const gb_scene *scene, float element_size, float element_cell,
                                   gb_implicit_model *model, gb_error *error);
void gb_implicit_model_free(gb_implicit_model *model);
/* implicit_elements.c: the elements of the finer mesh. */
gb_result gb_implicit_create_surfels(const gb_scene *scene, gb_implicit_model *model,
                                     gb_error *error);

#endif
