/* methods.c — the table of the runtime's GI methods (methods.h). */
#include "methods.h"
#include "flc/flc.h"
#include "flc_iv/flc_iv.h"
#include "implicit/implicit.h"
#include "octree/octree.h"
#include "topo/topo.h"

#include <string.h>

/* One line a method, in gb_method's order: its name (--method, the
 * window's M key), its indirect light (NULL: direct light alone) and its
 * options (indirect_method.h; NULL: none). A new method adds its line. */
static const struct {
    const char *name;
    const gb_indirect_method *indirect;
    const gb_method_option *options;
} methods[GB_METHOD_COUNT] = {
    [GB_METHOD_DIRECT] = {"direct", NULL, NULL},
    [GB_METHOD_TOPO] = {"topo", &gb_topo_method, gb_topo_options},
    [GB_METHOD_OCTREE] = {"octree", &gb_octree_method, gb_octree_options},
    [GB_METHOD_FLC] = {"flc", &gb_flc_method, gb_flc_options},
    [GB_METHOD_IMPLICIT] = {"implicit", &gb_implicit_method, gb_implicit_options},
    [GB_METHOD_FLC_IV] = {"flc-iv", &gb_flc_iv_method, gb_flc_iv_options},
};

const char *gb_method_name(gb_method method)
{
    return method >= 0 && method < GB_METHOD_COUNT ? methods[method].name : "?";
}

/* The names of the methods (those this build has, when implemented_only),
 * ", " between them. */
static void list_methods(int implemented_only, char *list, size_t size)
{
    list[0] = '\0';
    for (int m = 0; m < GB_METHOD_COUNT; ++m)
        if (!implemented_only || gb_method_implemented((gb_method)m)) {
            if (list[0])
                strncat(list, ", ", size - strlen(list) - 1);
            strncat(list, methods[m].name, size - strlen(list) - 1);
        }
}

gb_result gb_method_parse(const char *name, gb_method *method, gb_error *error)
{
    for (int m = 0; m < GB_METHOD_COUNT; ++m)
        if (strcmp(name, methods[m].name) == 0) {
            *method = (gb_method)m;
            return GB_OK;
        }
    char list[128];
    list_methods(0, list, sizeof list);
    return gb_fail(error, GB_ERROR_ARGUMENT, "unknown method '%s' (methods: %s)", name, list);
}

const gb_indirect_method *gb_method_indirect(gb_method method)
{
    return method >= 0 && method < GB_METHOD_COUNT ? methods[method].indirect : NULL;
}

const gb_method_option *gb_method_options(gb_method method)
{
    return method >= 0 && method < GB_METHOD_COUNT ? methods[method].options : NULL;
}

int gb_method_implemented(gb_method method)
{
    return method == GB_METHOD_DIRECT || gb_method_indirect(method) != NULL;
}

gb_result gb_method_check(gb_method method, gb_error *error)
{
    if (gb_method_implemented(method))
        return GB_OK;
    char list[128];
    list_methods(1, list, sizeof list);
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
