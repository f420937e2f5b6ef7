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

/* k-means++: the first centroid by weight, each next by weight x D², D the
 * chord to the nearest centroid chosen so far (kept in score, n, updated
 * with each new centroid). Returns the centroids chosen (< k when every
 * direction already coincides with one). */
static uint32_t seed_centroids(const float *directions, const float *weights, uint32_t n,
                               uint32_t k, gb_random *rng, float *centroids, double *score)
{
    double total = 0.0;
    for (uint32_t i = 0; i < n; ++i)
        total += score[i] = weights[i];
    uint32_t chosen = draw_proportional(score, n, total, rng);
    memcpy(centroids, &directions[3 * (size_t)chosen], 3 * sizeof *centroids);
    for (uint32_t i = 0; i < n; ++i)
        score[i] = INFINITY;
    uint32_t made = 1;
    for (; made < k; ++made) {
        const float *newest = &centroids[3 * (made - 1)];
        total = 0.0;
        for (uint32_t i = 0; i < n; ++i) {
            double d2 = chord2(&directions[3 * (size_t)i], newest);
            double s = d2 > 1e-12 ? weights[i] * d2 : 0.0;   /* on a centroid: never drawn */
            total += score[i] = s < score[i] ? s : score[i];
        }
        if (!(total > 0.0))
            break;
        chosen = draw_proportional(score, n, total, rng);
        memcpy(&centroids[3 * made], &directions[3 * (size_t)chosen], 3 * sizeof *centroids);
    }
    return made;
}

/* The photon that adds most to Σ w |d - c|², from a cluster of more than one
 * photon; UINT32_MAX when none adds anything. */
static uint32_t costliest_photon(const float *directions, const float *weights, uint32_t n,
                                 const uint32_t *assignment, const uint32_t *members,
                                 const float *centroids)
{
    uint32_t best = UINT32_MAX;
    double best_cost = 1e-12;
    for (uint32_t i = 0; i < n; ++i) {
        if (members[assignment[i]] < 2)
            continue;
        double cost = weights[i] * chord2(&directions[3 * (size_t)i],
                                          &centroids[3 * (size_t)assignment[i]]);
        if (cost > best_cost) {
            best_cost = cost;
            best = i;
        }
    }
    return best;
}

/* A cluster left empty moves to the costliest photon, which joins it; its
 * old cluster's centroid is kept until the next update. Returns whether any
 * moved. */
static int reseed_empty(const float *directions, const float *weights, uint32_t n, uint32_t k,
                        uint32_t *assignment, float *centroids)
{
    uint32_t members[GB_KMEANS_MAX_CLUSTERS] = {0};
    for (uint32_t i = 0; i < n; ++i)
        ++members[assignment[i]];
    int moved = 0;
    for (uint32_t c = 0; c < k; ++c) {
        if (members[c])
            continue;
        uint32_t i = costliest_photon(directions, weights, n, assignment, members, centroids);
        if (i == UINT32_MAX)
            break;
        --members[assignment[i]];
        assignment[i] = c;
        members[c] = 1;
        memcpy(&centroids[3 * (size_t)c], &directions[3 * (size_t)i], 3 * sizeof *centroids);
        moved = 1;
    }
    return moved;
}

/* Moves each centroid to the normalised weighted mean of its directions; a
 * cluster whose directions cancel keeps its centroid. */
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

static double cost(const float *directions, const float *weights, uint32_t n,
                   const float *centroids, const uint32_t *assignment)
{
    double sum = 0.0;
    for (uint32_t i = 0; i < n; ++i)
        sum += weights[i] * chord2(&directions[3 * (size_t)i], &centroids[3 * (size_t)assignment[i]]);
    return sum;
}

/* One k-means++ seeding and its Lloyd iterations; returns the clusters made. */
static uint32_t run_once(const float *directions, const float *weights, uint32_t n, uint32_t k,
                         gb_random *rng, float *centroids, uint32_t *assignment,
                         double *scratch)
{
    uint32_t made = seed_centroids(directions, weights, n, k, rng, centroids, scratch);
    for (uint32_t i = 0; i < n; ++i)
        assignment[i] = UINT32_MAX;
    for (int iteration = 0; iteration < GB_KMEANS_MAX_ITERATIONS; ++iteration) {
        int changed = assign(directions, n, centroids, made, assignment);
        changed |= reseed_empty(directions, weights, n, made, assignment, centroids);
        if (!changed)
            break;
        update_centroids(directions, weights, n, made, assignment, centroids, scratch);
    }
    return made;
}

uint32_t gb_kmeans_directions(const float *directions, const float *weights, uint32_t n,
                              uint32_t k, const gb_kmeans_options *options, gb_random *rng,
                              float *centroids, uint32_t *assignment, double *scratch)
{
    k = k < GB_KMEANS_MAX_CLUSTERS ? k : GB_KMEANS_MAX_CLUSTERS;
    if (n == 0 || k == 0)
        return 0;
    uint32_t restarts = options && options->restarts ? options->restarts : 1;
    float best[3 * GB_KMEANS_MAX_CLUSTERS];
    double best_cost = INFINITY;
    uint32_t best_made = 0;
    for (uint32_t run = 0; run < restarts; ++run) {
        uint32_t made = run_once(directions, weights, n, k, rng, centroids, assignment, scratch);
        double c = cost(directions, weights, n, centroids, assignment);
        if (c < best_cost || run == 0) {
            best_cost = c;
            best_made = made;
            memcpy(best, centroids, 3 * (size_t)made * sizeof *best);
        }
        if (!(best_cost > 0.0))
            break;
    }
    memcpy(centroids, best, 3 * (size_t)best_made * sizeof *best);
    assign(directions, n, centroids, best_made, assignment);
    return best_made;
}

double gb_kmeans_spread(const float *directions, const float *weights, uint32_t n,
                        const float *centroids, const uint32_t *assignment)
{
    double weight = 0.0;
    for (uint32_t i = 0; i < n; ++i)
        weight += weights[i];
    if (!(weight > 0.0))
        return 0.0;
    double chord = sqrt(cost(directions, weights, n, centroids, assignment) / weight);
    return 2.0 * asin(fmin(1.0, 0.5 * chord)) * (180.0 / M_PI);
}
