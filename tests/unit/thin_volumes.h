/* thin_volumes.h — small synthetic voxel volumes for the thin tests, and the
 * topology of their empty space computed without thin's code: components by
 * flood fill, the Euler characteristic of the cubical complex of closed
 * cubes by marking its faces on the doubled (Khalimsky) lattice, cavities by
 * flooding the complement, b1 from the three. */
#ifndef GB_THIN_VOLUMES_H
#define GB_THIN_VOLUMES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "voxel_grid.h"

/* ---- building volumes ---- */

/* A grid of nx x ny x nz wall voxels (voxel size 0.5, origin (1,2,3)). */
static gb_voxel_grid volume_solid(int nx, int ny, int nz)
{
    gb_voxel_grid grid = {0};
    int32_t size[3] = {nx, ny, nz};
    if (gb_voxel_grid_allocate(&grid, size, NULL)) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    memset(grid.surface, 1, (size_t)nx * ny * nz);
    grid.voxel_size = 0.5;
    grid.world_origin[0] = 1.0;
    grid.world_origin[1] = 2.0;
    grid.world_origin[2] = 3.0;
    grid.scene_hash = 0x1234abcd5678ef01ull;
    grid.resolution = (uint32_t)(nx > ny ? (nx > nz ? nx : nz) : (ny > nz ? ny : nz));
    return grid;
}

static int volume_inside(const gb_voxel_grid *g, int i, int j, int k)
{
    return i >= 0 && j >= 0 && k >= 0 && i < g->size[0] && j < g->size[1] && k < g->size[2];
}

/* Sets voxels of the box [x0,x1] x [y0,y1] x [z0,z1] (inclusive) to value
 * (0 empty, 1 wall). */
static void volume_box(gb_voxel_grid *g, int x0, int y0, int z0, int x1, int y1, int z1,
                       uint8_t value)
{
    for (int k = z0; k <= z1; ++k)
        for (int j = y0; j <= y1; ++j)
            for (int i = x0; i <= x1; ++i)
                if (volume_inside(g, i, j, k))
                    g->surface[gb_voxel_index(g, i, j, k)] = value;
}

/* Boxes for volume_boxes: {x0, y0, z0, x1, y1, z1, VOLUME_EMPTY or
 * VOLUME_SOLID}, the corners included; a zeroed one (VOLUME_END) ends the
 * list. */
enum { VOLUME_END, VOLUME_EMPTY, VOLUME_SOLID };

/* volume_box of each box in turn, up to the first VOLUME_END. */
static void volume_boxes(gb_voxel_grid *g, const int (*boxes)[7])
{
    for (; boxes[0][6] != VOLUME_END; ++boxes)
        volume_box(g, boxes[0][0], boxes[0][1], boxes[0][2], boxes[0][3], boxes[0][4],
                   boxes[0][5], boxes[0][6] == VOLUME_SOLID);
}

static int volume_empty(const gb_voxel_grid *g, int i, int j, int k)
{
    return volume_inside(g, i, j, k) && !g->surface[gb_voxel_index(g, i, j, k)];
}

/* The exact distance of voxel (i, j, k) to the nearest wall voxel of the
 * grid, centre to centre, in world units, by trying every voxel:
 * voxel_size * sqrt(n), n the least squared distance in voxels, as thin's
 * node radii should be. */
static float volume_brute_distance(const gb_voxel_grid *g, int i, int j, int k)
{
    long best = -1;
    for (int z = 0; z < g->size[2]; ++z)
        for (int y = 0; y < g->size[1]; ++y)
            for (int x = 0; x < g->size[0]; ++x) {
                if (!g->surface[gb_voxel_index(g, x, y, z)])
                    continue;
                long d = (long)(x - i) * (x - i) + (long)(y - j) * (y - j) + (long)(z - k) * (z - k);
                if (best < 0 || d < best)
                    best = d;
            }
    return (float)(sqrt((double)best) * g->voxel_size);
}

/* volume_solid and its boxes (volume_boxes). */
static gb_voxel_grid volume_made(int nx, int ny, int nz, const int (*boxes)[7])
{
    gb_voxel_grid g = volume_solid(nx, ny, nz);
    volume_boxes(&g, boxes);
    return g;
}

