/* octree_options.c — octree's gbview option (indirect_method.h). */
#include "cli.h"
#include "method_parameters.h"

static int parse_atlas(const char *name, const char *value, gb_method_parameters *p)
{
    (void)name;
    p->octree.atlas = value;
    return GB_EXIT_SUCCESS;
}

const gb_method_option gb_octree_options[] = {
    {"atlas", "FILE",
     "octree: render it into this atlas (from `atlas`) once\n"
     "and show it through it, one fetch a pixel (default:\n"
     "the bake's NAME.atlas if there is one; none: the\n"
     "octree walk at every pixel)",
     parse_atlas},
    {0},
};
