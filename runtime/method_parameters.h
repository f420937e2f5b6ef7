/* method_parameters.h — every GI method's parameters, as gbview's options
 * set them: one field a method, of the type its folder declares beside its
 * options (topo/topo_options.c ...). A zero field is the method's defaults.
 * A method reads its own field and, when it is made of others (flc-iv:
 * flc and implicit), theirs. A new method adds its field here. */
#ifndef GB_METHOD_PARAMETERS_H
#define GB_METHOD_PARAMETERS_H

#include "flc/flc.h"
#include "flc_iv/flc_iv.h"
#include "implicit/implicit.h"
#include "octree/octree.h"
#include "topo/topo.h"

struct gb_method_parameters {
    gb_topo_parameters topo;
    gb_octree_parameters octree;
    gb_flc_parameters flc;
    gb_implicit_parameters implicit;
    gb_flc_iv_parameters flc_iv;
};

#endif
