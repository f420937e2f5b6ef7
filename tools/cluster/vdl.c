/* vdl.c — from a leaf's gathered photons to its VDLs (vdl.h). */
#include "vdl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kmeans.h"
#include "light_octree_shading.h"

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

/* The light a VDL from direction w brings to normal n, as a factor of its
 * irradiance: the runtime's (gb_light_octree_vdl_gain) where it is lit. */
static double shading_factor(const float n[3], const float leaf_normal[3], const float w[3])
{
    return fmaxf(gb_light_octree_vdl_gain(n, leaf_normal, w), 0.0f);
}

/* The photons' own light at each normal: what VDLs of one photon each give. */
static void photon_light(const gb_vdl_workspace *w, const vdl_target *target, double *light)
{
    for (uint32_t j = 0; j < target->normal_count; ++j) {
        light[j] = 0.0;
        for (uint32_t i = 0; i < w->count; ++i)
            light[j] += w->weights[i] * shading_factor(target->normals[j].normal,
                                                       target->leaf_normal,
                                                       &w->directions[3 * (size_t)i]);
    }
}

/* The error of the workspace's clustering of `made` clusters (vdl.h): the
 * largest difference, over the target's normals, between its VDLs' light
 * and the photons' (light), over the leaf's irradiance. */
static double clustering_error(const gb_vdl_workspace *w, uint32_t made, const vdl_target *target,
                               const double *light)
{
    double cluster_weight[GB_LIGHT_OCTREE_MAX_VDLS] = {0.0}, total = 0.0;
    for (uint32_t i = 0; i < w->count; ++i) {
        cluster_weight[w->assignment[i]] += w->weights[i];
        total += w->weights[i];
    }
    float directions[GB_LIGHT_OCTREE_MAX_VDLS][3];
    for (uint32_t c = 0; c < made; ++c) {
        const float *m = &w->centroids[3 * c];
        float length = sqrtf(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
        for (int k = 0; k < 3; ++k)
            directions[c][k] = length > 0.0f ? m[k] / length : 0.0f;
    }
    double error = 0.0;
    for (uint32_t j = 0; j < target->normal_count; ++j) {
        double vdl_light = 0.0;
        for (uint32_t c = 0; c < made; ++c)
            vdl_light += cluster_weight[c] * shading_factor(target->normals[j].normal,
                                                            target->leaf_normal, directions[c]);
        error = fmax(error, fabs(vdl_light - light[j]));
    }
    return total > 0.0 ? error / total : 0.0;
}

static uint32_t run_kmeans(gb_vdl_workspace *w, uint32_t k, gb_random *rng)
{
    return gb_kmeans_directions(w->directions, w->weights, w->count, k, &w->kmeans, rng,
                                w->centroids, w->assignment, w->scratch);
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

/* The fewest k whose clustering is within the tolerance (vdl.h): k = 1, 2,
 * 4 ... up to K_max until one is, then bisection between the last that was
 * not and it; K_max when none is. The workspace keeps that clustering.
 * Returns the clusters made. */
static uint32_t choose_clustering(gb_vdl_workspace *w, const vdl_target *target,
                                  gb_random *rng, double *error)
{
    double light[GB_SURFACE_NORMALS];
    photon_light(w, target, light);
    uint32_t k = target->tolerance < 0.0f ? w->vdls_max : 1, failed = 0, made;
    for (;;) {
        made = run_kmeans(w, k, rng);
        *error = clustering_error(w, made, target, light);
        if (*error <= target->tolerance || made < k || k == w->vdls_max)
            break;
        failed = k;
        k = 2 * k < w->vdls_max ? 2 * k : w->vdls_max;
    }
    if (!(*error <= target->tolerance || made < k))
        return made;                            /* K_max, not within the tolerance */
    uint32_t low = failed + 1, high = k, kept = made; /* high passes; below low fail */
    double kept_error = *error;
    save_clustering(w, kept);
    while (low < high) {
        uint32_t middle = low + (high - low) / 2;
        made = run_kmeans(w, middle, rng);
        *error = clustering_error(w, made, target, light);
        if (*error <= target->tolerance || made < middle) {
            high = middle;
            kept = made;
            kept_error = *error;
            save_clustering(w, kept);
        } else {
            low = middle + 1;
        }
    }
    restore_clustering(w, kept);
    *error = kept_error;
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

uint32_t gb_vdls_from_photons(gb_vdl_workspace *w, const vdl_target *target, gb_random *rng,
                              gb_light_octree_vdl *out, double *error)
{
    *error = 0.0;
    if (w->count == 0)
        return 0;
    uint32_t made = choose_clustering(w, target, rng, error);
    double sums[GB_LIGHT_OCTREE_MAX_VDLS][3] = {{0.0}};
    for (uint32_t i = 0; i < w->count; ++i)
        for (int j = 0; j < 3; ++j)
            sums[w->assignment[i]][j] += w->powers[3 * (size_t)i + j];
    double area = M_PI * (double)target->radius * target->radius;   /* §3.1.1: density on the disc */
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
