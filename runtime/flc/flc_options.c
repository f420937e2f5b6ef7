/* flc_options.c — flc's gbview options (indirect_method.h), which flc-iv
 * takes too. */
#include "cli.h"
#include "method_parameters.h"

static int parse_n_avg(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_float("gbview", name, value, 1.0, 1e6, &p->flc.n_avg);
}

static int parse_mu(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_float("gbview", name, value, 1.01, 1e3, &p->flc.mu);
}

static int parse_levels(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_int("gbview", name, value, 1, GB_FLC_MAX_LEVELS, &p->flc.levels);
}

static int parse_epsilon(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_float("gbview", name, value, 1e-30, 1e30, &p->flc.epsilon);
}

static int parse_tiling(const char *name, const char *value, gb_method_parameters *p)
{
    return gb_cli_int("gbview", name, value, 0, GB_FLC_MAX_TILING, &p->flc.tiling);
}

static int parse_no_decimation(const char *name, const char *value, gb_method_parameters *p)
{
    (void)name, (void)value;
    p->flc.levels = GB_FLC_NO_DECIMATION;
    return GB_EXIT_SUCCESS;
}

const gb_method_option gb_flc_options[] = {
    {"navg", "N",
     "flc: N_avg, VPLs lighting a pixel (Eq. 1; default 256,\n"
     "within the paper's 64..1024 for quality or speed)",
     parse_n_avg},
    {"mu", "M", "flc: level growth, S_k = S0 M^k (Eq. 17; default 2)", parse_mu},
    {"levels", "L", "flc: N + 1 levels of VPLs (default 6, at most 16)", parse_levels},
    {"epsilon", "E",
     "flc: distance clamp, world units (default 1% of the\n"
     "scene's radius)",
     parse_epsilon},
    {"tiling", "T", "flc: splat into 4^T interleaved tiles (default 0)", parse_tiling},
    {"no-decimation", NULL,
     "flc: every triangle a VPL (the estimator without\n"
     "light cuts, for comparison)",
     parse_no_decimation},
    {0},
};
