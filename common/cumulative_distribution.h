/* cumulative_distribution.h — picking one of n things with probability
 * proportional to its weight: the discrete distribution p_i = w_i / sum w,
 * its cumulative distribution P_i = sum_{j < i} p_j, and the inversion
 * method (pick i with P_i <= u < P_{i+1} for u uniform in [0, 1), by
 * bisection.h). Used for the area lights by power (light_sampling.h) and the
 * lights of a scene by power (light_emission.h).
 *
 * A weight that is not positive (zero, negative, NaN) counts as zero: such
 * an index is never picked.
 *
 *   gb_cumulative_distribution d;
 *   gb_cumulative_distribution_build(weights, n, &d, &error);
 *   uint32_t i = gb_cumulative_distribution_pick(&d, u);
 *   double p = gb_cumulative_distribution_probability(&d, i);
 *   gb_cumulative_distribution_free(&d);
 *
 * The caller owns the weights (read once by build) and the distribution,
 * which it frees with gb_cumulative_distribution_free.
 */
#ifndef GB_CUMULATIVE_DISTRIBUTION_H
#define GB_CUMULATIVE_DISTRIBUTION_H

#include <stdint.h>

#include "result.h"

typedef struct gb_cumulative_distribution {
    uint32_t count;             /* n */
    double *cdf;                /* n + 1: P_0 = 0 ... P_n = 1 (when total > 0) */
    double total;               /* sum of the positive weights; 0: nothing to pick */
} gb_cumulative_distribution;

gb_result gb_cumulative_distribution_build(const double *weights, uint32_t count,
                                           gb_cumulative_distribution *distribution,
                                           gb_error *error);
void gb_cumulative_distribution_free(gb_cumulative_distribution *distribution);

/* The i with P_i <= u < P_{i+1}, for u in [0, 1): never an index of zero
 * weight. Only when total > 0. */
uint32_t gb_cumulative_distribution_pick(const gb_cumulative_distribution *distribution,
                                         double u);

/* p_i = P_{i+1} - P_i: the probability that pick returns i. */
double gb_cumulative_distribution_probability(const gb_cumulative_distribution *distribution,
                                              uint32_t i);

#endif
