/* cubical_complex.c — building the complex of the empty voxels and counting
 * the faces around a face. */
#include "cubical_complex.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "huge_pages.h"

/* The faces of a cell when the cubes around its point are those of mask:
 * bit dx + 2 dy + 4 dz set when the cube of cell (x-dx, y-dy, z-dz) exists.
 * A face exists when one of the cubes containing it exists. */
static uint8_t faces_of_cube_mask(unsigned mask)
{
    uint8_t faces = 0;
    for (unsigned d = 0; d < 8; ++d) {
        if (!(mask & (1u << d)))
            continue;
        unsigned dx = d & 1, dy = (d >> 1) & 1, dz = (d >> 2) & 1;
        faces |= GB_FACE_POINT;
        if (!dx) faces |= GB_FACE_EDGE_X;
        if (!dy) faces |= GB_FACE_EDGE_Y;
        if (!dz) faces |= GB_FACE_EDGE_Z;
        if (!dy && !dz) faces |= GB_FACE_SQUARE_YZ;
        if (!dx && !dz) faces |= GB_FACE_SQUARE_XZ;
        if (!dx && !dy) faces |= GB_FACE_SQUARE_XY;
        if (!d) faces |= GB_FACE_CUBE;
    }
    return faces;
}

static void mark_empty_voxels(gb_cubical_complex *complex, const gb_voxel_grid *grid)
{
    for (int32_t k = 0; k < grid->size[2]; ++k)
        for (int32_t j = 0; j < grid->size[1]; ++j) {
            const uint8_t *surface = grid->surface + gb_voxel_index(grid, 0, j, k);
            uint8_t *cell = complex->faces + gb_voxel_cell(complex, 0, j, k);
            for (int32_t i = 0; i < grid->size[0]; ++i)
                cell[i] = surface[i] ? 0 : GB_FACE_CUBE;
        }
}

/* Cells are visited in increasing index order and only look at cells of
 * lower or equal index, whose cube bit the table keeps. */
static void add_faces_of_cubes(gb_cubical_complex *complex)
{
    uint8_t table[256];
    for (unsigned mask = 0; mask < 256; ++mask)
        table[mask] = faces_of_cube_mask(mask);
    /* signed, so that p[-sx] steps back rather than wrapping around */
    const ptrdiff_t sx = (ptrdiff_t)complex->step[0], sy = (ptrdiff_t)complex->step[1],
                    sz = (ptrdiff_t)complex->step[2];
    for (int32_t z = 1; z < complex->size[2] - 1; ++z)
        for (int32_t y = 1; y < complex->size[1] - 1; ++y) {
            uint8_t *row = complex->faces + gb_cell_index(complex, 0, y, z);
            for (int32_t x = 1; x < complex->size[0] - 1; ++x) {
                uint8_t *p = row + x;
                unsigned mask = (unsigned)(p[0] >> 7) | (unsigned)(p[-sx] >> 7) << 1 |
                                (unsigned)(p[-sy] >> 7) << 2 |
                                (unsigned)(p[-sx - sy] >> 7) << 3 |
                                (unsigned)(p[-sz] >> 7) << 4 |
                                (unsigned)(p[-sx - sz] >> 7) << 5 |
                                (unsigned)(p[-sy - sz] >> 7) << 6 |
                                (unsigned)(p[-sx - sy - sz] >> 7) << 7;
                *p = table[mask];
            }
        }
}

gb_result gb_cubical_complex_build(gb_cubical_complex *complex, const gb_voxel_grid *grid,
                                   gb_error *error)
{
    memset(complex, 0, sizeof *complex);
    size_t count = 1;
    for (int axis = 0; axis < 3; ++axis) {
        if (grid->size[axis] <= 0 || grid->size[axis] > INT32_MAX - 3)
            return gb_fail(error, GB_ERROR_ARGUMENT, "cubical complex: bad grid size");
        complex->size[axis] = grid->size[axis] + 3;
        complex->step[axis] = count;
        if (count > SIZE_MAX / (size_t)complex->size[axis])
            return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "cubical complex: grid too large");
        count *= (size_t)complex->size[axis];
    }
    if (count > UINT32_MAX)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "cubical complex: %zu cells, more than 2^32", count);
    complex->cell_count = count;
    complex->faces = calloc(count, 1);
    gb_advise_huge_pages(complex->faces, count);
    if (!complex->faces)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                       "cubical complex: out of memory for %zu cells", count);
    mark_empty_voxels(complex, grid);
    add_faces_of_cubes(complex);
    return GB_OK;
}

void gb_cubical_complex_free(gb_cubical_complex *complex)
{
    if (!complex)
        return;
    free(complex->faces);
    memset(complex, 0, sizeof *complex);
}

void gb_cell_coordinates(const gb_cubical_complex *complex, size_t cell, int32_t xyz[3])
{
    xyz[0] = (int32_t)(cell % complex->step[1]);
    xyz[1] = (int32_t)(cell / complex->step[1] % (size_t)complex->size[1]);
    xyz[2] = (int32_t)(cell / complex->step[2]);
}

gb_face_counts gb_cubical_complex_count(const gb_cubical_complex *complex)
{
    gb_face_counts counts = {0, 0, 0, 0};
    for (size_t cell = 0; cell < complex->cell_count; ++cell) {
        uint8_t f = complex->faces[cell];
        if (!f)
            continue;
        counts.points += (f & GB_FACE_POINT) != 0;
        counts.edges += (uint64_t)gb_face_count(f & GB_FACE_EDGES);
        counts.squares += (uint64_t)gb_face_count(f & GB_FACE_SQUARES);
        counts.cubes += (f & GB_FACE_CUBE) != 0;
    }
    return counts;
}

int64_t gb_euler_characteristic(gb_face_counts counts)
{
    return (int64_t)counts.points - (int64_t)counts.edges + (int64_t)counts.squares -
           (int64_t)counts.cubes;
}
