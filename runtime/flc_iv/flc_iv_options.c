/* flc_iv_options.c — flc-iv's own gbview option (indirect_method.h); it
 * takes flc's and implicit's besides. */
#include "cli.h"
#include "method_parameters.h"

static int parse_bin_filter(const char *name, const char *value, gb_method_parameters *p)
{
    static const char *const filters[] = {"bilinear", "nearest"};
    return gb_cli_choice("gbview", name, value, filters, 2, &p->flc_iv.bin_filter);
}

const gb_method_option gb_flc_iv_options[] = {
    {"bin-filter", "F",
     "flc-iv: bilinear (default: the four nearest bins'\n"
     "tests weighed) or nearest (one bin)",
     parse_bin_filter},
    {0},
};
