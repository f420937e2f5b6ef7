/* surface_distance.c — exact distances to the surface by a pruned search
 * (see surface_distance.h). */
#include "surface_distance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { BLOCK = 8, SUPER = 64, BLOCKS_PER_SUPER = SUPER / BLOCK };

static size_t index3(const int32_t n[3], int32_t i, int32_t j, int32_t k)
{
    return (size_t)i + (size_t)n[0] * ((size_t)j + (size_t)n[1] * (size_t)k);
}

gb_result gb_surface_distance_build(gb_surface_distance *s, const gb_voxel_grid *grid,
                                    const gb_empty_voxels *empty, gb_error *error)
{
    memset(s, 0, sizeof *s);
    for (int a = 0; a < 3; ++a) {
        s->size[a] = grid->size[a];
        s->blocks[a] = (grid->size[a] + BLOCK - 1) / BLOCK;
        s->supers[a] = (grid->size[a] + SUPER - 1) / SUPER;
    }
    s->voxel_size = grid->voxel_size;
    s->empty = empty;
    s->block_marked = calloc((size_t)s->blocks[0] * s->blocks[1] * s->blocks[2], 1);
    s->super_marked = calloc((size_t)s->supers[0] * s->supers[1] * s->supers[2], 1);
    if (!s->block_marked || !s->super_marked) {
        gb_surface_distance_free(s);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "surface distance: out of memory");
    }
    /* a word of 64 empty voxels holds no surface: skipped whole */
    size_t count = (size_t)s->size[0] * s->size[1] * s->size[2];
    for (size_t word = 0; word * 64 < count; ++word) {
        if (empty->bits[word] == ~(uint64_t)0)
            continue;
        size_t end = word * 64 + 64 < count ? word * 64 + 64 : count;
        for (size_t v = word * 64; v < end; ++v) {
            if (gb_voxel_is_empty(empty, v))
                continue;
            int32_t i = (int32_t)(v % (size_t)s->size[0]);
            int32_t j = (int32_t)(v / (size_t)s->size[0] % (size_t)s->size[1]);
            int32_t k = (int32_t)(v / (size_t)s->size[0] / (size_t)s->size[1]);
            s->block_marked[index3(s->blocks, i / BLOCK, j / BLOCK, k / BLOCK)] = 1;
            s->super_marked[index3(s->supers, i / SUPER, j / SUPER, k / SUPER)] = 1;
        }
    }
    return GB_OK;
}

void gb_surface_distance_free(gb_surface_distance *s)
{
    free(s->block_marked);
    free(s->super_marked);
    s->block_marked = s->super_marked = NULL;
}

/* Squared distance from q to the box [lo, lo + side - 1] of voxels. */
static int64_t box_distance2(const int32_t q[3], const int32_t lo[3], int32_t side)
{
    int64_t sum = 0;
    for (int a = 0; a < 3; ++a) {
        int64_t d = lo[a] > q[a] ? lo[a] - q[a] : q[a] > lo[a] + side - 1 ? q[a] - (lo[a] + side - 1) : 0;
        sum += d * d;
    }
    return sum;
}

/* The surface voxels of the row of up to 8 voxels from voxel v on, as bits
 * (bit n: voxel v + n), n < length. */
static unsigned row_surface(const gb_surface_distance *s, size_t v, int length)
{
    const uint64_t *bits = s->empty->bits;
    size_t word = v / 64;
    unsigned offset = (unsigned)(v % 64);
    uint64_t empty = bits[word] >> offset;
    if (offset + (unsigned)length > 64)
        empty |= bits[word + 1] << (64 - offset);
    return (unsigned)(~empty & ((1u << length) - 1));
}

/* Lowers *best to the squared distance from q of the block's surface voxels
 * nearer than it, a row of 8 along x at a time. */
static void scan_block(const gb_surface_distance *s, const int32_t q[3], const int32_t lo[3],
                       int64_t *best)
{
    int32_t hi[3];
    for (int a = 0; a < 3; ++a)
        hi[a] = lo[a] + BLOCK < s->size[a] ? lo[a] + BLOCK : s->size[a];
    int length = hi[0] - lo[0];
    int64_t dx_least = lo[0] > q[0] ? lo[0] - q[0] : q[0] >= hi[0] ? q[0] - hi[0] + 1 : 0;
    for (int32_t k = lo[2]; k < hi[2]; ++k)
        for (int32_t j = lo[1]; j < hi[1]; ++j) {
            int64_t dj = j - q[1], dk = k - q[2], across = dj * dj + dk * dk;
            if (across + dx_least * dx_least >= *best)
                continue;
            unsigned row = row_surface(s, index3(s->size, lo[0], j, k), length);
            for (; row; row &= row - 1) {
                int64_t di = lo[0] + __builtin_ctz(row) - q[0];
                if (across + di * di < *best)
                    *best = across + di * di;
            }
        }
}

