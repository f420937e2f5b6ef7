/* test_surface_distance.c — thin's exact distance to the surface
 * (tools/thin/surface_distance.h) against a brute force that tries every
 * surface voxel: equal as floats, on a small random grid, on a grid of
 * 150 x 70 x 66 (past one 64^3 super-block on every axis) with few surface
 * voxels far apart, with one surface voxel in a corner, and with none. */
#include "tap.h"
#include "../../tools/thin/empty_voxels.h"
#include "../../tools/thin/surface_distance.h"
#include "random.h"
#include "voxel_grids.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

static gb_random rng;

static uint32_t random_u32(void)
{
    return gb_random_uint32(&rng);
}

static float brute_distance(const gb_voxel_grid *g, int i, int j, int k)
{
    long best = -1;
    for (int c = 0; c < g->size[2]; ++c)
        for (int b = 0; b < g->size[1]; ++b)
            for (int a = 0; a < g->size[0]; ++a)
                if (g->surface[gb_voxel_index(g, a, b, c)]) {
                    long squared = (long)(a - i) * (a - i) + (long)(b - j) * (b - j)
                                   + (long)(c - k) * (c - k);
                    if (best < 0 || squared < best)
                        best = squared;
                }
    return (float)(sqrt((double)best) * g->voxel_size);
}

/* Mismatches of count voxels (every step-th, in a shuffled order: the
 * previous query's bound is then of a voxel anywhere) against the brute
 * force; -1 when the index could not be built. */
static long mismatches(const gb_voxel_grid *g, size_t step)
{
    gb_empty_voxels empty = {0};
    gb_surface_distance index;
    gb_error error;
    if (gb_empty_voxels_of(g, &empty, &error) != GB_OK)
        return -1;
    if (gb_surface_distance_build(&index, g, &empty, &error) != GB_OK) {
        gb_empty_voxels_free(&empty);
        return -1;
    }
    size_t total = (size_t)g->size[0] * g->size[1] * g->size[2];
    size_t count = (total + step - 1) / step;
    size_t *voxels = malloc(count * sizeof *voxels);
    float *distances = malloc(count * sizeof *distances);
    for (size_t n = 0; n < count; ++n)
        voxels[n] = n * step;
    for (size_t n = count - 1; n > 0; n -= 2) {   /* every other one swapped far */
        size_t m = random_u32() % (n + 1), t = voxels[n];
        voxels[n] = voxels[m];
        voxels[m] = t;
        if (n < 2)
            break;
    }
    long wrong = 0;
    gb_surface_distances(&index, voxels, count, distances);
    for (size_t n = 0; n < count; ++n) {
        size_t v = voxels[n], nx = (size_t)g->size[0], ny = (size_t)g->size[1];
        wrong += distances[n] != brute_distance(g, (int)(v % nx), (int)(v / nx % ny),
                                                (int)(v / nx / ny));
    }
    free(voxels);
    free(distances);
    gb_surface_distance_free(&index);
    gb_empty_voxels_free(&empty);
    return wrong;
}

int main(void)
{
    rng = gb_random_make(48, 0);
    gb_voxel_grid g;
    voxel_grid_make(&g, 13, 9, 7);
    g.voxel_size = 0.3;
    for (size_t v = 0; v < 13 * 9 * 7; ++v)
        g.surface[v] = random_u32() % 37 == 0;
    g.surface[gb_voxel_index(&g, 12, 8, 6)] = 1;
    CHECK_EQ_INT(mismatches(&g, 1), 0, "random 13 x 9 x 7: every voxel's distance is the brute force's");
    gb_voxel_grid_free(&g);

    voxel_grid_make(&g, 150, 70, 66);
    g.voxel_size = 0.125;
    for (int n = 0; n < 12; ++n)
        g.surface[gb_voxel_index(&g, (int)(random_u32() % 150), (int)(random_u32() % 70),
                                 (int)(random_u32() % 66))] = 1;
    CHECK_EQ_INT(mismatches(&g, 97), 0,
                 "150 x 70 x 66, 12 surface voxels: distances across super-blocks exact");
    gb_voxel_grid_free(&g);

    voxel_grid_make(&g, 13, 9, 7);
    g.voxel_size = 0.3;
    g.surface[0] = 1;
    CHECK_EQ_INT(mismatches(&g, 1), 0, "one surface voxel in a corner");
    g.surface[0] = 0;
    gb_empty_voxels empty = {0};
    gb_surface_distance index;
    gb_error error;
    size_t voxel = gb_voxel_index(&g, 4, 6, 3);
    float distance = -1.0f;
    gb_empty_voxels_of(&g, &empty, &error);
    gb_surface_distance_build(&index, &g, &empty, &error);
    gb_surface_distances(&index, &voxel, 1, &distance);
    CHECK(distance == (float)(3.0 * 0.3), "no surface voxel: the distance out of the grid (3 voxels up y)");
    gb_surface_distance_free(&index);
    gb_empty_voxels_free(&empty);
    gb_voxel_grid_free(&g);
    return tap_done();
}
