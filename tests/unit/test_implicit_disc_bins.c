/* test_implicit_disc_bins.c — the bins through which a point sees a disc
 * (runtime/implicit/implicit_disc_bins.h), against a brute force: every
 * bin of the cube map, its centre ray cut with the disc's plane in double
 * precision. Random discs near and far, tilted, crossing the cube's faces,
 * and a point 5 mm under a wide disc (the cornice under a ceiling).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../runtime/implicit/implicit_disc_bins.h"
#include "random.h"
#include "tap.h"

/* The lengthening the distances may carry (implicit_disc_bins.c: 2^-10). */
#define DISTANCE_TOLERANCE 0x1p-9

typedef struct visited {
    int count, repeated;
    float *distance;            /* bins->count; -1 where not visited */
} visited;

static void note_bin(void *user, int bin, float distance)
{
    visited *v = user;
    v->repeated += v->distance[bin] >= 0.0f;
    v->distance[bin] = distance;
    ++v->count;
}

/* The distance along bin b's centre to the disc, or -1 when the ray misses
 * it; *marginal set when the hit lies within 1e-4 of the rim (rounding may
 * go either way there). */
static double brute_force(const gb_implicit_bins *bins, uint32_t b, const double from[3],
                          const double centre[3], const double normal[3], double radius,
                          int *marginal)
{
    const float *u = &bins->directions[3 * b];
    double height = 0.0, along = 0.0;
    for (int k = 0; k < 3; ++k) {
        height += (centre[k] - from[k]) * normal[k];
        along += u[k] * normal[k];
    }
    double t = height / along;
    *marginal = 0;
    if (!(t > 0.0) || !isfinite(t))
        return -1.0;
    double r2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        double q = from[k] + t * u[k] - centre[k];
        r2 += q * q;
    }
    *marginal = fabs(sqrt(r2) - radius) < 1e-4 * (radius + t);
    return r2 <= radius * radius ? t : -1.0;
}

static void random_unit(gb_random *rng, double n[3])
{
    double length;
    do {
        length = 0.0;
        for (int k = 0; k < 3; ++k) {
            n[k] = 2.0 * gb_random_float(rng) - 1.0;
            length += n[k] * n[k];
        }
    } while (length > 1.0 || length < 1e-4);
    for (int k = 0; k < 3; ++k)
        n[k] /= sqrt(length);
}

/* One disc: the visited bins against the brute force. Returns 1 if they
 * agree (marginal bins either way); counts into *covered. */
static int compare_disc(const gb_implicit_bins *bins, const double from[3],
                        const double centre[3], const double normal[3], double radius,
                        long *covered)
{
    float f[3], c[3], n[3];
    for (int k = 0; k < 3; ++k) {
        f[k] = (float)from[k];
        c[k] = (float)centre[k];
        n[k] = (float)normal[k];
    }
    visited v = {0, 0, malloc(bins->count * sizeof(float))};
    for (uint32_t b = 0; b < bins->count; ++b)
        v.distance[b] = -1.0f;
    gb_implicit_disc_bins(bins, f, c, n, (float)radius, note_bin, &v);
    int agree = v.repeated == 0;
    for (uint32_t b = 0; b < bins->count && agree; ++b) {
        int marginal;
        double t = brute_force(bins, b, from, centre, normal, radius, &marginal);
        if (marginal)
            continue;
        if (t < 0.0)
            agree = v.distance[b] < 0.0f;
        else
            agree = v.distance[b] >= t * (1.0 - 1e-5) &&
                    v.distance[b] <= t * (1.0 + DISTANCE_TOLERANCE);
        *covered += t >= 0.0;
    }
    free(v.distance);
    return agree;
}

