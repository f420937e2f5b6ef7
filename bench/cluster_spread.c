/* cluster_spread.c — the spread column of vivianloc-2007 Figure 17 on one
 * scene, and what the figure is made of: for each fixed k, the leaves'
 * k-means of cluster (gathering.c, kmeans.c, exactly as cluster runs them)
 * measured several ways:
 *
 *   rms      the spread cluster reports (kmeans.h): power-weighted RMS
 *            chord to the centroid, as an angle; mean over lit leaves
 *   pooled   the same RMS over every photon of every leaf at once
 *   wE       leaves weighted by their irradiance (sum of power)
 *   n>=50    leaves with at least 50 photons gathered only
 *   sd       the standard deviation of the chord (about its mean, not
 *            about 0), as an angle: the other reading of §5.3.2
 *   mean     the mean chord, as an angle
 *   hemi     the same k-means on a cosine-weighted hemisphere (uniform
 *            incident radiance: a diffuse interreflection bound) of the same
 *            photon count per leaf, rms
 *
 *   cluster_spread SCENE IN.phot DEPTH K RESTARTS k...
 * RESTARTS is passed to the k-means (gb_kmeans_options.restarts). With
 * SPREAD_NORMAL_COS=c in the environment, a leaf keeps only the photons
 * whose surface normal is within acos(c) of its own (photons of a wall met
 * at a corner left out).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/cluster/gathering.h"
#include "../tools/cluster/kmeans.h"
#include "../tools/cluster/octree.h"
#include "../tools/cluster/vdl.h"
#include "photon_map.h"
#include "scene.h"

enum { KMAX = 64, CHUNK = 4096 };

typedef struct measure {
    double rms, rms_n, pooled_sum, pooled_weight, weighted, weighted_by, big, big_n;
    double sd, mean, hemi;
} measure;

static double chord_angle(double chord)
{
    return 2.0 * asin(fmin(1.0, 0.5 * chord)) * (180.0 / M_PI);
}

/* A cosine-weighted hemisphere about +z. */
static void hemisphere(gb_random *rng, float *d)
{
    float u1 = gb_random_float(rng), u2 = gb_random_float(rng);
    float r = sqrtf(u1), phi = 2.0f * (float)M_PI * u2;
    d[0] = r * cosf(phi);
    d[1] = r * sinf(phi);
    d[2] = sqrtf(fmaxf(0.0f, 1.0f - u1));
}

static void measure_leaf(gb_vdl_workspace *w, uint32_t k, uint32_t restarts, uint32_t leaf,
                         measure *m, float *hemi_directions, float *ones)
{
    gb_random rng = gb_random_make(0, leaf);
    gb_kmeans_options o = {.restarts = restarts};
    gb_kmeans_directions(w->directions, w->weights, w->count, k, &o, &rng, w->centroids,
                         w->assignment, w->scratch);
    double sum2 = 0.0, sum1 = 0.0, weight = 0.0;
    for (uint32_t i = 0; i < w->count; ++i) {
        const float *d = &w->directions[3 * (size_t)i], *c = &w->centroids[3 * w->assignment[i]];
        double x = d[0] - c[0], y = d[1] - c[1], z = d[2] - c[2], c2 = x * x + y * y + z * z;
        sum2 += w->weights[i] * c2;
        sum1 += w->weights[i] * sqrt(c2);
        weight += w->weights[i];
    }
    if (!(weight > 0.0))
        return;
    double rms = chord_angle(sqrt(sum2 / weight)), mean = sum1 / weight;
    m->rms += rms;
    m->rms_n += 1.0;
    m->pooled_sum += sum2;
    m->pooled_weight += weight;
    m->weighted += weight * rms;
    m->weighted_by += weight;
    if (w->count >= 50) {
        m->big += rms;
        m->big_n += 1.0;
    }
    m->sd += chord_angle(sqrt(fmax(0.0, sum2 / weight - mean * mean)));
    m->mean += chord_angle(mean);
    for (uint32_t i = 0; i < w->count; ++i)
        hemisphere(&rng, &hemi_directions[3 * (size_t)i]);
    gb_kmeans_directions(hemi_directions, ones, w->count, k, &o, &rng, w->centroids,
                         w->assignment, w->scratch);
    m->hemi += gb_kmeans_spread(hemi_directions, ones, w->count, w->centroids, w->assignment);
}

/* Keeps the photons whose surface normal is within acos(normal_cos) of the
 * leaf normal. */
static uint32_t same_surface(const gb_photon_map *map, const float normal[3], float normal_cos,
                             uint32_t *kept, uint32_t n)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < n; ++i) {
        float m[3];
        gb_photon_unpack_normal(map->normals[kept[i]], m);
        if (m[0] * normal[0] + m[1] * normal[1] + m[2] * normal[2] >= normal_cos)
            kept[count++] = kept[i];
    }
    return count;
}

