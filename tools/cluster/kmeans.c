/* kmeans.c — chord-length k-means of directions (kmeans.h). */
#include "kmeans.h"

#include <math.h>
#include <string.h>

static double chord2(const float *a, const float *b)
{
    double d0 = (double)a[0] - b[0], d1 = (double)a[1] - b[1], d2 = (double)a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/* Index of the centroid nearest to d (the lowest on ties): for unit vectors
 * the chord |d - c|² = 2 - 2 d.c, so the nearest has the largest dot. */
static uint32_t nearest_centroid(const float *d, const float *centroids, uint32_t k)
{
    uint32_t best = 0;
    float best_dot = d[0] * centroids[0] + d[1] * centroids[1] + d[2] * centroids[2];
    for (uint32_t c = 1; c < k; ++c) {
        const float *m = &centroids[3 * c];
        float dot = d[0] * m[0] + d[1] * m[1] + d[2] * m[2];
        if (dot > best_dot) {
            best_dot = dot;
            best = c;
        }
    }
    return best;
}

/* A sample drawn with probability proportional to score[i]; total > 0. */
static uint32_t draw_proportional(const double *score, uint32_t n, double total,
                                  gb_random *rng)
{
    double u = (double)gb_random_float(rng) * total, sum = 0.0;
    uint32_t last = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (score[i] <= 0.0)
            continue;
        sum += score[i];
        last = i;
        if (u < sum)
            return i;
    }
    return last;
}

/* k-means++: the first centroid by weight, each next by weight x D². Uses
 * score (n) as scratch. Returns the centroids chosen (< k when every
 * direction already coincides with one). */
static uint32_t seed_centroids(const float *directions, const float *weights, uint32_t n,
                               uint32_t k, gb_random *rng, float *centroids, double *score)
{
    double total = 0.0;
    for (uint32_t i = 0; i < n; ++i)
        total += score[i] = weights[i];
    uint32_t chosen = draw_proportional(score, n, total, rng);
    memcpy(centroids, &directions[3 * (size_t)chosen], 3 * sizeof *centroids);
    uint32_t made = 1;
    for (; made < k; ++made) {
        total = 0.0;
        for (uint32_t i = 0; i < n; ++i) {
            const float *d = &directions[3 * (size_t)i];
            double best = chord2(d, &centroids[3 * (size_t)nearest_centroid(d, centroids, made)]);
            total += score[i] = best > 1e-12 ? weights[i] * best : 0.0;
        }
        if (!(total > 0.0))
            break;
        chosen = draw_proportional(score, n, total, rng);
        memcpy(&centroids[3 * made], &directions[3 * (size_t)chosen], 3 * sizeof *centroids);
    }
    return made;
}

/* Moves each centroid to the normalised weighted mean of its directions; a
 * cluster left empty, or whose directions cancel, keeps its centroid. */
static void update_centroids(const float *directions, const float *weights, uint32_t n,
                             uint32_t k, const uint32_t *assignment, float *centroids,
                             double *sums)
{
    memset(sums, 0, 3 * (size_t)k * sizeof *sums);
    for (uint32_t i = 0; i < n; ++i)
        for (int j = 0; j < 3; ++j)
            sums[3 * (size_t)assignment[i] + j] += (double)weights[i] * directions[3 * (size_t)i + j];
    for (uint32_t c = 0; c < k; ++c) {
        double *s = &sums[3 * c];
        double length = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        if (length > 1e-12)
            for (int j = 0; j < 3; ++j)
                centroids[3 * c + j] = (float)(s[j] / length);
    }
}

static int assign(const float *directions, uint32_t n, const float *centroids, uint32_t k,
                  uint32_t *assignment)
{
    int changed = 0;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t c = nearest_centroid(&directions[3 * (size_t)i], centroids, k);
        changed |= c != assignment[i];
        assignment[i] = c;
    }
    return changed;
}

uint32_t gb_kmeans_directions(const float *directions, const float *weights, uint32_t n,
                              uint32_t k, gb_random *rng, float *centroids,
                              uint32_t *assignment, double *scratch)
{
    if (n == 0 || k == 0)
        return 0;
    uint32_t made = seed_centroids(directions, weights, n, k, rng, centroids, scratch);
    for (uint32_t i = 0; i < n; ++i)
        assignment[i] = UINT32_MAX;
    for (int iteration = 0; iteration < GB_KMEANS_MAX_ITERATIONS; ++iteration) {
        if (!assign(directions, n, centroids, made, assignment))
            break;
        update_centroids(directions, weights, n, made, assignment, centroids, scratch);
    }
    return made;
}

double gb_kmeans_spread(const float *directions, const float *weights, uint32_t n,
                        const float *centroids, const uint32_t *assignment)
{
    double sum = 0.0, weight = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
        sum += weights[i] * chord2(&directions[3 * (size_t)i], &centroids[3 * (size_t)assignment[i]]);
        weight += weights[i];
    }
    if (!(weight > 0.0))
        return 0.0;
    double chord = sqrt(sum / weight);
    return 2.0 * asin(fmin(1.0, 0.5 * chord)) * (180.0 / M_PI);
}
