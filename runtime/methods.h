/* methods.h — the names of the runtime's GI methods (--method, the window's
 * M key) and of the light terms it shows (direct, indirect or both: the
 * window's T key).
 *
 *   direct    direct light only (this file's issue: no indirect term)
 *   topo      Noël & Biri 2014, visibility clusters and gates
 *   octree    the light octree of virtual directional lights (2007)
 *   flc       Forward Light Cuts (Laurent 2016)
 *   implicit  implicit visibility (Dong 2007)
 *   flc-iv    FLC shadowed by implicit visibility's bins (no seed paper)
 * Each GI method lives in its own folder under runtime/ (runtime/topo/ ...)
 * with its gb_indirect_method (indirect_method.h), its options and
 * parameters (indirect_method.h), and has one line in methods.c's table,
 * one in gb_method and one in method_parameters.h.
 */
#ifndef GB_METHODS_H
#define GB_METHODS_H

#include "indirect_method.h"
#include "result.h"

typedef enum gb_method {
    GB_METHOD_DIRECT = 0,
    GB_METHOD_TOPO,
    GB_METHOD_OCTREE,
    GB_METHOD_FLC,
    GB_METHOD_IMPLICIT,
    GB_METHOD_FLC_IV,
    GB_METHOD_COUNT,
} gb_method;

typedef enum gb_terms {
    GB_TERMS_BOTH = 0,
    GB_TERMS_DIRECT,
    GB_TERMS_INDIRECT,
    GB_TERMS_COUNT,
} gb_terms;

const char *gb_method_name(gb_method method);
/* GB_ERROR_ARGUMENT for a name that is no method, with the list of names. */
gb_result gb_method_parse(const char *name, gb_method *method, gb_error *error);
/* The method's indirect light, or NULL for direct and for methods this
 * build lacks. */
const gb_indirect_method *gb_method_indirect(gb_method method);
/* The method's options (indirect_method.h), ended by a NULL name, or NULL
 * when it has none. */
const gb_method_option *gb_method_options(gb_method method);
/* Nonzero when this build can render method. */
int gb_method_implemented(gb_method method);
/* GB_ERROR_UNSUPPORTED, naming the methods that are, when it is not. */
gb_result gb_method_check(gb_method method, gb_error *error);

const char *gb_terms_name(gb_terms terms);

#endif
