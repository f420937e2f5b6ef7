/* flc_decimation.h — the CPU side of Forward Light Cuts (Laurent et al.
 * 2016): the multiscale parameters (S0, S_k, S̄_k, D_k), the stochastic
 * decimation and partition of Alg. 1, the partition of unity f^k (Eq. 16),
 * the per-vertex and per-triangle random values (Alg. 2) and the list of
 * VPL triangles the GPU draws each frame.
 *
 * The GLSL of runtime/flc.c mirrors gb_flc_hash, gb_flc_uniform,
 * gb_flc_level and gb_flc_support name for name; change both together.
 *
 * Divergent triangles (area > S̄_N, Sec. 4) are subdivided here, once, in
 * model space, into n x n equal triangles (n = ceil(sqrt(area / S̄_N))):
 * the pattern the paper's tessellation stage would make, which depends only
 * on the triangle's area, with the per-sub-vertex random value v_rand_tess a
 * hash of its barycentric grid coordinates (Fig. 8). The scene is static,
 * so the second (indirect) draw of the paper becomes part of the one list.
 *
 * gb_flc_triangles_build → (draw) → gb_flc_triangles_free (also on a zeroed one).
 */
#ifndef GB_FLC_DECIMATION_H
#define GB_FLC_DECIMATION_H

#include <stdint.h>

#include "result.h"
#include "scene.h"

enum {
    GB_FLC_MAX_LEVELS = 16,         /* N + 1 at most */
    GB_FLC_MAX_SUBDIVISION = 256,   /* n at most for one divergent triangle */
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
} gb_flc_levels;

/* S0 = 4 pi D_near^2 / N_avg (Eq. 1). */
double gb_flc_S0(double D_near, double N_avg);
/* Fills levels; N is clamped to 0..GB_FLC_MAX_LEVELS-1. */
void gb_flc_levels_make(double D_near, double N_avg, double mu, int N, gb_flc_levels *levels);

/* Alg. 1: the level k of a triangle of that area for its uniform u in
 * [0, 1), or -1 when it is discarded. P(k) = area / S_k for a regular
 * triangle (area <= S̄_N), so P(k <= K) = area / S̄_K (Eq. 3). */
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
/* v_rand_tess of the sub-vertex (i, j) of a grid of n (Fig. 8). */
uint32_t gb_flc_tess_random(uint32_t i, uint32_t j, uint32_t n);
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

typedef struct gb_flc_triangles {
    uint32_t count;
    gb_flc_triangle *items;
    uint32_t regular_count;         /* scene triangles kept whole */
    uint32_t divergent_count;       /* scene triangles subdivided */
    uint32_t capped_count;          /* divergent ones still above S̄_N (n capped) */
} gb_flc_triangles;

/* The scene's triangles, the divergent ones subdivided. GB_ERROR_UNSUPPORTED
 * beyond GB_FLC_MAX_TRIANGLES (a smaller N_avg helps). */
gb_result gb_flc_triangles_build(const gb_scene *scene, const gb_flc_levels *levels,
                                 uint64_t seed, gb_flc_triangles *triangles, gb_error *error);
void gb_flc_triangles_free(gb_flc_triangles *triangles);

#endif
