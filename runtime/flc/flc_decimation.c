#include "flc_decimation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "random.h"

double gb_flc_S0(double D_near, double N_avg)
{
    return 4.0 * M_PI * D_near * D_near / N_avg;
}

void gb_flc_levels_make(double D_near, double N_avg, double mu, int N, gb_flc_levels *levels)
{
    memset(levels, 0, sizeof *levels);
    levels->N = N < 0 ? 0 : N >= GB_FLC_MAX_LEVELS ? GB_FLC_MAX_LEVELS - 1 : N;
    levels->mu = (float)mu;
    levels->N_avg = (float)N_avg;
    levels->D_near = (float)D_near;
    double S0 = gb_flc_S0(D_near, N_avg), inverse_sum = 0.0;
    levels->S0 = (float)S0;
    for (int k = 0; k <= levels->N; ++k) {
        double S_k = S0 * pow(mu, k);                   /* Eq. 17 */
        inverse_sum += 1.0 / S_k;
        levels->S[k] = (float)S_k;
        levels->S_bar[k] = (float)(1.0 / inverse_sum);
        levels->D[k] = (float)sqrt(S_k);                /* Eq. 18 */
    }
    levels->D[levels->N + 1] = levels->D[levels->N];
}

int gb_flc_level(const gb_flc_levels *levels, float u, float area)
{
    if (levels->keep_all)
        return levels->N;
    for (int k = 0; k <= levels->N; ++k)
        if (u < area / levels->S_bar[k])
            return k;
    return -1;
}

float gb_flc_support(const gb_flc_levels *levels, int k, float d)
{
    const float *D = levels->D;
    int N = levels->N;
    if (k < 0 || k > N)
        return 0.0f;
    if (k > 0 && d <= D[k - 1])
        return 0.0f;
    if (k > 0 && d < D[k])                              /* rising */
        return (d - D[k - 1]) / (D[k] - D[k - 1]);
    if (k == N || d <= D[k])
        return 1.0f;
    if (d < D[k + 1])                                   /* falling */
        return (D[k + 1] - d) / (D[k + 1] - D[k]);
    return 0.0f;
}

uint32_t gb_flc_vertex_random(uint64_t seed, uint32_t vertex)
{
    gb_random rng = gb_random_make(seed, vertex);
    return gb_random_uint32(&rng);
}

uint32_t gb_flc_tess_random(uint32_t i, uint32_t j, uint32_t n)
{
    return gb_flc_hash(gb_flc_hash(gb_flc_hash(n) ^ i) ^ (j * 0x9e3779b9u));
}

static void corner(const gb_scene *scene, uint32_t t, int c, double p[3])
{
    const float *v = &scene->positions[3 * (size_t)scene->indices[3 * (size_t)t + c]];
    p[0] = v[0], p[1] = v[1], p[2] = v[2];
}

uint32_t gb_flc_subdivision(const gb_flc_levels *levels, double area)
{
    double limit = levels->S_bar[levels->N];
    if (!(area > limit))
        return 1;
    double n = ceil(sqrt(area / limit));
    return n > GB_FLC_MAX_SUBDIVISION ? GB_FLC_MAX_SUBDIVISION : (uint32_t)n;
}

/* t of gb_flc_tessellation. */
static double tessellation_t(const gb_flc_levels *levels, double area)
{
    double x = sqrt(area / levels->S_bar[levels->N]);
    return sqrt(2.0 / 3.0) * (x < GB_FLC_MAX_SUBDIVISION ? x : GB_FLC_MAX_SUBDIVISION);
}

void gb_flc_tessellation(const gb_flc_levels *levels, double area, uint32_t *c, uint32_t *m)
{
    *c = *m = 1;
    if (!(area > levels->S_bar[levels->N]))
        return;
    double t = tessellation_t(levels, area);
    *c = t > GB_FLC_MAX_TESS_LEVEL ? (uint32_t)ceil(t / GB_FLC_MAX_TESS_LEVEL) : 1;
    *m = 2 * (uint32_t)ceil(t / (2.0 * *c));
    *m = *m < 2 ? 2 : *m;
}

/* The subdivision of triangle t: n (1 for a regular triangle). */
static uint32_t subdivision(const gb_scene *scene, uint32_t t, const gb_flc_levels *levels)
{
    return gb_flc_subdivision(levels, gb_triangle_area(scene, t));
}

/* The point of barycentric grid coordinates (i, j) of n over p[3]. */
static void grid_point(double p[3][3], uint32_t i, uint32_t j, uint32_t n, float out[3])
{
    double a = (double)i / n, b = (double)j / n;
    for (int c = 0; c < 3; ++c)
        out[c] = (float)(p[0][c] + a * (p[1][c] - p[0][c]) + b * (p[2][c] - p[0][c]));
}