/* The block (i, j, k) if it is in the grid, holds surface and is nearer
 * than *best. */
static void visit_block(const gb_surface_distance *s, const int32_t q[3], int32_t i, int32_t j,
                        int32_t k, int64_t *best)
{
    if (i < 0 || j < 0 || k < 0 || i >= s->blocks[0] || j >= s->blocks[1] || k >= s->blocks[2])
        return;
    if (!s->super_marked[index3(s->supers, i / BLOCKS_PER_SUPER, j / BLOCKS_PER_SUPER,
                                k / BLOCKS_PER_SUPER)]
        || !s->block_marked[index3(s->blocks, i, j, k)])
        return;
    int32_t lo[3] = {i * BLOCK, j * BLOCK, k * BLOCK};
    if (box_distance2(q, lo, BLOCK) < *best)
        scan_block(s, q, lo, best);
}

/* The least squared distance, in voxels, from q to a surface voxel, given
 * that it is below bound; bound when there is none below it. Blocks are
 * visited in Chebyshev shells around q's block, nearest first, so that the
 * best found soon prunes the rest. */
static int64_t nearest_squared(const gb_surface_distance *s, const int32_t q[3], int64_t bound)
{
    int64_t best = bound;
    int32_t c[3] = {q[0] / BLOCK, q[1] / BLOCK, q[2] / BLOCK};
    int32_t most = s->blocks[0];
    if (s->blocks[1] > most)
        most = s->blocks[1];
    if (s->blocks[2] > most)
        most = s->blocks[2];
    for (int32_t r = 0; r <= most; ++r) {
        int64_t least = r == 0 ? 0 : (int64_t)(r - 1) * BLOCK + 1;
        if (least * least >= best)
            break;
        /* the shell of radius r: its faces of constant k or j whole, the
         * two ends of its rows between */
        for (int32_t dk = -r; dk <= r; ++dk)
            for (int32_t dj = -r; dj <= r; ++dj) {
                int whole = dk == -r || dk == r || dj == -r || dj == r;
                for (int32_t di = -r; di <= r; di += whole || r == 0 ? 1 : 2 * r)
                    visit_block(s, q, c[0] + di, c[1] + dj, c[2] + dk, &best);
            }
    }
    return best;
}

/* The squared distance from q to the nearest voxel outside the grid (which
 * thin counts as not empty): straight along one axis. */
static int64_t outside_squared(const gb_surface_distance *s, const int32_t q[3])
{
    int64_t least = INT64_MAX;
    for (int a = 0; a < 3; ++a) {
        int64_t below = (int64_t)q[a] + 1, above = (int64_t)s->size[a] - q[a];
        int64_t d = below < above ? below : above;
        least = d < least ? d : least;
    }
    return least * least;
}

void gb_surface_distances(const gb_surface_distance *s, const size_t *voxels, size_t count,
                          float *distances)
{
    size_t nx = (size_t)s->size[0], ny = (size_t)s->size[1];
    int32_t last[3] = {0, 0, 0};
    int64_t last_squared = -1;
    for (size_t n = 0; n < count; ++n) {
        size_t v = voxels[n];
        int32_t q[3] = {(int32_t)(v % nx), (int32_t)(v / nx % ny), (int32_t)(v / nx / ny)};
        /* the previous voxel's nearest is at most |q - last| farther from q
         * (the triangle inequality): a bound just above that, in integers */
        int64_t bound = INT64_MAX;
        if (last_squared >= 0) {
            int64_t di = q[0] - last[0], dj = q[1] - last[1], dk = q[2] - last[2];
            double reach = sqrt((double)last_squared) + sqrt((double)(di * di + dj * dj + dk * dk));
            if (reach < 3.0e9)
                bound = (int64_t)(reach * reach) + 2;
        }
        int64_t squared = nearest_squared(s, q, bound);
        memcpy(last, q, sizeof last);
        if (squared == INT64_MAX)
            squared = outside_squared(s, q);
        last_squared = squared;
        distances[n] = (float)(sqrt((double)squared) * s->voxel_size);
    }
}