/* ---- topology of the empty space, independently of thin ---- */

typedef struct volume_topology {
    long b0, b1, b2, euler;
} volume_topology;

/* Components of the cells where open[] is set, neighbours given by offsets. */
static long volume_components(const uint8_t *open, int nx, int ny, int nz, int connectivity)
{
    size_t n = (size_t)nx * ny * nz;
    uint8_t *seen = calloc(n, 1);
    size_t *stack = malloc(n * sizeof *stack);
    long components = 0;
    for (size_t start = 0; start < n; ++start) {
        if (!open[start] || seen[start])
            continue;
        ++components;
        size_t top = 0;
        stack[top++] = start;
        seen[start] = 1;
        while (top) {
            size_t v = stack[--top];
            int i = (int)(v % nx), j = (int)(v / nx % ny), k = (int)(v / nx / ny);
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int steps = abs(dx) + abs(dy) + abs(dz);
                        if (!steps || (connectivity == 6 && steps > 1))
                            continue;
                        int a = i + dx, b = j + dy, c = k + dz;
                        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz)
                            continue;
                        size_t w = (size_t)a + (size_t)nx * ((size_t)b + (size_t)ny * c);
                        if (open[w] && !seen[w]) {
                            seen[w] = 1;
                            stack[top++] = w;
                        }
                    }
        }
    }
    free(seen);
    free(stack);
    return components;
}

/* Faces of the closed cubes on the lattice of doubled coordinates: a cell
 * (a,b,c) of dimension "number of odd coordinates". */
static long volume_euler(const gb_voxel_grid *g)
{
    int kx = 2 * g->size[0] + 1, ky = 2 * g->size[1] + 1, kz = 2 * g->size[2] + 1;
    uint8_t *marked = calloc((size_t)kx * ky * kz, 1);
    for (int k = 0; k < g->size[2]; ++k)
        for (int j = 0; j < g->size[1]; ++j)
            for (int i = 0; i < g->size[0]; ++i) {
                if (!volume_empty(g, i, j, k))
                    continue;
                for (int c = 2 * k; c <= 2 * k + 2; ++c)
                    for (int b = 2 * j; b <= 2 * j + 2; ++b)
                        for (int a = 2 * i; a <= 2 * i + 2; ++a)
                            marked[(size_t)a + (size_t)kx * ((size_t)b + (size_t)ky * c)] = 1;
            }
    long euler = 0;
    for (int c = 0; c < kz; ++c)
        for (int b = 0; b < ky; ++b)
            for (int a = 0; a < kx; ++a)
                if (marked[(size_t)a + (size_t)kx * ((size_t)b + (size_t)ky * c)])
                    euler += ((a & 1) + (b & 1) + (c & 1)) % 2 ? -1 : 1;
    free(marked);
    return euler;
}

static volume_topology volume_topology_of(const gb_voxel_grid *g)
{
    volume_topology t;
    int nx = g->size[0], ny = g->size[1], nz = g->size[2];
    uint8_t *empty = malloc((size_t)nx * ny * nz);
    for (size_t v = 0; v < (size_t)nx * ny * nz; ++v)
        empty[v] = !g->surface[v];
    t.b0 = volume_components(empty, nx, ny, nz, 26);
    free(empty);
    /* the complement, with one layer of outside around the grid */
    int px = nx + 2, py = ny + 2, pz = nz + 2;
    uint8_t *complement = malloc((size_t)px * py * pz);
    for (int k = 0; k < pz; ++k)
        for (int j = 0; j < py; ++j)
            for (int i = 0; i < px; ++i)
                complement[(size_t)i + (size_t)px * ((size_t)j + (size_t)py * k)] =
                    !volume_empty(g, i - 1, j - 1, k - 1);
    t.b2 = volume_components(complement, px, py, pz, 6) - 1;
    free(complement);
    t.euler = volume_euler(g);
    t.b1 = t.b0 + t.b2 - t.euler;
    return t;
}

#endif
