/* cumulative_distribution.c — the inversion method over a discrete
 * distribution (cumulative_distribution.h). */
#include "cumulative_distribution.h"

#include <stdlib.h>

#include "bisection.h"

gb_result gb_cumulative_distribution_build(const double *weights, uint32_t count,
                                           gb_cumulative_distribution *distribution,
                                           gb_error *error)
{
    *distribution = (gb_cumulative_distribution){.count = count};
    distribution->cdf = malloc(((size_t)count + 1) * sizeof *distribution->cdf);
    if (!distribution->cdf)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                       "cumulative distribution: out of memory for %u weights", count);
    double *cdf = distribution->cdf, total = 0.0;
    cdf[0] = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        if (weights[i] > 0.0)
            total += weights[i];
        cdf[i + 1] = total;
    }
    distribution->total = total;
    if (!(total > 0.0))
        return GB_OK;
    for (uint32_t i = 1; i <= count; ++i)
        cdf[i] /= total;
    cdf[count] = 1.0;
    return GB_OK;
}

void gb_cumulative_distribution_free(gb_cumulative_distribution *distribution)
{
    free(distribution->cdf);
    *distribution = (gb_cumulative_distribution){0};
}

typedef struct pick_query {
    const double *cdf;
    double u;
} pick_query;

static int at_or_below_u(const void *user, size_t i)
{
    const pick_query *query = user;
    return query->cdf[i] <= query->u;
}

uint32_t gb_cumulative_distribution_pick(const gb_cumulative_distribution *distribution,
                                         double u)
{
    pick_query query = {distribution->cdf, u};
    return (uint32_t)gb_bisection_last(distribution->count, at_or_below_u, &query);
}

double gb_cumulative_distribution_probability(const gb_cumulative_distribution *distribution,
                                              uint32_t i)
{
    return distribution->cdf[i + 1] - distribution->cdf[i];
}
