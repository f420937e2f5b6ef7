/* flc_decimation.h — the CPU side of Forward Light Cuts (Laurent et al.
 * 2016): the multiscale parameters (S0, S_k, S̄_k, D_k), the stochastic
 * decimation and partition of Alg. 1, the partition of unity f^k (Eq. 16),
 * the per-vertex and per-triangle random values (Alg. 2) and the list of
 * VPL triangles the GPU draws each frame.
 *
 * The GLSL of runtime/flc/ (flc_common.glsl, flc_generate.glsl) mirrors
 * gb_flc_hash, gb_flc_uniform, gb_flc_level and gb_flc_support name for
 * name; change both together.
 *
 * Divergent triangles (area > S̄_N, Sec. 4) need n = ceil(sqrt(area / S̄_N))
 * (at most GB_FLC_MAX_SUBDIVISION) subdivisions a side. The runtime
 * (runtime/flc/flc.c) keeps them whole (gb_flc_triangles_build_whole) and has
 * the GPU's tessellation stage subdivide them each frame, in a second,
 * indirect, draw (the paper's divergent pipeline): the barycentric grid of
 * c x c cells, each tessellated at one even level m <= GB_FLC_MAX_TESS_LEVEL
 * (gb_flc_tessellation). GL's equal-spacing pattern of an even level m is
 * m / 2 concentric rings, 3 m^2 / 2 triangles in all, each 2 / (3 m^2) of
 * the cell's area, so m is the least even level for which that is <= S̄_N:
 * the sub-triangles are as large as Alg. 1 allows, about as many as an
 * n x n grid's. (An odd level would leave a centre triangle of 1 / m^2.)
 * v_rand_tess of a sub-vertex is a hash of its barycentric coordinates
 * quantized to 1 / GB_FLC_TESS_GRID (gb_flc_tess_coord_random; the paper
 * fetches a noise texture there). gb_flc_triangles_build splits them on the
 * CPU instead, into the n x n equal triangles of the barycentric grid
 * (gb_flc_tess_random): the runtime's former path, kept for the tests.
 *
 * gb_flc_triangles_build[_whole] → (draw) → gb_flc_triangles_free (also on
 * a zeroed one).
 */
#ifndef GB_FLC_DECIMATION_H
#define GB_FLC_DECIMATION_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

enum {
    GB_FLC_MAX_LEVELS = 16,         /* N + 1 at most */
    GB_FLC_MAX_SUBDIVISION = 256,   /* n at most for one divergent triangle */
    GB_FLC_MAX_TESS_LEVEL = 64,     /* m at most: GL's least GL_MAX_TESS_GEN_LEVEL */
    GB_FLC_TESS_GRID = 1 << 20,     /* the quantum of v_rand_tess's coordinates */
};
#define GB_FLC_MAX_TRIANGLES (1u << 24)

typedef struct gb_flc_levels {
    int N;                          /* levels 0..N */
    float mu;                       /* S_k = S0 mu^k (Eq. 17), mu > 1 */
    float N_avg, D_near;
    float S0;                       /* Eq. 1 */
    float S[GB_FLC_MAX_LEVELS];     /* S_k */
    float S_bar[GB_FLC_MAX_LEVELS]; /* S̄_k = 1 / sum_{j<=k} 1/S_j */
    float D[GB_FLC_MAX_LEVELS + 1]; /* D_k = sqrt(S0 mu^k) (Eq. 18), D_{N+1} = D_N */
    int keep_all;                   /* no decimation: every VPL triangle is kept, at
                                       level N (support everywhere), its weight its
                                       own area instead of S_N (the brute-force
                                       estimator FLC approximates); 0: Alg. 1 */
} gb_flc_levels;

/* S0 = 4 pi D_near^2 / N_avg (Eq. 1). */
double gb_flc_S0(double D_near, double N_avg);
/* Fills levels; N is clamped to 0..GB_FLC_MAX_LEVELS-1. */
void gb_flc_levels_make(double D_near, double N_avg, double mu, int N, gb_flc_levels *levels);

/* Alg. 1: the level k of a triangle of that area for its uniform u in
 * [0, 1), or -1 when it is discarded. P(k) = area / S_k for a regular
 * triangle (area <= S̄_N), so P(k <= K) = area / S̄_K (Eq. 3). With
 * keep_all: always N. */
int gb_flc_level(const gb_flc_levels *levels, float u, float area);

