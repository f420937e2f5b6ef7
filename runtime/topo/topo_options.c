/* topo_options.c — topo's gbview options (indirect_method.h). */
#include "cli.h"
#include "method_parameters.h"

static int parse_vpls(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_int("gbview", name, value, 1, 1 << 24, &p->topo.vpls);
}

static int parse_write_vpls(const char *name, const char *value, gb_method_parameters *p)
{
    (void)name;
    p->topo.write_vpls = value;
    return GB_EXIT_SUCCESS;
}

static int parse_visibility(const char *name, const char *value, gb_method_parameters *p)
{
    static const char *const visibilities[] = {"full", "clusters", "none"};
    return gb_cli_choice("gbview", name, value, visibilities, 3, &p->topo.visibility);
}

const gb_method_option gb_topo_options[] = {
    {"vpls", "N",
     "topo: VPLs traced from the lights (default 1024:\n"
     "the paper's Table 1 is real time under 512 and\n"
     "interactive to a few thousand)",
     parse_vpls},
    {"write-vpls", "FILE", "topo: write the VPL set (for reference --vpl FILE)",
     parse_write_vpls},
    {"topo-visibility", "V",
     "topo: full (clusters and gates, default), clusters\n"
     "(gates off) or none (no shadows on indirect)",
     parse_visibility},
    {0},
};