static void print_measure(uint32_t k, const measure *m)
{
    double n = m->rms_n > 0.0 ? m->rms_n : 1.0;
    printf("%3u %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f\n", k, m->rms / n,
           chord_angle(sqrt(m->pooled_sum / (m->pooled_weight > 0.0 ? m->pooled_weight : 1.0))),
           m->weighted / (m->weighted_by > 0.0 ? m->weighted_by : 1.0),
           m->big / (m->big_n > 0.0 ? m->big_n : 1.0), m->sd / n, m->mean / n, m->hemi / n);
}

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: cluster_spread SCENE IN.phot DEPTH K RESTARTS k...\n");
        return 2;
    }
    uint32_t depth = (uint32_t)atoi(argv[3]), K = (uint32_t)atoi(argv[4]);
    uint32_t restarts = (uint32_t)atoi(argv[5]), nk = (uint32_t)(argc - 6), ks[16];
    for (uint32_t i = 0; i < nk && i < 16; ++i)
        ks[i] = (uint32_t)atoi(argv[6 + i]);
    nk = nk < 16 ? nk : 16;
    gb_error error;
    gb_scene scene;
    gb_photon_map map = {0};
    gb_octree_leaves leaves = {0};
    gb_gathering gathering = {0};
    gb_vdl_workspace w = {0};
    if (gb_scene_load(argv[1], NULL, &scene, &error) != GB_OK ||
        gb_photon_map_read(argv[2], &map, &error) != GB_OK ||
        gb_octree_build(&scene, depth, &leaves, &error) != GB_OK ||
        gb_gathering_build(&map, K, 2, &gathering, &error) != GB_OK ||
        gb_vdl_workspace_create(&w, K, KMAX, &error) != GB_OK) {
        fprintf(stderr, "cluster_spread: %s\n", error.message);
        return 1;
    }
    K = gathering.knn;
    int *indices = malloc((size_t)CHUNK * K * sizeof *indices);
    float *distances2 = malloc((size_t)CHUNK * K * sizeof *distances2);
    uint32_t *kept = malloc(K * sizeof *kept);
    float *hemi = malloc(3 * (size_t)K * sizeof *hemi), *ones = malloc(K * sizeof *ones);
    measure m[16];
    memset(m, 0, sizeof m);
    for (uint32_t i = 0; i < K; ++i)
        ones[i] = 1.0f;
    float edge = gb_octree_leaf_edge(&leaves);
    const char *cone = getenv("SPREAD_NORMAL_COS");
    float normal_cos = cone ? strtof(cone, NULL) : -2.0f;
    uint64_t gathered = 0, small = 0;
    for (uint32_t first = 0; first < leaves.count; first += CHUNK) {
        uint32_t count = leaves.count - first < CHUNK ? leaves.count - first : CHUNK;
        if (gb_gathering_knn(&gathering, &leaves.points[3 * (size_t)first], count, indices,
                             distances2, &error) != GB_OK) {
            fprintf(stderr, "cluster_spread: %s\n", error.message);
            return 1;
        }
        for (uint32_t j = 0; j < count; ++j) {
            uint32_t leaf = first + j;
            float radius;
            uint32_t n = gb_gather_ellipsoid(&gathering, &leaves.points[3 * (size_t)leaf],
                                             &leaves.normals[3 * (size_t)leaf],
                                             &indices[(size_t)j * K], &distances2[(size_t)j * K],
                                             3.0f * edge, 1e-4f * edge, 0.5f, kept, &radius);
            if (normal_cos > -1.0f)
                n = same_surface(&map, &leaves.normals[3 * (size_t)leaf], normal_cos, kept, n);
            gb_vdl_workspace_load(&w, &map, kept, n);
            gathered += n;
            small += n > 0 && n < 50;
            for (uint32_t i = 0; i < nk && n > 0; ++i)
                measure_leaf(&w, ks[i], restarts, leaf, &m[i], hemi, ones);
        }
    }
    printf("# %u leaves, %.1f photons gathered per leaf, %llu lit leaves under 50 photons; "
           "restarts %u\n", leaves.count, leaves.count ? (double)gathered / leaves.count : 0.0,
           (unsigned long long)small, restarts);
    printf("%3s %7s %7s %7s %7s %7s %7s %7s\n", "k", "rms", "pooled", "wE", "n>=50", "sd",
           "mean", "hemi");
    for (uint32_t i = 0; i < nk; ++i)
        print_measure(ks[i], &m[i]);
    free(indices);
    free(distances2);
    free(kept);
    free(hemi);
    free(ones);
    gb_vdl_workspace_free(&w);
    gb_gathering_free(&gathering);
    gb_octree_leaves_free(&leaves);
    gb_photon_map_free(&map);
    gb_scene_free(&scene);
    return 0;
}