/* f^k(d) of Eq. 16, a piecewise affine partition of unity in d >= 0: level
 * 0 is 1 up to D_0, every level a hat over D_{k-1}, D_k, D_{k+1}, and level
 * N stays 1 beyond D_N (so that sum_k f^k(d) = 1 for every d; the paper's
 * D_{N+1} = D_N would leave distances beyond D_N unlit). */
float gb_flc_support(const gb_flc_levels *levels, int k, float d);

/* The integer hash behind every random value (PCG, Jarzynski & Olano 2020). */
static inline uint32_t gb_flc_hash(uint32_t v)
{
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* A uniform in [0, 1) from 32 random bits. */
static inline float gb_flc_uniform(uint32_t bits)
{
    return (float)(bits >> 8) * 0x1p-24f;
}

/* v_rand of vertex (Alg. 2), from PCG32 stream `vertex` of seed. */
uint32_t gb_flc_vertex_random(uint64_t seed, uint32_t vertex);
/* v_rand_tess of the sub-vertex (i, j) of a grid of n (Fig. 8), CPU subdivision. */
uint32_t gb_flc_tess_random(uint32_t i, uint32_t j, uint32_t n);
/* v_rand_tess of the tessellation's sub-vertex at barycentric (a, b) of its
 * base triangle, from g = round((a, b) GB_FLC_TESS_GRID) (the GLSL's twin). */
static inline uint32_t gb_flc_tess_coord_random(uint32_t ga, uint32_t gb)
{
    return gb_flc_hash(gb_flc_hash(ga) ^ (gb * 0x9e3779b9u));
}
/* The subdivision n of a triangle of that area (1: regular). */
uint32_t gb_flc_subdivision(const gb_flc_levels *levels, double area);
/* Its tessellation (the GLSL's twin): with t = sqrt(2/3) min(sqrt(area /
 * S̄_N), GB_FLC_MAX_SUBDIVISION), c = ceil(t / GB_FLC_MAX_TESS_LEVEL) cells a
 * side, each of the even level m = 2 ceil(t / 2c) (at least 2); c = m = 1 for
 * a regular triangle. */
void gb_flc_tessellation(const gb_flc_levels *levels, double area, uint32_t *c, uint32_t *m);
/* u_i of a triangle whose key is the XOR of its vertices' values: the hash
 * of key XOR u_rand (Alg. 2, hashed so that triangles sharing vertices are
 * not correlated). */
static inline uint32_t gb_flc_triangle_random(uint32_t key, uint32_t u_rand)
{
    return gb_flc_hash(key ^ u_rand);
}

/* One VPL triangle, 48 bytes, the std430 layout of the GPU's
 * struct { vec4 p0_material; vec4 p1_key; vec4 p2_area; }. */
typedef struct gb_flc_triangle {
    float p0[3];
    uint32_t material;
    float p1[3];
    uint32_t key;                   /* XOR of the corners' v_rand (and v_rand_tess) */
    float p2[3];
    float area;
} gb_flc_triangle;

/* items[0, regular_count) are the regular scene triangles, in scene order;
 * items[regular_count, count) the sub-triangles of the divergent ones, or
 * with _whole the divergent ones themselves (the paper's divergent
 * pipeline), so that each pipeline can be drawn and timed apart. */
typedef struct gb_flc_triangles {
    uint32_t count;
    gb_flc_triangle *items;
    uint32_t regular_count;         /* scene triangles kept whole */
    uint32_t divergent_count;       /* scene triangles subdivided */
    uint32_t capped_count;          /* divergent ones still above S̄_N (n capped) */
    /* _whole: room for the tessellation, with slack for the GPU's float
     * arithmetic rounding c or m up: */
    uint64_t patch_bound;           /* cells, sum of (c + 1)^2 (at most 16) */
    uint64_t tessellated_bound;     /* sub-triangles, sum of 3 (t + 2 c + 2)^2 / 2 */
} gb_flc_triangles;

/* The scene's triangles, the divergent ones subdivided. GB_ERROR_UNSUPPORTED
 * beyond GB_FLC_MAX_TRIANGLES (a smaller N_avg helps). */
gb_result gb_flc_triangles_build(const gb_scene *scene, const gb_flc_levels *levels,
                                 uint64_t seed, gb_flc_triangles *triangles, gb_error *error);
/* The same list with the divergent triangles whole (one item each, after the
 * regular ones), for the GPU's tessellation; divergent_count and
 * capped_count as above, the bounds set. */
gb_result gb_flc_triangles_build_whole(const gb_scene *scene, const gb_flc_levels *levels,
                                       uint64_t seed, gb_flc_triangles *triangles,
                                       gb_error *error);
void gb_flc_triangles_free(gb_flc_triangles *triangles);

#endif
