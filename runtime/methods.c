#include "methods.h"
#include "flc/flc.h"
#include "flc_iv/flc_iv.h"
#include "implicit/implicit.h"
#include "octree/octree.h"
#include "topo/topo.h"

#include <string.h>

static const char *const method_names[GB_METHOD_COUNT] = {
    "direct", "topo", "octree", "flc", "implicit", "flc-iv",
};

const char *gb_method_name(gb_method method)
{
    return method >= 0 && method < GB_METHOD_COUNT ? method_names[method] : "?";
}

gb_result gb_method_parse(const char *name, gb_method *method, gb_error *error)
{
    for (int m = 0; m < GB_METHOD_COUNT; ++m)
        if (strcmp(name, method_names[m]) == 0) {
            *method = (gb_method)m;
            return GB_OK;
        }
    return gb_fail(error, GB_ERROR_ARGUMENT,
                   "unknown method '%s' (methods: direct, topo, octree, flc, implicit, flc-iv)", name);
}

/* One entry a method: its indirect light, NULL until it lands. */
static const gb_indirect_method *const indirect_methods[GB_METHOD_COUNT] = {
    [GB_METHOD_DIRECT] = NULL,
    [GB_METHOD_TOPO] = &gb_topo_method,
    [GB_METHOD_OCTREE] = &gb_octree_method,
    [GB_METHOD_FLC] = &gb_flc_method,
    [GB_METHOD_IMPLICIT] = &gb_implicit_method,
    [GB_METHOD_FLC_IV] = &gb_flc_iv_method,
};

const gb_indirect_method *gb_method_indirect(gb_method method)
{
    return method >= 0 && method < GB_METHOD_COUNT ? indirect_methods[method] : NULL;
}

int gb_method_implemented(gb_method method)
{
    return method == GB_METHOD_DIRECT || gb_method_indirect(method) != NULL;
}

gb_result gb_method_check(gb_method method, gb_error *error)
{
    if (gb_method_implemented(method))
        return GB_OK;
    char list[128] = "";
    for (int m = 0; m < GB_METHOD_COUNT; ++m)
        if (gb_method_implemented((gb_method)m)) {
            if (list[0])
                strncat(list, ", ", sizeof list - strlen(list) - 1);
            strncat(list, method_names[m], sizeof list - strlen(list) - 1);
        }
    return gb_fail(error, GB_ERROR_UNSUPPORTED,
                   "method '%s' is not available in this build (available: %s)",
                   gb_method_name(method), list);
}

const char *gb_terms_name(gb_terms terms)
{
    switch (terms) {
    case GB_TERMS_BOTH: return "direct+indirect";
    case GB_TERMS_DIRECT: return "direct";
    case GB_TERMS_INDIRECT: return "indirect";
    case GB_TERMS_COUNT: break;
    }
    return "?";
}
