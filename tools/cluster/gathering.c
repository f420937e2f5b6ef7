/* gathering.c — FLANN KNN and the ellipsoid of each leaf (gathering.h). */
#include "gathering.h"

#include <flann/flann.h>
#include <math.h>
#include <string.h>

static struct FLANNParameters single_tree_parameters(int threads)
{
    struct FLANNParameters p = DEFAULT_FLANN_PARAMETERS;
    p.algorithm = FLANN_INDEX_KDTREE_SINGLE;
    p.leaf_max_size = 10;
    p.checks = FLANN_CHECKS_UNLIMITED;   /* exact search */
    p.eps = 0.0f;
    p.sorted = 1;
    p.cores = threads;
    p.log_level = FLANN_LOG_NONE;
    p.random_seed = 1;
    return p;
}

gb_result gb_gathering_build(const gb_photon_map *map, uint32_t knn, int threads,
                             gb_gathering *gathering, gb_error *error)
{
    memset(gathering, 0, sizeof *gathering);
    gathering->map = map;
    gathering->threads = threads;
    gathering->knn = knn;
    gathering->searched = map->count < knn ? (uint32_t)map->count : knn;
    if (map->count == 0)
        return GB_OK;
    if (map->count > INT32_MAX)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "gathering: %llu photons, FLANN takes at "
                       "most %d", (unsigned long long)map->count, INT32_MAX);
    struct FLANNParameters p = single_tree_parameters(threads);
    float speedup;
    /* FLANN takes float * but only reads the points (the index copies them) */
    gathering->index = flann_build_index_float((float *)map->positions, (int)map->count, 3,
                                               &speedup, &p);
    if (!gathering->index)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gathering: FLANN could not build its "
                       "kd-tree over %llu photons", (unsigned long long)map->count);
    return GB_OK;
}

/* Spreads count rows of `searched` neighbours to rows of K, last row first
 * (in place), the missing ones as index -1 at infinite distance. */
static void pad_rows(const gb_gathering *gathering, uint32_t count, int *indices,
                     float *distances2)
{
    uint32_t K = gathering->knn, searched = gathering->searched;
    for (uint32_t row = count; row-- > 0;)
        for (uint32_t i = K; i-- > 0;) {
            size_t to = (size_t)row * K + i, from = (size_t)row * searched + i;
            indices[to] = i < searched ? indices[from] : -1;
            distances2[to] = i < searched ? distances2[from] : INFINITY;
        }
}

gb_result gb_gathering_knn(const gb_gathering *gathering, const float *centres,
                           uint32_t count, int *indices, float *distances2, gb_error *error)
{
    if (count == 0 || gathering->knn == 0)
        return GB_OK;
    struct FLANNParameters p = single_tree_parameters(gathering->threads);
    if (gathering->index &&
        flann_find_nearest_neighbors_index_float(gathering->index, (float *)centres,
                                                 (int)count, indices, distances2,
                                                 (int)gathering->searched, &p) != 0)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gathering: FLANN search failed");
    if (gathering->searched < gathering->knn)
        pad_rows(gathering, count, indices, distances2);
    return GB_OK;
}

uint32_t gb_gather_ellipsoid(const gb_gathering *gathering, const float centre[3],
                             const float normal[3], const int *indices,
                             const float *distances2, float max_radius, float min_radius,
                             float flattening, uint32_t *kept, float *radius)
{
    uint32_t k = gathering->knn;
    float r = max_radius;
    if (k > 0 && sqrtf(distances2[k - 1]) < r)
        r = sqrtf(distances2[k - 1]);
    r = fmaxf(r, min_radius);
    *radius = r;
    uint32_t count = 0;
    const float *positions = gathering->map->positions;
    for (uint32_t i = 0; i < k; ++i) {
        if (indices[i] < 0 || distances2[i] > r * r)
            continue;
        const float *p = &positions[3 * (size_t)indices[i]];
        float d[3] = {p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]};
        float along = d[0] * normal[0] + d[1] * normal[1] + d[2] * normal[2];
        float length2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        float tangent2 = fmaxf(0.0f, length2 - along * along);
        float scaled = along / flattening;
        if (tangent2 + scaled * scaled <= r * r)
            kept[count++] = (uint32_t)indices[i];
    }
    return count;
}

void gb_gathering_free(gb_gathering *gathering)
{
    if (gathering->index) {
        struct FLANNParameters p = single_tree_parameters(gathering->threads);
        flann_free_index_float(gathering->index, &p);
    }
    memset(gathering, 0, sizeof *gathering);
}
