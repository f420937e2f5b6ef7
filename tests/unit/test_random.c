/* PCG32: determinism, independent streams, uniformity. */
#include "random.h"
#include "tap.h"

int main(void)
{
    gb_random a = gb_random_make(42, 7), b = gb_random_make(42, 7);
    int same = 1;
    for (int i = 0; i < 1000; ++i)
        same &= gb_random_uint32(&a) == gb_random_uint32(&b);
    CHECK(same, "same seed and stream give the same sequence");

    gb_random c = gb_random_make(42, 8), d = gb_random_make(42, 7);
    int equal = 0;
    for (int i = 0; i < 1000; ++i)
        equal += gb_random_uint32(&c) == gb_random_uint32(&d);
    CHECK(equal < 3, "another stream gives another sequence");

    gb_random r = gb_random_make(1, 0);
    enum { N = 200000, BINS = 10 };
    int bins[BINS] = {0};
    double sum = 0.0;
    float lowest = 1.0f, highest = 0.0f;
    for (int i = 0; i < N; ++i) {
        float u = gb_random_float(&r);
        sum += u;
        lowest = u < lowest ? u : lowest;
        highest = u > highest ? u : highest;
        bins[(int)(u * BINS)]++;
    }
    CHECK(lowest >= 0.0f && highest < 1.0f, "floats lie in [0, 1)");
    CHECK_NEAR(sum / N, 0.5, 0.005, "mean of uniform floats is 1/2");
    double chi2 = 0.0;
    for (int i = 0; i < BINS; ++i)
        chi2 += (bins[i] - N / BINS) * (double)(bins[i] - N / BINS) / (N / BINS);
    CHECK(chi2 < 27.9, "chi-square of 10 bins below the 0.1% critical value (9 dof)");

    int in_range = 1;
    for (int i = 0; i < 10000; ++i)
        in_range &= gb_random_below(&r, 3) < 3;
    CHECK(in_range, "below(3) stays below 3");
    return tap_done();
}
