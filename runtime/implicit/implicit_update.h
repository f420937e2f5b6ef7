/* implicit_update.h — UpdateElements (4.2.1; implicit_update.c). */
#ifndef GB_IMPLICIT_UPDATE_H
#define GB_IMPLICIT_UPDATE_H

#include "implicit_model.h"
#include "result.h"

/* Step 4, UpdateElements (implicit_update.c): every node again from
 * model->vertices, which the caller may have moved (a deforming model),
 * leaves from the finer triangles, internal nodes from their children; the
 * hierarchy stays. gb_implicit_update_leaves does the leaves only. */
gb_result gb_implicit_update_elements(gb_implicit_model *model, gb_error *error);
gb_result gb_implicit_update_leaves(gb_implicit_model *model, gb_error *error);

#endif
