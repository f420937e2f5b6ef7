/* The one bisection (common/bisection.h) and the inversion method over a
 * discrete distribution (common/cumulative_distribution.h) against brute
 * force: a linear scan of the same sorted arrays, and the analytic
 * frequencies w_i / sum w of a stratified sweep of u. */
#include <math.h>
#include <stdlib.h>

#include "bisection.h"
#include "cumulative_distribution.h"
#include "random.h"
#include "tap.h"

typedef struct sorted_ints {
    const int *values;
    int value;
} sorted_ints;

static int at_or_below(const void *user, size_t i)
{
    const sorted_ints *query = user;
    return query->values[i] <= query->value;
}

/* The last i >= 1 with values[i] <= value, else 0: a linear scan. */
static size_t last_linear(const int *values, size_t count, int value)
{
    size_t last = 0;
    for (size_t i = 1; i < count; ++i)
        if (values[i] <= value)
            last = i;
    return last;
}

static void test_bisection(void)
{
    gb_random rng = gb_random_make(5, 0);
    int agree = 1;
    for (int trial = 0; trial < 2000; ++trial) {
        size_t count = 1 + gb_random_below(&rng, 40);
        int values[40];
        values[0] = (int)gb_random_below(&rng, 4);
        for (size_t i = 1; i < count; ++i)     /* increasing, with repeats */
            values[i] = values[i - 1] + (int)gb_random_below(&rng, 3);
        sorted_ints query = {values, (int)gb_random_below(&rng, 90) - 2};
        agree &= gb_bisection_last(count, at_or_below, &query) ==
                 last_linear(values, count, query.value);
    }
    CHECK(agree, "bisection: the linear scan's answer on 2000 sorted arrays with repeats");
}

/* The i with cdf[i] <= u < cdf[i + 1] by a linear scan from the start. */
static uint32_t pick_linear(const gb_cumulative_distribution *d, double u)
{
    uint32_t i = 0;
    while (i + 1 < d->count && d->cdf[i + 1] <= u)
        ++i;
    return i;
}

static void test_distribution(void)
{
    enum { COUNT = 7, SWEEP = 700000 };
    const double w[COUNT] = {0.0, 3.0, 0.0, 1.0, 6.0, -2.0, 0.5};
    const double total = 10.5;
    gb_cumulative_distribution d;
    gb_error error;
    if (!CHECK(gb_cumulative_distribution_build(w, COUNT, &d, &error) == GB_OK, "built"))
        return;
    CHECK_NEAR(d.total, total, 1e-12, "total: the positive weights");
    int probabilities = 1;
    double sum = 0.0;
    for (uint32_t i = 0; i < COUNT; ++i) {
        double p = gb_cumulative_distribution_probability(&d, i);
        probabilities &= fabs(p - (w[i] > 0.0 ? w[i] / total : 0.0)) < 1e-15;
        sum += p;
    }
    CHECK(probabilities, "probability: w_i / sum w, 0 for a weight not positive");
    CHECK_NEAR(sum, 1.0, 1e-15, "probabilities sum to 1");

    /* u on a stratified sweep of [0, 1): index i is picked on an interval of
     * length p_i, so its count is p_i SWEEP within 1. */
    long picked[COUNT] = {0};
    int agree = 1;
    for (long k = 0; k < SWEEP; ++k) {
        double u = (k + 0.5) / SWEEP;
        uint32_t i = gb_cumulative_distribution_pick(&d, u);
        agree &= i == pick_linear(&d, u);
        ++picked[i];
    }
    CHECK(agree, "pick: the linear scan's index for every u");
    int frequencies = 1;
    for (uint32_t i = 0; i < COUNT; ++i)
        frequencies &= fabs(picked[i] - (w[i] > 0.0 ? w[i] / total : 0.0) * SWEEP) <= 1.0;
    CHECK(frequencies, "pick: each index p_i of the time, never one of no weight");
    CHECK(gb_cumulative_distribution_pick(&d, 0.0) == 1 &&
              gb_cumulative_distribution_pick(&d, nextafter(1.0, 0.0)) == COUNT - 1,
          "pick: the ends of [0, 1) go to the first and last indices of weight");
    gb_cumulative_distribution_free(&d);
}

int main(void)
{
    test_bisection();
    test_distribution();
    return tap_done();
}