static float area_of(const gb_flc_triangle *t)
{
    double e1[3], e2[3];
    for (int c = 0; c < 3; ++c)
        e1[c] = (double)t->p1[c] - t->p0[c], e2[c] = (double)t->p2[c] - t->p0[c];
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2],
           z = e1[0] * e2[1] - e1[1] * e2[0];
    return (float)(0.5 * sqrt(x * x + y * y + z * z));
}

typedef struct grid_corner {
    uint32_t i, j;
} grid_corner;

static void put_sub(double p[3][3], uint32_t n, const grid_corner g[3], uint32_t key,
                    uint32_t material, gb_flc_triangle *out)
{
    grid_point(p, g[0].i, g[0].j, n, out->p0);
    grid_point(p, g[1].i, g[1].j, n, out->p1);
    grid_point(p, g[2].i, g[2].j, n, out->p2);
    out->material = material;
    out->key = key;
    for (int c = 0; c < 3; ++c)
        out->key ^= n > 1 ? gb_flc_tess_random(g[c].i, g[c].j, n) : 0u;
    out->area = area_of(out);
}

/* The n x n sub-triangles of t (its barycentric grid, "up" and "down"
 * triangles of each cell), written from out; returns how many. */
static uint32_t subdivide(const gb_scene *scene, uint32_t t, uint32_t n, uint32_t key,
                          gb_flc_triangle *out)
{
    double p[3][3];
    for (int c = 0; c < 3; ++c)
        corner(scene, t, c, p[c]);
    uint32_t material = scene->triangle_material[t], count = 0;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i + j < n; ++i) {
            grid_corner up[3] = {{i, j}, {i + 1, j}, {i, j + 1}};
            put_sub(p, n, up, key, material, &out[count++]);
            if (i + j + 1 < n) {
                grid_corner down[3] = {{i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                put_sub(p, n, down, key, material, &out[count++]);
            }
        }
    return count;
}

/* The list: regular triangles first, then the divergent ones, subdivided
 * (split) or whole. */
static gb_result build(const gb_scene *scene, const gb_flc_levels *levels, uint64_t seed,
                       int split, gb_flc_triangles *triangles, gb_error *error)
{
    memset(triangles, 0, sizeof *triangles);
    double total = 0.0;
    for (uint32_t t = 0; t < scene->triangle_count; ++t) {
        uint32_t n = subdivision(scene, t, levels);
        total += split ? (double)n * n : 1.0;
    }
    if (total > GB_FLC_MAX_TRIANGLES)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "flc: %.0f VPL triangles after subdividing the divergent ones "
                       "(at most %u): lower N_avg", total, GB_FLC_MAX_TRIANGLES);
    triangles->items = malloc(((size_t)total + 1) * sizeof *triangles->items);
    if (!triangles->items)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "flc: out of memory");
    float limit = levels->S_bar[levels->N];
    for (int divergent = 0; divergent < 2; ++divergent)     /* regular ones first */
        for (uint32_t t = 0; t < scene->triangle_count; ++t) {
            uint32_t n = subdivision(scene, t, levels), key = 0;
            if ((n > 1) != divergent)
                continue;
            for (int c = 0; c < 3; ++c)
                key ^= gb_flc_vertex_random(seed, scene->indices[3 * (size_t)t + c]);
            gb_flc_triangle *out = &triangles->items[triangles->count];
            triangles->count += subdivide(scene, t, split ? n : 1, key, out);
            n > 1 ? ++triangles->divergent_count : ++triangles->regular_count;
            if (n > 1 && split)
                triangles->capped_count += out->area > limit;
            else if (n > 1) {
                triangles->capped_count += out->area > (double)limit * n * n;
                uint32_t cells, level;
                gb_flc_tessellation(levels, out->area, &cells, &level);
                uint64_t side = cells + 1 > 4 ? 4 : cells + 1;
                double t = tessellation_t(levels, out->area) + 2.0 * (cells + 1);
                triangles->patch_bound += side * side;
                triangles->tessellated_bound += (uint64_t)ceil(1.5 * t * t);
            }
        }
    return GB_OK;
}

gb_result gb_flc_triangles_build(const gb_scene *scene, const gb_flc_levels *levels,
                                 uint64_t seed, gb_flc_triangles *triangles, gb_error *error)
{
    return build(scene, levels, seed, 1, triangles, error);
}

gb_result gb_flc_triangles_build_whole(const gb_scene *scene, const gb_flc_levels *levels,
                                       uint64_t seed, gb_flc_triangles *triangles,
                                       gb_error *error)
{
    return build(scene, levels, seed, 0, triangles, error);
}

void gb_flc_triangles_free(gb_flc_triangles *triangles)
{
    free(triangles->items);
    memset(triangles, 0, sizeof *triangles);
}