static void test_random_discs(int n)
{
    gb_implicit_bins bins;
    gb_error error;
    if (!CHECK(gb_implicit_bins_create(n, &bins, &error) == GB_OK, "bins"))
        return;
    gb_random rng = gb_random_make(7, (uint64_t)n);
    int agree = 1;
    long covered = 0;
    for (int i = 0; i < 2000 && agree; ++i) {
        double from[3] = {0, 0, 0}, centre[3], normal[3], direction[3];
        random_unit(&rng, direction);
        random_unit(&rng, normal);
        /* from far (a fraction of a bin) to nearer than the radius */
        double distance = pow(10.0, 2.0 * gb_random_float(&rng) - 1.0);
        for (int k = 0; k < 3; ++k)
            centre[k] = distance * direction[k];
        agree &= compare_disc(&bins, from, centre, normal, 0.3, &covered);
    }
    char what[128];
    snprintf(what, sizeof what,
             "6x%dx%d bins: 2000 random discs visit exactly the bins whose centre ray meets "
             "them, once, at that distance", n, n);
    CHECK(agree, what);
    printf("# 6x%dx%d: %ld bins covered in all\n", n, n, covered);
    CHECK(covered > 2000, "the random discs cover bins");
    gb_implicit_bins_free(&bins);
}

/* A point 5 mm under a disc of radius 2 facing down: every bin of the upper
 * hemisphere up to 89.8 degrees from the normal meets it. */
static void test_point_under_wide_disc(void)
{
    gb_implicit_bins bins;
    gb_error error;
    if (!CHECK(gb_implicit_bins_create(12, &bins, &error) == GB_OK, "bins"))
        return;
    const double from[3] = {0.3, 0.995, -0.2}, centre[3] = {0, 1, 0}, down[3] = {0, -1, 0};
    long covered = 0;
    CHECK(compare_disc(&bins, from, centre, down, 2.0, &covered),
          "5 mm under a wide disc: the bins match the brute force");
    long upper = 0;
    for (uint32_t b = 0; b < bins.count; ++b)
        upper += bins.directions[3 * b + 1] > 0.01f;
    printf("# 5 mm under a wide disc: %ld bins covered, %ld above 0.6 degrees\n", covered, upper);
    CHECK(covered >= upper, "5 mm under a wide disc: every bin above 0.6 degrees is covered");
    CHECK(covered <= bins.count / 2, "5 mm under a wide disc: no bin below it is");
    float f[3] = {0, 1, 0}, c[3] = {0, 1, 0}, n[3] = {0, -1, 0};
    visited v = {0, 0, malloc(bins.count * sizeof(float))};
    for (uint32_t b = 0; b < bins.count; ++b)
        v.distance[b] = -1.0f;
    gb_implicit_disc_bins(&bins, f, c, n, 2.0f, note_bin, &v);
    CHECK_EQ_INT(v.count, 0, "a point in the disc's plane sees it through no bin");
    free(v.distance);
    gb_implicit_bins_free(&bins);
}

/* A zero-area element's disc (Sponza has them) straight along the centre
 * ray of a bin (6x1x1: each face's one bin looks down its axis),
 * where the ray meets the disc's centre exactly: no bin, and no division by
 * the radius (the sanitized build traps one). */
static void test_disc_of_no_area(void)
{
    gb_implicit_bins bins;
    gb_error error;
    if (!CHECK(gb_implicit_bins_create(1, &bins, &error) == GB_OK, "bins"))
        return;
    float f[3] = {0, 0, 0}, c[3] = {0, 1, 0}, n[3] = {0, -1, 0};
    visited v = {0, 0, malloc(bins.count * sizeof(float))};
    for (uint32_t b = 0; b < bins.count; ++b)
        v.distance[b] = -1.0f;
    gb_implicit_disc_bins(&bins, f, c, n, 1e-3f, note_bin, &v);
    CHECK_EQ_INT(v.count, 1, "a small disc straight up is seen through the bin looking up");
    v.count = 0;
    gb_implicit_disc_bins(&bins, f, c, n, 0.0f, note_bin, &v);
    CHECK_EQ_INT(v.count, 0, "a disc of radius 0 is seen through no bin");
    gb_implicit_disc_bins(&bins, f, c, n, 1e-30f, note_bin, &v);
    CHECK_EQ_INT(v.count, 0, "a disc whose radius squares to 0 is seen through no bin");
    free(v.distance);
    gb_implicit_bins_free(&bins);
}

int main(void)
{
    test_random_discs(8);
    test_random_discs(12);
    test_point_under_wide_disc();
    test_disc_of_no_area();
    return tap_done();
}
