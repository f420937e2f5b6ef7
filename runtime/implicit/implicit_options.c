/* implicit_options.c — implicit's gbview options (indirect_method.h),
 * which flc-iv reads too. */
#include "cli.h"
#include "method_parameters.h"

static int parse_bins(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_int("gbview", name, value, 1, 64, &p->implicit.bins);
}

static int parse_bounces(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_int("gbview", name, value, 1, 8, &p->implicit.bounces);
}

static int parse_paper_rules(const char *name, const char *value, gb_method_parameters *p)
{
    (void)name, (void)value;
    p->implicit.paper_rules = 1;
    return GB_EXIT_SUCCESS;
}

const gb_method_option gb_implicit_options[] = {
    {"bins", "N",
     "implicit, flc-iv: 6 x N x N cube-map bins (8, 12\n"
     "default, 16; 12: the paper's compromise of speed\n"
     "and quality)",
     parse_bins},
    {"bounces", "N", "implicit: bounces of indirect light (1 default, 2)", parse_bounces},
    {"paper-rules", NULL,
     "implicit: the links by the paper's rules alone\n"
     "(subdivide at a whole bin, no discs): several\n"
     "times faster to build, coarser shadows",
     parse_paper_rules},
    {0},
};
