/* vdl.c — from a leaf's gathered photons to its VDLs (vdl.h). */
#include "vdl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kmeans.h"

gb_result gb_vdl_workspace_create(gb_vdl_workspace *w, uint32_t capacity, uint32_t vdls_max,
                                  gb_error *error)
{
    memset(w, 0, sizeof *w);
    size_t n = capacity ? capacity : 1, scratch = n > 3 * (size_t)vdls_max ? n : 3 * (size_t)vdls_max;
    w->capacity = capacity;
    w->vdls_max = vdls_max;
    size_t k = 3 * (size_t)vdls_max;
    /* the doubles first, then the 4-byte arrays (7 n + 2 k floats, 2 n
     * indices): each stays aligned */
    w->storage = malloc(scratch * sizeof(double) + (9 * n + 2 * k) * sizeof(float));
    if (!w->storage)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cluster: out of memory");
    w->scratch = w->storage;
    w->directions = (float *)(w->scratch + scratch);
    w->powers = w->directions + 3 * n;
    w->weights = w->powers + 3 * n;
    w->centroids = w->weights + n;
    w->kept_centroids = w->centroids + k;
    w->assignment = (uint32_t *)(void *)(w->kept_centroids + k);
    w->kept_assignment = w->assignment + n;
    return GB_OK;
}

void gb_vdl_workspace_free(gb_vdl_workspace *w)
{
    free(w->storage);
    memset(w, 0, sizeof *w);
}

void gb_vdl_workspace_load(gb_vdl_workspace *w, const gb_photon_map *map,
                           const uint32_t *photon_indices, uint32_t n)
{
    w->count = n;
    for (uint32_t i = 0; i < n; ++i) {
        size_t p = photon_indices[i];
        gb_photon_unpack_direction(map->directions[p], &w->directions[3 * (size_t)i]);
        memcpy(&w->powers[3 * (size_t)i], &map->powers[3 * p], 3 * sizeof(float));
        w->weights[i] = map->powers[3 * p] + map->powers[3 * p + 1] + map->powers[3 * p + 2];
    }
}

static uint32_t run_kmeans(gb_vdl_workspace *w, uint32_t k, gb_random *rng, double *spread)
{
    uint32_t made = gb_kmeans_directions(w->directions, w->weights, w->count, k, &w->kmeans,
                                         rng, w->centroids, w->assignment, w->scratch);
    *spread = gb_kmeans_spread(w->directions, w->weights, w->count, w->centroids,
                               w->assignment);
    return made;
}

/* Keeps the workspace's clustering of `made` clusters aside, and back. */
static void save_clustering(gb_vdl_workspace *w, uint32_t made)
{
    memcpy(w->kept_assignment, w->assignment, w->count * sizeof *w->assignment);
    memcpy(w->kept_centroids, w->centroids, 3 * (size_t)made * sizeof *w->centroids);
}

static void restore_clustering(gb_vdl_workspace *w, uint32_t made)
{
    memcpy(w->assignment, w->kept_assignment, w->count * sizeof *w->assignment);
    memcpy(w->centroids, w->kept_centroids, 3 * (size_t)made * sizeof *w->centroids);
}

/* The fewest k whose clustering spreads at most max_spread, by bisection
 * over k (vdl.h); the workspace keeps that clustering. K_max is tried
 * first: when even it spreads more (most leaves under indirect light), it
 * is the answer. Returns the clusters made. */
static uint32_t choose_clustering(gb_vdl_workspace *w, float max_spread, gb_random *rng,
                                  double *spread)
{
    uint32_t made = run_kmeans(w, w->vdls_max, rng, spread);
    if (*spread > max_spread || w->vdls_max == 1)
        return made;
    uint32_t low = 1, high = w->vdls_max, kept = made; /* high passes; below low fail */
    double kept_spread = *spread;
    save_clustering(w, kept);
    while (low < high) {
        uint32_t k = low + (high - low) / 2;
        made = run_kmeans(w, k, rng, spread);
        if (*spread <= max_spread || made < k) {
            high = k;
            kept = made;
            kept_spread = *spread;
            save_clustering(w, kept);
        } else {
            low = k + 1;
        }
    }
    restore_clustering(w, kept);
    *spread = kept_spread;
    return kept;
}

static int brighter_first(const void *a, const void *b)
{
    const gb_light_octree_vdl *x = a, *y = b;
    float sx = x->irradiance[0] + x->irradiance[1] + x->irradiance[2];
    float sy = y->irradiance[0] + y->irradiance[1] + y->irradiance[2];
    if (sx != sy)
        return sx > sy ? -1 : 1;
    return (x->direction > y->direction) - (x->direction < y->direction);
}

uint32_t gb_vdls_from_photons(gb_vdl_workspace *w, float radius, float max_spread,
                              gb_random *rng, gb_light_octree_vdl *out, double *spread)
{
    *spread = 0.0;
    if (w->count == 0)
        return 0;
    uint32_t made = choose_clustering(w, max_spread, rng, spread);
    double sums[GB_LIGHT_OCTREE_MAX_VDLS][3] = {{0.0}};
    for (uint32_t i = 0; i < w->count; ++i)
        for (int j = 0; j < 3; ++j)
            sums[w->assignment[i]][j] += w->powers[3 * (size_t)i + j];
    double area = M_PI * (double)radius * radius;   /* §3.1.1: density on the disc */
    uint32_t count = 0;
    for (uint32_t c = 0; c < made; ++c) {
        if (!(sums[c][0] + sums[c][1] + sums[c][2] > 0.0))
            continue;
        for (int j = 0; j < 3; ++j)
            out[count].irradiance[j] = (float)(sums[c][j] / area);
        out[count].direction = gb_photon_pack_direction(&w->centroids[3 * c]);
        ++count;
    }
    qsort(out, count, sizeof *out, brighter_first);
    return count;
}
